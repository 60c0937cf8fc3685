#include "freeplay/runner/suite_runner.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <mutex>
#include <thread>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/rng.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/progress.hpp"
#include "freeplay/results/run_folder.hpp"
#include "freeplay/results/summary.hpp"

namespace freeplay::runner {

std::uint64_t episode_seed(std::uint64_t scenario_seed, int index) {
  return SeedSequence(scenario_seed).seed_for(fmt::format("episode/{}", index));
}

EventsOutput events_output_from_name(std::string_view name) {
  if (name == "auto") return EventsOutput::Auto;
  if (name == "all") return EventsOutput::All;
  if (name == "gz") return EventsOutput::Gz;
  if (name == "none") return EventsOutput::None;
  throw InputError(fmt::format("unknown event-log output '{}'", name), "--events", "auto, all, gz, none");
}

bool in_shard(const std::string& variant_id, int index, int shard_index, int shard_count) {
  if (shard_count <= 1) return true;
  // Round-robin on the episode index, offset per variant: balanced within ±1 per variant and deterministic.
  const auto offset = fnv1a64(variant_id) % static_cast<std::uint64_t>(shard_count);
  return (static_cast<std::uint64_t>(index) + offset) % static_cast<std::uint64_t>(shard_count) ==
         static_cast<std::uint64_t>(shard_index);
}

void check_policies(const scenario::Suite& suite) {
  for (const auto& variant : suite.variants) {
    const auto& scenario = variant.scenario;
    if (scenario.kind == scenario::ScenarioKind::controller || scenario.condition != scenario::Condition::ChildRobot) continue;
    policies::make_policy(scenario.robot.policy, scenario.robot.params)->check_run(scenario.episodes);
  }
}

results::ExpectedRun expected_run(const scenario::Suite& suite, const std::string& title) {
  results::ExpectedRun expected;
  expected.title = title.empty() ? suite.name : title;
  for (const auto& v : suite.variants) expected.variants.push_back({v.id, v.scenario.episodes, v.scenario.config_hash});
  return expected;
}

RunReport run_suite(const scenario::Suite& suite, const RunOptions& options, const EpisodeFunction& run_episode,
                    std::atomic<bool>& stop) {
  if (options.shard_count < 1 || options.shard_index < 0 || options.shard_index >= options.shard_count) {
    throw InputError(fmt::format("shard {}/{} does not exist", options.shard_index + 1, options.shard_count),
                     "--shard", "I/N with 1 ≤ I ≤ N");
  }
  results::RunFolder folder(options.out);
  if (folder.dropped_partial_line()) {
    spdlog::warn("{}: dropped an incomplete last line of episodes.jsonl (an interrupted write); that episode "
                 "runs again", folder.dir().string());
  }
  check_policies(suite);
  RunReport report;
  report.dir = folder.dir();
  std::vector<EpisodeTask> tasks;
  for (const auto& variant : suite.variants) {
    for (int i = 0; i < variant.scenario.episodes; ++i) {
      if (!in_shard(variant.id, i, options.shard_index, options.shard_count)) continue;
      ++report.total;
      if (folder.finished(variant.id, i, variant.scenario.config_hash)) {
        ++report.skipped;
        continue;
      }
      tasks.push_back({&variant, i, episode_seed(variant.scenario.seed, i)});
    }
  }
  auto events = options.events;
  if (events == EventsOutput::Auto) {
    events = report.total > kAutoEventsMaxEpisodes ? EventsOutput::None : EventsOutput::All;
    if (events == EventsOutput::None) {
      spdlog::info("{} episodes in this run: no event logs (per-episode output stays small); pass --events all "
                   "or --events gz to keep them", report.total);
    }
  }
  for (auto& task : tasks) task.events = events != EventsOutput::None;
  if (report.skipped > 0) {
    spdlog::info("resuming {}: {} of {} episodes already finished", folder.dir().string(), report.skipped,
                 report.total);
  }

  ProgressReporter progress(static_cast<int>(tasks.size()), options.progress);
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr first_error;
  auto worker = [&] {
    while (!stop.load()) {
      const std::size_t k = next.fetch_add(1);
      if (k >= tasks.size()) return;
      const auto& task = tasks[k];
      try {
        auto output = run_episode(task, stop);
        if (stop.load() && output.record.is_null()) return;  // aborted mid-episode: not recorded
        const auto file_id = results::RunFolder::episode_file_id(task.variant->id, task.index);
        for (const auto& [relative, contents] : output.files) {
          const bool event_log = relative.starts_with("events/");
          if (event_log && events == EventsOutput::None) continue;
          if (event_log && events == EventsOutput::Gz) {
            folder.write(relative + ".gz", results::gzip_compress(contents));
          } else {
            folder.write(relative, contents);
          }
        }
        auto& r = output.record;
        r["variant"] = task.variant->id;
        r["scenario"] = task.variant->scenario.name;
        r["scenario_file"] = task.variant->scenario.file;
        r["condition"] = std::string(to_string(task.variant->scenario.condition));
        if (task.variant->scenario.condition == scenario::Condition::ChildRobot) r["policy"] = task.variant->scenario.robot.policy;
        r["episode"] = task.index;
        r["episode_id"] = file_id;
        r["seed"] = task.seed;
        r["config_hash"] = task.variant->scenario.config_hash;
        r["program_version"] = program_version();
        folder.append(r);
        progress.episode_done(output.simulated_s);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        stop.store(true);
        return;
      }
    }
  };
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(std::max<std::size_t>(tasks.size(), 1))));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  progress.finish();

  std::vector<std::string> order;
  for (const auto& v : suite.variants) order.push_back(v.id);
  folder.finalize(order);
  report.finished = static_cast<int>(folder.record_count()) - report.skipped;
  report.interrupted = stop.load() && report.skipped + report.finished < report.total;
  results::write_summaries(folder.dir(), order, options.title.empty() ? suite.name : options.title, options.jobs);
  if (first_error) std::rethrow_exception(first_error);
  return report;
}

}  // namespace freeplay::runner
