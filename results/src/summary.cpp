#include "freeplay/results/summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <future>

#include "freeplay/agents/condition.hpp"
#include "freeplay/core/task_pool.hpp"

namespace freeplay::results {

using agents::Condition;

const PinsoroDurations* pinsoro_durations(const std::string& condition) {
  static const PinsoroDurations child_child{45, 24.15, 11.25, 22.4, 0.89, 0.56, 0.38};
  static const PinsoroDurations child_robot{30, 19.18, 10.0, 17.4, 0.73, 0.37, 0.13};
  Condition parsed = Condition::Controller;
  if (!from_string(condition, parsed)) return nullptr;
  if (parsed == Condition::ChildChild) return &child_child;
  if (parsed == Condition::ChildRobot) return &child_robot;
  return nullptr;
}

std::map<std::string, double> flatten_numbers(const nlohmann::json& value, const std::string& prefix,
                                              NullLeaves nulls) {
  std::map<std::string, double> out;
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) {
      auto nested = flatten_numbers(child, prefix.empty() ? key : prefix + "." + key, nulls);
      out.insert(nested.begin(), nested.end());
    }
  } else if (value.is_number()) {
    out[prefix] = value.get<double>();
  } else if (value.is_boolean()) {
    out[prefix] = value.get<bool>() ? 1.0 : 0.0;
  } else if (value.is_null() && nulls == NullLeaves::as_nan && !prefix.empty()) {
    out[prefix] = std::nan("");
  }
  return out;
}

namespace {
constexpr std::array<double, 3> kStillPlayingMin = {10.0, 20.0, 30.0};
}  // namespace

void MetricSample::add(double value) {
  if (std::isnan(value)) return;
  ++n_;
  const double delta = value - mean_;
  mean_ += delta / static_cast<double>(n_);
  m2_ += delta * (value - mean_);
  if (kept_.size() < kBootstrapMaxValues) {
    kept_.push_back(value);
    return;
  }
  // Algorithm R: the n-th value replaces a random kept one with probability kept/n.
  rng_ += 0x9e3779b97f4a7c15ULL;
  std::uint64_t z = rng_;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  const auto slot = z % n_;
  if (slot < kept_.size()) kept_[slot] = value;
}

Summary MetricSample::summary(std::uint64_t seed, double divisor) const {
  std::vector<double> scaled = kept_;
  if (divisor != 1.0) {
    for (auto& v : scaled) v /= divisor;
  }
  if (n_ <= kBootstrapMaxValues) return summarize(scaled, seed);
  Summary s;
  s.n = static_cast<int>(n_);
  s.mean = mean_ / divisor;
  s.sd = std::sqrt(m2_ / static_cast<double>(n_ - 1)) / divisor;
  s.median = median(scaled);
  const double half = 1.959963984540054 * s.sd / std::sqrt(static_cast<double>(n_));
  s.ci95 = {s.mean - half, s.mean + half};
  return s;
}

RunSummarizer::RunSummarizer(const std::vector<std::string>& variant_order) {
  for (const auto& variant : variant_order) {
    if (index_.contains(variant)) continue;
    index_.emplace(variant, variants_.size());
    variants_.emplace_back().summary.variant = variant;
  }
}

void RunSummarizer::add(const nlohmann::json& r) {
  const auto it = index_.find(r.value("variant", ""));
  if (it == index_.end()) return;
  auto& v = variants_[it->second];
  ++v.summary.episodes;
  v.summary.condition = r.value("condition", "");
  v.summary.policy = r.value("policy", "");
  const double duration = r.value("duration_s", std::nan(""));
  v.values["duration_s"].add(duration);
  for (std::size_t i = 0; i < kStillPlayingMin.size(); ++i) {
    if (duration / 60.0 >= kStillPlayingMin[i]) ++v.still_playing[i];
  }
  for (const auto& [key, value] : flatten_numbers(r.value("metrics", nlohmann::json::object()), "metrics")) {
    v.values[key].add(value);
  }
}

