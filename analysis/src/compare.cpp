#include "freeplay/analysis/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "freeplay/core/error.hpp"
#include "freeplay/core/rng.hpp"
#include "report_values.hpp"

namespace freeplay::analysis {

namespace {

using detail::kNaN;
using detail::json_number;

using detail::values_of;

/// Seed → value of one metric; empty when a seed repeats (pairing by seed is then impossible).
std::map<std::uint64_t, double> values_by_seed(const std::vector<EpisodeValues>& episodes, const std::string& metric) {
  std::map<std::uint64_t, double> out;
  for (const auto& e : episodes) {
    const auto it = e.metrics.find(metric);
    if (it == e.metrics.end() || std::isnan(it->second)) continue;
    if (!out.emplace(e.seed, it->second).second) return {};
  }
  return out;
}

SideSummary summarize_side(const std::vector<double>& values, const CompareOptions& options, std::uint64_t seed) {
  SideSummary s;
  s.n = static_cast<int>(values.size());
  s.mean = mean(values);
  s.sd = sample_sd(values);
  s.ci = bootstrap_mean_ci(values, options.confidence, options.resamples, seed);
  return s;
}

std::optional<PairedComparison> paired_comparison(const std::vector<EpisodeValues>& a,
                                                  const std::vector<EpisodeValues>& b, const std::string& metric,
                                                  const CompareOptions& options, std::uint64_t seed) {
  if (!options.allow_paired) return std::nullopt;
  const auto by_seed_a = values_by_seed(a, metric);
  const auto by_seed_b = values_by_seed(b, metric);
  if (by_seed_a.empty() || by_seed_a.size() != by_seed_b.size()) return std::nullopt;
  std::vector<double> differences;
  for (const auto& [s, value_a] : by_seed_a) {
    const auto it = by_seed_b.find(s);
    if (it == by_seed_b.end()) return std::nullopt;
    differences.push_back(it->second - value_a);
  }
  PairedComparison p;
  p.pairs = static_cast<int>(differences.size());
  p.mean_difference = mean(differences);
  p.ci = bootstrap_mean_ci(differences, options.confidence, options.resamples, seed);
  p.wilcoxon = wilcoxon_signed_rank(differences);
  return p;
}

std::set<std::string> selected_metrics(const std::vector<EpisodeValues>& episodes,
                                       const std::vector<std::string>& patterns) {
  std::set<std::string> out;
  for (const auto& e : episodes) {
    for (const auto& [name, value] : e.metrics) {
      if (metric_matches(name, patterns)) out.insert(name);
    }
  }
  return out;
}

std::string number(double v) { return std::isnan(v) ? "–" : fmt::format("{:.4g}", v); }
std::string interval(const Interval& i) { return fmt::format("[{}, {}]", number(i.low), number(i.high)); }
std::string p_text(double p) { return std::isnan(p) ? "–" : (p < 0.001 ? "<0.001" : fmt::format("{:.3f}", p)); }

nlohmann::json interval_json(const Interval& i) { return {json_number(i.low), json_number(i.high)}; }
nlohmann::json rank_json(const RankTest& t) {
  return {{"statistic", json_number(t.statistic)}, {"z", json_number(t.z)}, {"p", json_number(t.p_value)},
          {"exact", t.exact}, {"n", t.n}};
}

/// Display width of UTF-8 text (counts code points; every character used here is one column wide).
std::size_t display_width(const std::string& text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

}  // namespace

bool Comparison::paired() const {
  return !metrics.empty() &&
         std::all_of(metrics.begin(), metrics.end(), [](const MetricComparison& m) { return m.paired.has_value(); });
}

Comparison compare_samples(const Sample& a, const Sample& b, const CompareOptions& options) {
  if (!(options.confidence > 0.0 && options.confidence < 1.0)) {
    throw InputError(fmt::format("confidence {} is not a level", options.confidence), "--confidence",
                     "a number in (0, 1), e.g. 0.95");
  }
  if (options.resamples < 100) {
    throw InputError(fmt::format("{} resamples are too few", options.resamples), "--resamples", "at least 100");
  }
  const auto in_a = selected_metrics(a.episodes, options.metrics);
  const auto in_b = selected_metrics(b.episodes, options.metrics);
  for (const auto& pattern : options.metrics) {
    const auto matches = [&](const std::string& m) { return metric_matches(m, {pattern}); };
    if (std::none_of(in_a.begin(), in_a.end(), matches) && std::none_of(in_b.begin(), in_b.end(), matches)) {
      std::set<std::string> all = selected_metrics(a.episodes, {});
      const auto more = selected_metrics(b.episodes, {});
      all.insert(more.begin(), more.end());
      throw InputError(fmt::format("'{}' matches no metric of either run", pattern), "--metric",
                       fmt::format("{}", fmt::join(all, ", ")));
    }
  }
  Comparison c;
  c.label_a = a.label;
  c.label_b = b.label;
  c.options = options;
  for (const auto& metric : in_a) {
    if (!in_b.count(metric)) {
      c.only_in_a.push_back(metric);
      continue;
    }
    const auto va = values_of(a.episodes, metric);
    const auto vb = values_of(b.episodes, metric);
    const std::uint64_t base = fnv1a64(metric) ^ options.seed;  // independent of which other metrics are compared
    MetricComparison m;
    m.metric = metric;
    m.a = summarize_side(va, options, splitmix64(base + 1));
    m.b = summarize_side(vb, options, splitmix64(base + 2));
    m.difference = m.b.mean - m.a.mean;
    m.difference_ci = bootstrap_difference_ci(va, vb, options.confidence, options.resamples, splitmix64(base + 3));
    m.cohens_d = cohens_d(va, vb);
    m.cliffs_delta = cliffs_delta(va, vb);
    m.mann_whitney = mann_whitney_u(va, vb);
    m.paired = paired_comparison(a.episodes, b.episodes, metric, options, splitmix64(base + 4));
    c.metrics.push_back(std::move(m));
  }
  for (const auto& metric : in_b) {
    if (!in_a.count(metric)) c.only_in_b.push_back(metric);
  }
  std::vector<double> p_unpaired;
  std::vector<double> p_paired;
  for (const auto& m : c.metrics) {
    p_unpaired.push_back(m.mann_whitney.p_value);
    p_paired.push_back(m.paired ? m.paired->wilcoxon.p_value : kNaN);
  }
  const auto holm_unpaired = holm_adjust(p_unpaired);
  const auto holm_paired = holm_adjust(p_paired);
  for (std::size_t i = 0; i < c.metrics.size(); ++i) {
    auto& m = c.metrics[i];
    m.p_holm = holm_unpaired[i];
    if (m.paired) m.paired->p_holm = holm_paired[i];
    const double decisive = m.paired ? m.paired->p_holm : m.p_holm;
    m.significant = !std::isnan(decisive) && decisive < options.alpha;
  }
  return c;
}

std::string comparison_table(const Comparison& c) {
  const bool any_paired =
      std::any_of(c.metrics.begin(), c.metrics.end(), [](const MetricComparison& m) { return m.paired.has_value(); });
  const int level = static_cast<int>(std::lround(c.options.confidence * 100.0));
  std::vector<std::string> header = {"metric", "n A/B", fmt::format("mean A [{}% CI]", level),
                                     fmt::format("mean B [{}% CI]", level), fmt::format("B−A [{}% CI]", level),
                                     "d", "δ", "p MW", "p Holm"};
  if (any_paired) {
    header.insert(header.end(), {"pairs", fmt::format("paired B−A [{}% CI]", level), "p W", "p Holm W"});
  }
  header.push_back("");
  std::vector<std::vector<std::string>> rows{header};
  for (const auto& m : c.metrics) {
    std::vector<std::string> row = {m.metric,
                                    fmt::format("{}/{}", m.a.n, m.b.n),
                                    fmt::format("{} {}", number(m.a.mean), interval(m.a.ci)),
                                    fmt::format("{} {}", number(m.b.mean), interval(m.b.ci)),
                                    fmt::format("{} {}", number(m.difference), interval(m.difference_ci)),
                                    number(m.cohens_d),
                                    number(m.cliffs_delta),
                                    p_text(m.mann_whitney.p_value),
                                    p_text(m.p_holm)};
    if (any_paired) {
      if (m.paired) {
        row.insert(row.end(), {std::to_string(m.paired->pairs),
                               fmt::format("{} {}", number(m.paired->mean_difference), interval(m.paired->ci)),
                               p_text(m.paired->wilcoxon.p_value), p_text(m.paired->p_holm)});
      } else {
        row.insert(row.end(), {"–", "–", "–", "–"});
      }
    }
    row.push_back(m.significant ? "*" : "");
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> widths(header.size(), 0);
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < row.size(); ++k) widths[k] = std::max(widths[k], display_width(row[k]));
  }
  std::string out = fmt::format("A: {}\nB: {}\n", c.label_a, c.label_b);
  out += any_paired ? (c.paired() ? "paired by seed (common random numbers): every metric\n"
                                  : "paired by seed (common random numbers): where the columns say so\n")
                    : "independent samples (the runs do not share seeds)\n";
  out += "\n";
  for (const auto& row : rows) {
    std::string line;
    for (std::size_t k = 0; k < row.size(); ++k) {
      const auto pad = std::string(widths[k] - display_width(row[k]), ' ');
      line += k == 0 ? row[k] + pad : "  " + pad + row[k];  // metric left-aligned, numbers right-aligned
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  if (c.metrics.empty()) out += "(no metric in common)\n";
  out += fmt::format(
      "\nd: Cohen's d (pooled SD); δ: Cliff's delta; p MW: Mann–Whitney U (two-sided); p W: Wilcoxon signed-rank on "
      "pairs; Holm: adjusted across the {} metrics; *: adjusted p < {} ({}).\n",
      c.metrics.size(), c.options.alpha, any_paired ? "the paired test where paired" : "Mann–Whitney");
  if (!c.only_in_a.empty()) out += fmt::format("only in A (not compared): {}\n", fmt::join(c.only_in_a, ", "));
  if (!c.only_in_b.empty()) out += fmt::format("only in B (not compared): {}\n", fmt::join(c.only_in_b, ", "));
  return out;
}

nlohmann::json comparison_json(const Comparison& c) {
  nlohmann::json metrics = nlohmann::json::array();
  for (const auto& m : c.metrics) {
    auto side = [](const SideSummary& s) {
      return nlohmann::json{
          {"n", s.n}, {"mean", json_number(s.mean)}, {"sd", json_number(s.sd)}, {"ci", interval_json(s.ci)}};
    };
    nlohmann::json row = {{"metric", m.metric},
                          {"a", side(m.a)},
                          {"b", side(m.b)},
                          {"difference", json_number(m.difference)},
                          {"difference_ci", interval_json(m.difference_ci)},
                          {"cohens_d", json_number(m.cohens_d)},
                          {"cliffs_delta", json_number(m.cliffs_delta)},
                          {"mann_whitney", rank_json(m.mann_whitney)},
                          {"p_holm", json_number(m.p_holm)},
                          {"significant", m.significant}};
    if (m.paired) {
      row["paired"] = {{"pairs", m.paired->pairs},
                       {"mean_difference", json_number(m.paired->mean_difference)},
                       {"ci", interval_json(m.paired->ci)},
                       {"wilcoxon", rank_json(m.paired->wilcoxon)},
                       {"p_holm", json_number(m.paired->p_holm)}};
    } else {
      row["paired"] = nullptr;
    }
    metrics.push_back(std::move(row));
  }
  return {{"a", c.label_a},
          {"b", c.label_b},
          {"difference", "b - a"},
          {"confidence", c.options.confidence},
          {"alpha", c.options.alpha},
          {"resamples", c.options.resamples},
          {"seed", c.options.seed},
          {"paired", c.paired()},
          {"metrics", std::move(metrics)},
          {"only_in_a", c.only_in_a},
          {"only_in_b", c.only_in_b}};
}

}  // namespace freeplay::analysis
