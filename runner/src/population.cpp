#include "freeplay/runner/population.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "freeplay/runner/suite_runner.hpp"

namespace freeplay::runner {

agents::SessionResult session_result(const EpisodeResult& episode) {
  agents::SessionResult s;
  s.duration_s = episode.duration_s;
  s.hit_cap = episode.hit_cap;
  if (!episode.children.empty()) s.purple = episode.children[0];
  if (episode.children.size() > 1) s.yellow = episode.children[1];
  return s;
}

std::vector<agents::SessionResult> run_population(const scenario::Scenario& scenario, int episodes, int threads,
                                                  const SharedModels& models,
                                                  const std::function<void(int done)>& progress) {
  std::vector<agents::SessionResult> out(static_cast<std::size_t>(std::max(0, episodes)));
  std::atomic<int> next{0};
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  const std::atomic<bool> never_stop{false};
  const auto worker = [&] {
    for (int i = next++; i < episodes; i = next++) {
      const EpisodeResult r = run_episode(
          {.scenario = scenario, .seed = episode_seed(scenario.seed, i), .models = models, .stop = never_stop});
      out[static_cast<std::size_t>(i)] = session_result(r);
      const int finished = ++done;
      if (progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        progress(finished);
      }
    }
  };
  const int workers = std::clamp(threads, 1, std::max(1, episodes));
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return out;
}

}  // namespace freeplay::runner