std::vector<VariantSummary> RunSummarizer::finish(int threads) const {
  TaskPool pool(threads > 1 ? threads : 0);
  struct Pending {
    std::vector<std::future<Summary>> metrics;
    std::future<Summary> duration;
  };
  std::vector<VariantSummary> out;
  std::vector<Pending> pending;
  for (const auto& [summary, values, still_playing] : variants_) {
    if (summary.episodes == 0) continue;
    auto& s = out.emplace_back(summary);
    auto& p = pending.emplace_back();
    std::uint64_t seed = 1;
    for (const auto& [metric, v] : values) {
      s.metrics.push_back({metric, {}});
      p.metrics.push_back(pool.submit([&v = v, seed] { return v.summary(seed); }));
      ++seed;
    }
    p.duration = pool.submit([&values = values] { return values.at("duration_s").summary(7, 60.0); });
    for (std::size_t i = 0; i < still_playing.size(); ++i) {
      s.still_playing[i] = static_cast<double>(still_playing[i]) / static_cast<double>(summary.episodes);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    for (std::size_t k = 0; k < out[i].metrics.size(); ++k) out[i].metrics[k].stats = pending[i].metrics[k].get();
    out[i].duration_min = pending[i].duration.get();
  }
  return out;
}

std::vector<VariantSummary> summarize_run(const std::vector<nlohmann::json>& records,
                                          const std::vector<std::string>& variant_order) {
  RunSummarizer summarizer(variant_order);
  for (const auto& r : records) summarizer.add(r);
  return summarizer.finish();
}

std::string summary_csv(const std::vector<VariantSummary>& summaries) {
  std::string out = "variant,condition,policy,metric,n,mean,sd,median,ci_low,ci_high\n";
  for (const auto& s : summaries) {
    for (const auto& m : s.metrics) {
      out += fmt::format("\"{}\",{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", s.variant, s.condition, s.policy,
                         m.metric, m.stats.n, m.stats.mean, m.stats.sd, m.stats.median, m.stats.ci95.low,
                         m.stats.ci95.high);
    }
  }
  return out;
}

namespace {

const MetricSummary* find_metric(const VariantSummary& s, const std::string& name) {
  for (const auto& m : s.metrics) {
    if (m.metric == name) return &m;
  }
  return nullptr;
}

std::string cell(const MetricSummary* m, double scale = 1.0, int digits = 2) {
  if (m == nullptr || m->stats.n == 0) return "–";
  return fmt::format("{:.{}f} [{:.{}f}, {:.{}f}]", m->stats.mean * scale, digits, m->stats.ci95.low * scale, digits,
                     m->stats.ci95.high * scale, digits);
}

}  // namespace

std::string summary_markdown(const std::vector<VariantSummary>& summaries, const std::string& title) {
  std::string out = fmt::format("# {}\n\n## Free-play duration (minutes)\n\n", title);
  out += "| variant | condition | policy | n | mean [95% CI] | SD | median | ≥10 min | ≥20 min | ≥30 min |"
         " PInSoRo mean (SD) | PInSoRo ≥10/20/30 |\n";
  out += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : summaries) {
    const auto& stats = s.duration_min;
    const auto* ref = pinsoro_durations(s.condition);
    const bool asocial_reference =
        ref != nullptr && (s.condition == to_string(Condition::ChildChild) || s.policy == "asocial");
    out += fmt::format("| {} | {} | {} | {} | {:.2f} [{:.2f}, {:.2f}] | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {} | {} |\n",
                       s.variant, s.condition, s.policy.empty() ? "–" : s.policy, stats.n, stats.mean,
                       stats.ci95.low, stats.ci95.high, stats.sd, stats.median, s.still_playing[0], s.still_playing[1],
                       s.still_playing[2],
                       asocial_reference ? fmt::format("{:.2f} ({:.2f})", ref->mean_min, ref->sd_min) : "–",
                       asocial_reference ? fmt::format("{:.2f}/{:.2f}/{:.2f}", ref->survival_10, ref->survival_20,
                                                       ref->survival_30)
                                         : "–");
  }
  const std::vector<std::pair<std::string, std::string>> headline = {
      {"metrics.label_share.purple.cooperative", "purple cooperative share"},
      {"metrics.label_share.purple.goaloriented", "purple goal-oriented share"},
      {"metrics.label_share.purple.noplay", "purple no-play share"},
      {"metrics.child_touches_per_min", "child touches / min"},
      {"metrics.child_item_moves_per_min", "child item moves / min"},
      {"metrics.robot_item_moves_per_min", "robot item moves / min"},
      {"metrics.robot_actions_per_min", "robot actions / min"},
      {"metrics.items_taken_by_robot_from_child", "items robot took from a child"},
      {"metrics.items_taken_by_child_from_robot", "items a child took from the robot"},
      {"metrics.mutual_gaze_s", "mutual gaze (s)"},
      {"metrics.robot_response_latency_s", "robot response latency (s)"},
  };
  out += "\n## Main metrics (mean [95% bootstrap CI])\n\n| metric |";
  for (const auto& s : summaries) out += fmt::format(" {} |", s.variant);
  out += "\n|---|";
  for (std::size_t i = 0; i < summaries.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& [key, label] : headline) {
    bool any = false;
    for (const auto& s : summaries) any = any || find_metric(s, key) != nullptr;
    if (!any) continue;
    out += fmt::format("| {} |", label);
    for (const auto& s : summaries) out += fmt::format(" {} |", cell(find_metric(s, key)));
    out += "\n";
  }
  out += "\nEvery metric, with SD and median: `summary.csv`. Per-episode values: `episodes.jsonl`.\n";
  return out;
}

}  // namespace freeplay::results
