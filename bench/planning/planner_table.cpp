// Side-by-side table of every planner on the benchmark cases: per-plan time (median, p90), path length,
// clearance and success rate, printed as Markdown.

#include <algorithm>
#include <cstdio>
#include <vector>

#include "cases.hpp"

namespace {

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
  return values[index];
}

}  // namespace

int main() {
  using namespace freeplay::planning;
  constexpr int kCases = 48;
  std::printf("| planner | items | median time (ms) | p90 time (ms) | success | median length (m) | "
              "median clearance (mm) |\n|---|---|---|---|---|---|---|\n");
  for (const auto& name : planner_names()) {
    const auto planner = make_planner(name);
    for (const int n_items : {0, 5, 10}) {
      auto cases = bench::make_cases(n_items, kCases, 2000 + static_cast<std::uint64_t>(n_items));
      freeplay::Rng rng(11);
      std::vector<double> times;
      std::vector<double> lengths;
      std::vector<double> clearances;
      int successes = 0;
      for (auto& request : cases) {
        bench::apply_budget(name, request);
        const PlanResult result = planner->plan(request, rng);
        times.push_back(result.metrics.planning_time_s * 1e3);
        if (!result.ok) continue;
        ++successes;
        lengths.push_back(result.metrics.path_length_m);
        if (n_items > 1) clearances.push_back(result.metrics.min_clearance_m * 1e3);
      }
      std::printf("| %s | %d | %.3f | %.3f | %d/%d | %.3f | %s |\n", name.c_str(), n_items, percentile(times, 0.5),
                  percentile(times, 0.9), successes, kCases, percentile(lengths, 0.5),
                  clearances.empty() ? "–" : std::to_string(percentile(clearances, 0.5)).substr(0, 5).c_str());
    }
  }
  return 0;
}
