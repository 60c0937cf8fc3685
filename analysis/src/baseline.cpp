#include "freeplay/analysis/baseline.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "freeplay/core/rng.hpp"
#include "report_values.hpp"

namespace freeplay::analysis {

namespace {

using detail::kNaN;
constexpr const char* kHigherIsBetter = "higher_is_better";
constexpr const char* kLowerIsBetter = "lower_is_better";

std::shared_ptr<const Schema> gate_schema() {
  const auto width = Schema::number(0.0, 1e15);
  const auto not_worse = Schema::map({
      required("direction", Schema::enumeration({kHigherIsBetter, kLowerIsBetter}), "which way is better"),
      with_default("ci", Schema::number(0.5, 0.9999), "0.95", "level of the run's CI of the mean"),
  });
  return Schema::map({
      optional("expected", Schema::number(-1e15, 1e15), "expected mean (required unless 'equals')"),
      optional("equals", Schema::string(), "expected text of a text metric (e.g. metrics.trace_hash); no band"),
      optional("abs", width, "allowed |mean − expected|"),
      optional("rel", width, "allowed |mean − expected| / |expected|"),
      optional("not_worse_than", not_worse, "fail only when the CI lies wholly on the worse side"),
      optional("note", Schema::string(), "free text for people"),
  });
}

std::string quoted(const std::string& text) { return nlohmann::json(text).dump(); }
std::string number_text(double v) { return fmt::format("{}", v); }
std::string short_number(double v) { return std::isnan(v) ? "–" : fmt::format("{:.4g}", v); }

std::vector<double> metric_values(const std::vector<EpisodeValues>& episodes, const std::string& metric) {
  std::vector<double> out;
  for (const auto& e : episodes) {
    const auto it = e.metrics.find(metric);
    if (it != e.metrics.end() && !std::isnan(it->second)) out.push_back(it->second);
  }
  return out;
}

GateResult evaluate(const Gate& gate, const std::vector<double>& values, int resamples, std::uint64_t seed) {
  GateResult r;
  r.gate = gate;
  r.n = static_cast<int>(values.size());
  r.mean = mean(values);
  r.ci = {kNaN, kNaN};
  const double deviation = r.mean - gate.expected;
  const double slack = 1e-12 * std::max(1.0, std::fabs(gate.expected));  // round-trip noise of printed numbers
  switch (gate.kind) {
    case BandKind::Absolute:
    case BandKind::Relative: {
      const double allowed = gate.kind == BandKind::Absolute ? gate.width : gate.width * std::fabs(gate.expected);
      r.passed = std::fabs(deviation) <= allowed + slack;
      r.miss = r.passed ? 0.0 : std::fabs(deviation) - allowed;
      const std::string relative =
          gate.expected != 0.0 ? fmt::format(" ({:+.1f} %)", 100.0 * deviation / std::fabs(gate.expected)) : "";
      r.verdict = fmt::format("mean {} (n {}), expected {} {}: off by {}{}", short_number(r.mean), r.n,
                              short_number(gate.expected), gate.band_text(), short_number(deviation), relative);
      if (!r.passed) r.verdict += fmt::format(", {} beyond the band", short_number(r.miss));
      break;
    }
    case BandKind::NotWorseThan: {
      r.ci = bootstrap_mean_ci(values, gate.confidence, resamples, seed);
      const bool higher = gate.direction == Direction::HigherIsBetter;
      r.passed = higher ? !(r.ci.high < gate.expected - slack) : !(r.ci.low > gate.expected + slack);
      r.miss = r.passed ? 0.0 : (higher ? gate.expected - r.ci.high : r.ci.low - gate.expected);
      r.verdict = fmt::format("mean {} (n {}), {} % CI [{}, {}], expected {} {}", short_number(r.mean), r.n,
                              std::lround(gate.confidence * 100.0), short_number(r.ci.low), short_number(r.ci.high),
                              short_number(gate.expected), gate.band_text());
      if (!r.passed) {
        r.verdict += fmt::format(": the whole CI is {}, {} short", higher ? "lower" : "higher", short_number(r.miss));
      }
      break;
    }
    case BandKind::Equals: break;  // text gates: evaluate_text
  }
  return r;
}

GateResult evaluate_text(const Gate& gate, const std::vector<std::string>& values) {
  GateResult r;
  r.gate = gate;
  r.n = static_cast<int>(values.size());
  r.mean = kNaN;
  r.ci = {kNaN, kNaN};
  const auto differing = std::find_if(values.begin(), values.end(), [&](const std::string& v) { return v != gate.expected_text; });
  r.passed = differing == values.end();
  r.miss = static_cast<double>(std::count_if(values.begin(), values.end(),
                                             [&](const std::string& v) { return v != gate.expected_text; }));
  r.text = r.passed ? gate.expected_text : *differing;
  r.verdict = r.passed ? fmt::format("{} (n {}) equals the expected value", gate.expected_text, r.n)
                       : fmt::format("{} of {} episodes differ: {} instead of {}", static_cast<int>(r.miss), r.n,
                                     r.text, gate.expected_text);
  return r;
}

std::vector<std::string> text_values(const std::vector<EpisodeValues>& episodes, const std::string& metric) {
  std::vector<std::string> out;
  for (const auto& e : episodes) {
    const auto it = e.texts.find(metric);
    if (it != e.texts.end()) out.push_back(it->second);
  }
  return out;
}

}  // namespace

std::string Gate::band_text() const {
  switch (kind) {
    case BandKind::Absolute: return fmt::format("±{}", short_number(width));
    case BandKind::Relative: return fmt::format("±{} %", short_number(width * 100.0));
    case BandKind::NotWorseThan:
      return fmt::format("not {} ({} % CI)", direction == Direction::HigherIsBetter ? "lower" : "higher",
                         std::lround(confidence * 100.0));
    case BandKind::Equals: return "equal";
  }
  return "?";
}

std::shared_ptr<const Schema> baseline_schema() {
  static const auto schema = Schema::map({
      optional("baseline", Schema::map({optional("source", Schema::string(), "the run the values came from"),
                                        optional("program_version", Schema::string(), "program of that run"),
                                        optional("note", Schema::string(), "free text")}),
               "where the expected values came from"),
      required("variants", Schema::dictionary(Schema::dictionary(gate_schema())),
               "variant id → metric → {expected, one band}"),
  });
  return schema;
}

Baseline parse_baseline(const YamlDocument& document) {
  ValidationErrors errors;
  YAML::Node root = document.root;  // a handle: validation fills in defaults, marks stay for messages
  if (!root.IsDefined() || root.IsNull()) {
    errors.add(InputError("the baseline file is empty", "variants", "a map with keys baseline, variants",
                          {document.file, 1, 1}));
    errors.throw_if_any();
  }
  baseline_schema()->validate(root, "", document.file, errors);
  errors.throw_if_any();
  Baseline baseline;
  baseline.file = document.file;
  if (root["baseline"]) {
    baseline.source = root["baseline"]["source"] ? root["baseline"]["source"].as<std::string>() : "";
    baseline.program_version =
        root["baseline"]["program_version"] ? root["baseline"]["program_version"].as<std::string>() : "";
  }
  for (auto v = root["variants"].begin(); v != root["variants"].end(); ++v) {
    const auto variant = v->first.as<std::string>();
    for (auto m = v->second.begin(); m != v->second.end(); ++m) {
      const auto metric = m->first.as<std::string>();
      const YAML::Node node = m->second;
      Gate gate;
      gate.variant = variant;
      gate.metric = metric;
      gate.where = location_of(m->first, document.file);
      if (node["equals"]) {
        gate.kind = BandKind::Equals;
        gate.expected_text = node["equals"].as<std::string>();
        if (node["expected"] || node["abs"] || node["rel"] || node["not_worse_than"]) {
          errors.add(InputError("an 'equals' gate takes no expected value or band",
                                fmt::format("variants.{}.{}", variant, metric), "equals: TEXT alone",
                                location_of(node, document.file)));
          continue;
        }
        baseline.gates.push_back(std::move(gate));
        continue;
      }
      if (!node["expected"]) {
        errors.add(InputError("missing required key 'expected'", fmt::format("variants.{}.{}.expected", variant, metric),
                              "a number (or 'equals: TEXT' for a text metric)", location_of(node, document.file)));
        continue;
      }
      gate.expected = node["expected"].as<double>();
      int bands = 0;
      if (node["abs"]) {
        ++bands;
        gate.kind = BandKind::Absolute;
        gate.width = node["abs"].as<double>();
      }
      if (node["rel"]) {
        ++bands;
        gate.kind = BandKind::Relative;
        gate.width = node["rel"].as<double>();
      }
      if (node["not_worse_than"]) {
        ++bands;
        gate.kind = BandKind::NotWorseThan;
        gate.direction = node["not_worse_than"]["direction"].as<std::string>() == kHigherIsBetter
                             ? Direction::HigherIsBetter
                             : Direction::LowerIsBetter;
        gate.confidence = node["not_worse_than"]["ci"].as<double>();
      }
      if (bands != 1) {
        errors.add(InputError(fmt::format("a gate needs exactly one band, found {}", bands),
                              fmt::format("variants.{}.{}", variant, metric), "abs, rel or not_worse_than",
                              location_of(node, document.file)));
        continue;
      }
      baseline.gates.push_back(std::move(gate));
    }
  }
  if (errors.empty() && baseline.gates.empty()) {
    errors.add(InputError("the baseline has no gate", "variants", "variant id → metric → {expected, band}",
                          location_of(root["variants"], document.file)));
  }
  errors.throw_if_any();
  return baseline;
}

Baseline load_baseline(const std::filesystem::path& path) { return parse_baseline(load_yaml_file(path)); }

Baseline make_baseline(const RunData& run, const BaselineOptions& options, const std::string& program_version) {
  for (const auto& v : options.variants) {
    if (!run.has_variant(v)) {
      throw InputError(fmt::format("the run has no variant '{}'", v), "--variant",
                       fmt::format("{}", fmt::join(run.variants, ", ")));
    }
  }
  if (!(options.width >= 0.0) && options.kind != BandKind::NotWorseThan) {
    throw InputError(fmt::format("band width {} is negative", options.width), "--rel/--abs", "a number ≥ 0");
  }
  Baseline baseline;
  baseline.source = run.dir;
  baseline.program_version = program_version;
  for (const auto& variant : run.variants) {
    if (!options.variants.empty() &&
        std::find(options.variants.begin(), options.variants.end(), variant) == options.variants.end()) {
      continue;
    }
    const auto episodes = run.of_variant(variant);
    std::set<std::string> names;
    for (const auto& e : episodes) {
      for (const auto& [name, value] : e.metrics) {
        if (metric_matches(name, options.metrics)) names.insert(name);
      }
    }
    for (const auto& metric : names) {
      const auto values = metric_values(episodes, metric);
      if (values.empty()) continue;
      Gate gate;
      gate.variant = variant;
      gate.metric = metric;
      gate.expected = mean(values);
      gate.kind = options.kind;
      gate.width = options.width;
      gate.direction = options.direction;
      gate.confidence = options.confidence;
      if (gate.kind == BandKind::Relative && gate.expected == 0.0) {
        const double sd = values.size() > 1 ? sample_sd(values) : 0.0;
        gate.kind = BandKind::Absolute;
        gate.width = std::max(3.0 * sd / std::sqrt(static_cast<double>(values.size())), options.zero_floor);
      }
      baseline.gates.push_back(std::move(gate));
    }
    if (!options.texts) continue;
    std::set<std::string> text_names;
    for (const auto& e : episodes) {
      for (const auto& [name, value] : e.texts) {
        if (metric_matches(name, options.metrics)) text_names.insert(name);
      }
    }
    for (const auto& metric : text_names) {
      const auto values = text_values(episodes, metric);
      if (values.size() != episodes.size() ||
          std::any_of(values.begin(), values.end(), [&](const std::string& v) { return v != values.front(); })) {
        continue;  // differs between episodes (e.g. different seeds): nothing to pin
      }
      Gate gate;
      gate.variant = variant;
      gate.metric = metric;
      gate.kind = BandKind::Equals;
      gate.expected_text = values.front();
      baseline.gates.push_back(std::move(gate));
    }
  }
  if (baseline.gates.empty()) {
    throw InputError("the selection holds no metric to gate", "--metric",
                     "patterns that match metrics of the run (e.g. 'duration_s', 'metrics.*')");
  }
  return baseline;
}

std::string baseline_yaml(const Baseline& baseline) {
  std::string out =
      "# Regression baseline for `freeplay check` (format: docs/analysis.md).\n"
      "# Each gate: the expected mean of a variant's metric and ONE band:\n"
      "#   abs: X   passes when |mean - expected| <= X\n"
      "#   rel: R   passes when |mean - expected| <= R * |expected|\n"
      "#   not_worse_than: {direction: higher_is_better|lower_is_better, ci: 0.95}\n"
      "#            fails only when the run's CI of the mean lies wholly on the worse side of expected\n"
      "#   {equals: TEXT}  a text metric (a golden-trace hash): every episode's value must equal TEXT\n";
  out += "baseline:\n";
  out += fmt::format("  source: {}\n", quoted(baseline.source));
  out += fmt::format("  program_version: {}\n", quoted(baseline.program_version));
  out += "variants:\n";
  std::string current;
  bool first = true;
  for (const auto& gate : baseline.gates) {
    if (first || gate.variant != current) {
      out += fmt::format("  {}:\n", quoted(gate.variant));
      current = gate.variant;
      first = false;
    }
    std::string band;
    switch (gate.kind) {
      case BandKind::Absolute: band = fmt::format("abs: {}", number_text(gate.width)); break;
      case BandKind::Relative: band = fmt::format("rel: {}", number_text(gate.width)); break;
      case BandKind::NotWorseThan:
        band = fmt::format("not_worse_than: {{direction: {}, ci: {}}}",
                           gate.direction == Direction::HigherIsBetter ? kHigherIsBetter : kLowerIsBetter,
                           number_text(gate.confidence));
        break;
      case BandKind::Equals:
        out += fmt::format("    {}: {{equals: {}}}\n", quoted(gate.metric), quoted(gate.expected_text));
        continue;
    }
    out += fmt::format("    {}: {{expected: {}, {}}}\n", quoted(gate.metric), number_text(gate.expected), band);
  }
  return out;
}

int CheckReport::failures() const {
  return static_cast<int>(std::count_if(results.begin(), results.end(), [](const GateResult& r) { return !r.passed; }));
}

CheckReport check_run(const RunData& run, const Baseline& baseline, int resamples, std::uint64_t seed) {
  ValidationErrors errors;
  CheckReport report;
  report.run = run.dir;
  report.baseline = baseline.file;
  for (const auto& gate : baseline.gates) {
    const auto key = fmt::format("variants.{}.{}", gate.variant, gate.metric);
    if (!run.has_variant(gate.variant)) {
      errors.add(InputError(fmt::format("the run '{}' has no episodes of variant '{}'", run.dir, gate.variant), key,
                            fmt::format("{}", fmt::join(run.variants, ", ")), gate.where));
      continue;
    }
    if (gate.kind == BandKind::Equals) {
      const auto texts = text_values(run.of_variant(gate.variant), gate.metric);
      if (!texts.empty()) {
        report.results.push_back(evaluate_text(gate, texts));
        continue;
      }
    }
    const auto values = gate.kind == BandKind::Equals ? std::vector<double>{}
                                                      : metric_values(run.of_variant(gate.variant), gate.metric);
    if (values.empty()) {
      std::set<std::string> names;
      for (const auto& e : run.of_variant(gate.variant)) {
        for (const auto& [name, value] : e.metrics) names.insert(name);
      }
      errors.add(InputError(fmt::format("the run '{}' has no metric '{}' in variant '{}'", run.dir, gate.metric,
                                        gate.variant),
                            key, fmt::format("{}", fmt::join(names, ", ")), gate.where));
      continue;
    }
    const auto gate_seed = splitmix64(seed ^ fnv1a64(gate.variant + "/" + gate.metric));
    report.results.push_back(evaluate(gate, values, resamples, gate_seed));
  }
  errors.throw_if_any();
  return report;
}

std::string check_table(const CheckReport& report) {
  std::size_t variant_width = 7;
  std::size_t metric_width = 6;
  for (const auto& r : report.results) {
    variant_width = std::max(variant_width, r.gate.variant.size());
    metric_width = std::max(metric_width, r.gate.metric.size());
  }
  std::string out = fmt::format("run {} against {}\n\n", report.run, report.baseline.empty() ? "(baseline)" : report.baseline);
  out += fmt::format("{:<4}  {:<{}}  {:<{}}  {}\n", "gate", "variant", variant_width, "metric", metric_width, "verdict");
  for (const auto& r : report.results) {
    out += fmt::format("{:<4}  {:<{}}  {:<{}}  {}\n", r.passed ? "ok" : "FAIL", r.gate.variant, variant_width,
                       r.gate.metric, metric_width, r.verdict);
  }
  const int failed = report.failures();
  out += fmt::format("\n{} of {} gates {}\n", failed == 0 ? static_cast<int>(report.results.size()) : failed,
                     report.results.size(), failed == 0 ? "passed" : "FAILED");
  return out;
}

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\t': out += "&#9;"; break;
      case '\n': out += "&#10;"; break;
      case '\r': out += "&#13;"; break;
      default:
        // XML 1.0 forbids the other C0 control characters even as references.
        out += static_cast<unsigned char>(c) < 0x20 ? '?' : c;
    }
  }
  return out;
}

