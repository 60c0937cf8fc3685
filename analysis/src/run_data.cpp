#include "freeplay/analysis/run_data.hpp"

#include <fmt/format.h>
#include <fnmatch.h>

#include <algorithm>

#include "freeplay/core/error.hpp"
#include "freeplay/results/run_folder.hpp"
#include "freeplay/results/summary.hpp"

namespace freeplay::analysis {

std::vector<EpisodeValues> RunData::of_variant(const std::string& variant) const {
  std::vector<EpisodeValues> out;
  std::copy_if(episodes.begin(), episodes.end(), std::back_inserter(out),
               [&](const EpisodeValues& e) { return e.variant == variant; });
  return out;
}

bool RunData::has_variant(const std::string& variant) const {
  return std::find(variants.begin(), variants.end(), variant) != variants.end();
}

std::map<std::string, double> comparable_metrics(const nlohmann::json& record) {
  auto values = results::flatten_numbers(record.value("metrics", nlohmann::json::object()), "metrics");
  const auto duration = record.find("duration_s");
  if (duration != record.end() && duration->is_number()) values["duration_s"] = duration->get<double>();
  return values;
}

namespace {

void collect_texts(const nlohmann::json& value, const std::string& prefix, std::map<std::string, std::string>& out) {
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) collect_texts(child, prefix + "." + key, out);
  } else if (value.is_string()) {
    out[prefix] = value.get<std::string>();
  }
}

}  // namespace

std::map<std::string, std::string> comparable_texts(const nlohmann::json& record) {
  std::map<std::string, std::string> out;
  collect_texts(record.value("metrics", nlohmann::json::object()), "metrics", out);
  return out;
}

RunData run_from_records(const std::vector<nlohmann::json>& records, const std::string& dir) {
  RunData run;
  run.dir = dir;
  for (const auto& record : records) {
    EpisodeValues e;
    e.variant = record.value("variant", "");
    e.episode = record.value("episode", -1);
    const auto seed = record.find("seed");
    if (seed != record.end() && seed->is_number_unsigned()) e.seed = seed->get<std::uint64_t>();
    e.metrics = comparable_metrics(record);
    e.texts = comparable_texts(record);
    if (!run.has_variant(e.variant)) run.variants.push_back(e.variant);
    if (run.episodes.empty()) run.program_version = record.value("program_version", std::string{});
    run.episodes.push_back(std::move(e));
  }
  return run;
}

RunData load_run(const std::filesystem::path& dir) {
  if (!std::filesystem::is_regular_file(dir / "episodes.jsonl")) {
    throw InputError(fmt::format("'{}' is not a run folder (it has no episodes.jsonl)", dir.string()), "RUN",
                     "a folder written by `freeplay run` or `freeplay suite`");
  }
  const results::RunFolder folder(dir);
  auto run = run_from_records(folder.records(), dir.string());
  if (run.episodes.empty()) {
    throw InputError(fmt::format("the run folder '{}' holds no finished episode", dir.string()), "RUN",
                     "a run with at least one finished episode");
  }
  return run;
}

bool metric_matches(const std::string& metric, const std::vector<std::string>& patterns) {
  if (patterns.empty()) return true;
  return std::any_of(patterns.begin(), patterns.end(),
                     [&](const std::string& p) { return ::fnmatch(p.c_str(), metric.c_str(), 0) == 0; });
}

}  // namespace freeplay::analysis
