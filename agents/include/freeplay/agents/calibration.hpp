#pragma once
// Calibration of the child model against the PInSoRo statistics (pinsoro-targets.md): population simulation,
// summary statistics, the simulated-vs-target table, and the documented fitting procedure.

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "freeplay/agents/params.hpp"
#include "freeplay/agents/session.hpp"

namespace freeplay::agents {

/// Survival is reported at these session lengths (minutes).
inline constexpr std::array<double, 4> kSurvivalMinutes = {5.0, 10.0, 20.0, 30.0};

/// Session-duration statistics of a population (minutes).
struct DurationStats {
  int sessions = 0;                    ///< number of sessions
  double mean_min = 0.0;               ///< mean
  double sd_min = 0.0;                 ///< sample standard deviation
  double q1_min = 0.0;                 ///< first quartile
  double median_min = 0.0;             ///< median
  double q3_min = 0.0;                 ///< third quartile
  std::array<double, 4> survival{};    ///< fraction still running at kSurvivalMinutes
  double cap_fraction = 0.0;           ///< fraction stopped by the 40-minute cap
};

/// Label statistics of a population (the children's ground-truth timelines).
struct LabelStats {
  std::array<std::array<double, kMaxLabels>, kAxisCount> share{};        ///< per-child mean share per label
  std::array<std::array<double, kMaxLabels>, kAxisCount> bout_median_s{};///< pooled bout-duration median per label
  std::array<std::array<int, kMaxLabels>, kAxisCount> bouts{};           ///< pooled bout counts per label
  std::array<std::array<double, 5>, 5> social_transitions{};            ///< row → next-label probability
  std::array<double, kAxisCount> changes_per_min{};                     ///< label changes per minute of session
  double dyad_same_social = 0.0;   ///< P(both children carry the same social label), 1-s sampling (child-child)
  double dyad_cooperative = 0.0;   ///< share of sampled seconds with both children cooperative (child-child)
  double coder_agreement = 0.0;    ///< share of sampled seconds where the coded social label equals the child's state
  std::array<double, kAxisCount> coder_agreement_by_axis{};  ///< the same agreement on each axis
  std::array<double, kAxisCount> dyad_same{};  ///< P(both children carry the same label) on each axis (child-child)
  std::array<double, kMaxLabels> dyad_pair_share{};  ///< share of sampled seconds with both children in label j
  double items_taken_per_min = 0.0;      ///< items the partner took from a child, per child-minute
  double contingent_per_min = 0.0;       ///< partner responses a child perceived as contingent, per child-minute
  double unanswered_bids_per_min = 0.0;  ///< bids that went unanswered, per child-minute
};

/// Everything measured on one simulated population.
struct PopulationStats {
  Condition condition = Condition::ChildChild;  ///< which condition
  DurationStats duration;                       ///< session lengths
  LabelStats labels;                            ///< ground-truth label statistics (all simulated children)
};

/// Simulates `sessions` sessions (session i uses seed SeedSequence(seed).derive("session.<i>")) on `threads` threads.
std::vector<SessionResult> simulate_population(const ChildModelParams& params, Condition condition, int sessions,
                                               std::uint64_t seed, int threads = 1);
/// Statistics of simulated sessions.
PopulationStats summarise(const std::vector<SessionResult>& sessions, Condition condition);

/// One row of the simulated-vs-target table.
struct ComparisonRow {
  std::string group;       ///< e.g. "cc duration", "cc share task_engagement"
  std::string name;        ///< e.g. "mean (min)", "goaloriented"
  double simulated = 0.0;  ///< simulated value
  double target = 0.0;     ///< PInSoRo value
  double lo = 0.0;         ///< lower bound of the acceptance band
  double hi = 0.0;         ///< upper bound of the acceptance band
  bool checked = false;    ///< false for rows shown for information only (no bound in the issue)

  /// True when the row is unchecked or the simulated value lies in [lo, hi].
  bool within() const { return !checked || (simulated >= lo && simulated <= hi); }
};

/// Half-width of the acceptance band of a social-transition probability (PInSoRo rows hold 174–300 transitions).
inline constexpr double kTransitionTolerance = 0.15;

/// Side-by-side rows for child-child (`cc`, may be null) and child-robot (`cr`, may be null) statistics.
std::vector<ComparisonRow> compare_with_targets(const PopulationStats* cc, const PopulationStats* cr);
/// The rows as an aligned text table with a within/OUTSIDE mark per checked row.
std::string format_comparison(const std::vector<ComparisonRow>& rows);

/// Options of the fitting procedure.
struct FitOptions {
  int sessions = 120;            ///< sessions per condition per evaluation (common random numbers)
  std::uint64_t seed = 2017;     ///< root of the session seeds (fit on one seed, check on another)
  int rounds = 4;                ///< sweeps of the coordinate search over every fitted parameter
  int threads = 1;               ///< worker threads for the simulations
  std::function<void(const std::string&)> log;  ///< progress lines (may be empty)
  /// Names of the fitted parameters to move (as fit_parameter_names() spells them); empty: all of them.
  std::vector<std::string> only;
  /// Simulates both conditions with the given parameters (the child-child and the child-robot population); empty:
  /// the logic-only simulator with `sessions`, `seed` and `threads`. The full episode loop plugs in here.
  std::function<std::pair<PopulationStats, PopulationStats>(const ChildModelParams&)> simulate;
};

/// Outcome of a fit.
struct FitResult {
  ChildModelParams params;   ///< fitted parameters
  double loss_before = 0.0;  ///< fit_loss of the starting parameters
  double loss_after = 0.0;   ///< … and of the fitted ones
  int outside_before = 0;    ///< checked target rows outside their bands before
  int outside_after = 0;     ///< … and after
  int simulations = 0;       ///< sessions simulated in total
};

/// The fitting loss over the given targets only: every checked child-child row and the child-robot duration rows,
/// each as its distance to the target in units of the band's half-width, squared, plus a steep penalty beyond 0.8 of
/// it; the child-child label changes per minute (no band) enter with a light weight. Child-robot label statistics
/// never enter (they are predictions). `outside` receives the number of checked rows outside their bands.
double fit_loss(const std::vector<ComparisonRow>& rows, int* outside = nullptr);

/// PInSoRo's child-child median bout of `label` on `axis` (pinsoro-targets.md §4), in seconds.
double bout_median_target_s(Axis axis, std::size_t label);

/// Simulated method of moments (docs/agents.md, "Fitting"): a coordinate search (each parameter stepped up and down
/// on its own scale, steps growing on success and shrinking on failure) over the entry biases and dwell medians of
/// the three axes (a dwell median within a factor of 3 of its label's PInSoRo bout median) and the drive, partnership and expression parameters listed in fit.cpp, minimising fit_loss with
/// common random numbers (the same seeds for every evaluation).
FitResult fit_child_model(const ChildModelParams& start, const FitOptions& options);

/// The names of every parameter the fit may move, in the order it moves them (for `FitOptions::only`).
std::vector<std::string> fit_parameter_names();

}  // namespace freeplay::agents