std::string junit_xml(const CheckReport& report) {
  std::vector<std::string> variants;
  for (const auto& r : report.results) {
    if (std::find(variants.begin(), variants.end(), r.gate.variant) == variants.end()) variants.push_back(r.gate.variant);
  }
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format("<testsuites name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\">\n",
                     xml_escape("freeplay check " + report.run), report.results.size(), report.failures());
  for (const auto& variant : variants) {
    int tests = 0;
    int failures = 0;
    for (const auto& r : report.results) {
      if (r.gate.variant != variant) continue;
      ++tests;
      failures += r.passed ? 0 : 1;
    }
    out += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"0\" time=\"0\">\n",
                       xml_escape(variant), tests, failures);
    out += fmt::format("    <properties>\n      <property name=\"run\" value=\"{}\"/>\n"
                       "      <property name=\"baseline\" value=\"{}\"/>\n    </properties>\n",
                       xml_escape(report.run), xml_escape(report.baseline));
    for (const auto& r : report.results) {
      if (r.gate.variant != variant) continue;
      out += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"0\">\n",
                         xml_escape("freeplay.check." + variant), xml_escape(r.gate.metric));
      if (!r.passed) {
        out += fmt::format("      <failure message=\"{}\" type=\"RegressionGate\">{}</failure>\n",
                           xml_escape(fmt::format("{} misses its band by {}", r.gate.metric, short_number(r.miss))),
                           xml_escape(r.verdict));
      }
      out += fmt::format("      <system-out>{}</system-out>\n    </testcase>\n", xml_escape(r.verdict));
    }
    out += "  </testsuite>\n";
  }
  out += "</testsuites>\n";
  return out;
}

}  // namespace freeplay::analysis
