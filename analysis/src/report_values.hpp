#pragma once
// What the analysis units share when they compute and report statistics: the value of a statistic that cannot be
// computed, a metric's values over episodes and a statistic's JSON form. Private to freeplay_analysis.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "freeplay/analysis/run_data.hpp"

namespace freeplay::analysis::detail {

/// The value of a statistic that cannot be computed (too few values, no pairing by seed).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The values of `metric` over `episodes`, in their order (episodes without it, or with NaN, are left out).
inline std::vector<double> values_of(const std::vector<EpisodeValues>& episodes, const std::string& metric) {
  std::vector<double> out;
  for (const auto& e : episodes) {
    const auto it = e.metrics.find(metric);
    if (it != e.metrics.end() && !std::isnan(it->second)) out.push_back(it->second);
  }
  return out;
}

/// `v` as JSON: the number, or null when it is not finite (JSON has no NaN or infinity).
inline nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace freeplay::analysis::detail
