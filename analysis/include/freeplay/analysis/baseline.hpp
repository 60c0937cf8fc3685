#pragma once
// Regression gates: a baseline file states, per variant and metric, the expected value and an allowed band;
// checking a run against it says which gates fail and by how much, as a table and as JUnit XML for CI servers.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "freeplay/analysis/run_data.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/core/yaml_schema.hpp"

namespace freeplay::analysis {

/// How far a run's mean may stray from the expected value.
enum class BandKind {
  Absolute,     ///< |mean − expected| ≤ width
  Relative,     ///< |mean − expected| ≤ width · |expected|
  NotWorseThan, ///< fails only when the run's CI of the mean lies entirely on the worse side of expected
  Equals        ///< a text metric (e.g. a golden-trace hash): every episode's value equals `expected_text`
};

/// Which way is better, for "not worse than" bands.
enum class Direction {
  HigherIsBetter,  ///< a lower mean is worse
  LowerIsBetter    ///< a higher mean is worse
};

/// One gate: a variant's metric, its expected value and band.
struct Gate {
  std::string variant;                          ///< suite variant id (the scenario name for plain suites)
  std::string metric;                           ///< dotted metric name
  double expected = 0.0;                        ///< expected mean
  BandKind kind = BandKind::Relative;           ///< band kind
  double width = 0.0;                           ///< abs or rel width (unused for NotWorseThan)
  Direction direction = Direction::HigherIsBetter;  ///< for NotWorseThan
  double confidence = 0.95;                     ///< CI level for NotWorseThan
  SourceLocation where;                         ///< where the gate stands in its file
  std::string expected_text = {};               ///< expected text (Equals gates)

  /// The band in words, e.g. "±25 %", "±0.5", "not lower than (95 % CI)".
  std::string band_text() const;
};

/// A baseline: every gate, in file order.
struct Baseline {
  std::string file;            ///< where it was loaded from ("" when made in code)
  std::string source;          ///< the run it was made from (informational)
  std::string program_version; ///< the program that made that run (informational)
  std::vector<Gate> gates;     ///< the gates
};

/// The schema of baseline files (see docs/analysis.md).
std::shared_ptr<const Schema> baseline_schema();

/// Parses and validates a baseline document; every problem in one InputError with file:line:column.
Baseline parse_baseline(const YamlDocument& document);
/// Loads and validates a baseline file.
Baseline load_baseline(const std::filesystem::path& path);

/// How `make_baseline` chooses each gate's band.
struct BaselineOptions {
  BandKind kind = BandKind::Relative;               ///< band kind for every gate
  double width = 0.25;                              ///< rel (fraction) or abs width
  Direction direction = Direction::HigherIsBetter;  ///< for NotWorseThan
  double confidence = 0.95;                         ///< for NotWorseThan
  double zero_floor = 1e-6;                         ///< Relative bands of metrics expected at 0 become abs bands of
                                                    ///< max(3 standard errors, zero_floor)
  std::vector<std::string> metrics;                 ///< glob patterns of the metrics to gate (empty: all)
  std::vector<std::string> variants;                ///< variants to gate (empty: all)
  bool texts = true;  ///< also gate text metrics (Equals) whose value is the same in every episode of a variant
};

/// A baseline whose expected values are the run's means; InputError when a filter selects nothing.
Baseline make_baseline(const RunData& run, const BaselineOptions& options, const std::string& program_version = {});

/// The baseline as a YAML file (keys quoted, numbers with round-trip precision, a header comment).
std::string baseline_yaml(const Baseline& baseline);

/// The outcome of one gate on a run.
struct GateResult {
  Gate gate;             ///< the gate
  int n = 0;             ///< episodes with a value
  double mean = 0.0;     ///< the run's mean
  Interval ci;           ///< the run's bootstrap CI of the mean (NotWorseThan only; NaN otherwise)
  bool passed = true;    ///< within the band
  double miss = 0.0;     ///< how far outside the band (0 when passed), in the metric's units
  std::string verdict;   ///< one line: value, expected, band and by how much it misses
  std::string text = {};  ///< the first differing (or common) text value (Equals gates)
};

/// The outcome of every gate.
struct CheckReport {
  std::string run;                  ///< the checked run
  std::string baseline;             ///< the baseline file
  std::vector<GateResult> results;  ///< in baseline order

  /// Number of failed gates.
  int failures() const;
};

/// Checks a run against a baseline; InputError (naming the gate's file:line:column) when a gate's variant or
/// metric is absent from the run — every such problem at once.
CheckReport check_run(const RunData& run, const Baseline& baseline, int resamples = 2000, std::uint64_t seed = 1);

/// A readable table of the gates in baseline order, each marked "ok" or "FAIL", with a count at the end.
std::string check_table(const CheckReport& report);

/// JUnit XML: one <testsuite> per variant, one <testcase> per gate, <failure> for failed gates.
std::string junit_xml(const CheckReport& report);

/// Escapes text for XML attributes and content (& < > " ' and characters XML 1.0 forbids).
std::string xml_escape(std::string_view text);

}  // namespace freeplay::analysis
