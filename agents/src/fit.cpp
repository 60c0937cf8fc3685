// The fitting procedure of the child model against the given PInSoRo targets (docs/agents.md, "Fitting").
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "freeplay/agents/calibration.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::agents {
namespace {

/// How far a fitted internal dwell median may lie from its label's coded bout median (a factor).
constexpr double kDwellBand = 3.0;

/// Where the loss of a checked row turns steep, in units of its band's half-width (fit_loss).
constexpr double kSteepFrom = 0.6;

/// How a fitted parameter is searched: on its own scale, within bounds.
enum class Scale : std::uint8_t {
  Linear,  ///< biases and couplings (log-weights already)
  Log,     ///< positive quantities (rates, times)
  Logit,   ///< probabilities and shares
};

/// One fitted parameter: where it lives in the parameters, its search scale and its bounds.
struct Fitted {
  std::string name;
  std::function<double&(ChildModelParams&)> ref;
  Scale scale;
  double lo;
  double hi;
};

double to_search(const Fitted& f, double v) {
  switch (f.scale) {
    case Scale::Log: return std::log(std::max(v, 1e-9));
    case Scale::Logit: {
      const double q = std::clamp(v, 1e-4, 1.0 - 1e-4);
      return std::log(q / (1.0 - q));
    }
    case Scale::Linear: break;
  }
  return v;
}

double from_search(const Fitted& f, double x) {
  const double v = f.scale == Scale::Log ? std::exp(x) : f.scale == Scale::Logit ? 1.0 / (1.0 + std::exp(-x)) : x;
  return std::clamp(v, f.lo, f.hi);
}

/// The parameters the fit moves: what the targets inform (entry biases and dwell medians of every axis; the drives
/// and quit hazard for the durations; answering, joining and reciprocity for the social labels and the dyad; speech
/// and gaze rates of joint play and the assertive share of proposals for the coded labels). The contingency
/// detector, the coder's rules, motor and trait parameters stay as set from their sources.
std::vector<Fitted> fitted_parameters() {
  std::vector<Fitted> out;
  const auto axis = [&out](Axis a, const char* name) {
    for (std::size_t j = 0; j < label_count(a); ++j) {
      out.push_back({fmt::format("{}.bias.{}", name, label_name(a, j)),
                     [a, j](ChildModelParams& p) -> double& { return p.axis(a).bias[j]; }, Scale::Linear, -10.0, 10.0});
      // A child's own stretch of one kind of play lasts about as long as a coder's bout of it: the internal dwell
      // stays within a factor of 3 of the label's PInSoRo bout median (§4), so the fit cannot trade an internal
      // state that never ends (or flickers) against the coder's rules.
      const double bout = bout_median_target_s(a, j);
      out.push_back({fmt::format("{}.dwell_median_s.{}", name, label_name(a, j)),
                     [a, j](ChildModelParams& p) -> double& { return p.axis(a).dwell_median_s[j]; }, Scale::Log,
                     bout / kDwellBand, bout * kDwellBand});
    }
  };
  axis(Axis::SocialEngagement, "social_engagement");
  axis(Axis::SocialAttitude, "social_attitude");
  axis(Axis::TaskEngagement, "task_engagement");
#define FREEPLAY_FITTED(path, scale, lo, hi) \
  out.push_back({#path, [](ChildModelParams& p) -> double& { return p.path; }, Scale::scale, lo, hi})
  FREEPLAY_FITTED(drives.decay_per_min, Log, 0.01, 5.0);
  FREEPLAY_FITTED(drives.boredom_rate_per_min, Log, 0.001, 2.0);
  FREEPLAY_FITTED(drives.quit_hazard_per_min, Log, 1e-4, 1.0);
  FREEPLAY_FITTED(drives.quit_motivation_slope, Log, 0.1, 10.0);
  FREEPLAY_FITTED(drives.partner_quit_factor, Log, 1.0, 200.0);
  FREEPLAY_FITTED(drives.contingency_gain, Log, 0.001, 2.0);
  FREEPLAY_FITTED(drives.unanswered_bid_drop, Log, 0.001, 2.0);
  FREEPLAY_FITTED(drives.novelty_gain_per_min, Log, 0.001, 1.0);
  FREEPLAY_FITTED(partnership.reciprocity_window_s, Log, 3.0, 120.0);
  FREEPLAY_FITTED(partnership.join_probability, Logit, 0.01, 1.0);
  FREEPLAY_FITTED(partnership.expectation_exponent, Log, 0.1, 4.0);
  {
    // Watching long enough to be onlooking: within the dwell band of the coded onlooker bout (§4).
    const double bout = bout_median_target_s(Axis::SocialEngagement, static_cast<std::size_t>(SocialEngagement::Onlooker));
    FREEPLAY_FITTED(partnership.onlooking_after_s, Log, bout / kDwellBand, bout * kDwellBand);
  }
  FREEPLAY_FITTED(partnership.answer_probability[2], Logit, 0.01, 0.99);
  FREEPLAY_FITTED(partnership.answer_probability[3], Logit, 0.01, 0.99);
  FREEPLAY_FITTED(partnership.answer_probability[4], Logit, 0.01, 0.99);
  FREEPLAY_FITTED(expression.speech_per_min[3], Log, 0.5, 20.0);
  FREEPLAY_FITTED(expression.speech_per_min[4], Log, 0.5, 20.0);
  FREEPLAY_FITTED(expression.proposal_share[2], Logit, 0.01, 0.99);
  FREEPLAY_FITTED(expression.partner_face_share[3], Logit, 0.01, 0.9);
  FREEPLAY_FITTED(expression.partner_face_share[4], Logit, 0.01, 0.9);
  FREEPLAY_FITTED(expression.noplay_watch_share, Logit, 0.01, 0.99);
  FREEPLAY_FITTED(expression.noplay_speech_share, Logit, 0.02, 0.999);
  FREEPLAY_FITTED(reactions.unanswered_frustration_probability, Logit, 0.001, 0.5);
  FREEPLAY_FITTED(reactions.frustrated_weight, Log, 0.1, 10.0);
  FREEPLAY_FITTED(reactions.take_reaction_probability, Logit, 0.01, 0.99);
  FREEPLAY_FITTED(motor.action_gap_median_s[1], Log, 0.5, 30.0);
  // The coder's windows: how long a human coder holds a label on evidence (set on the child-child bouts before too).
  FREEPLAY_FITTED(coder.cooperation_hold_s, Log, 2.0, 60.0);
  FREEPLAY_FITTED(coder.interaction_hold_s, Log, 2.0, 60.0);
  FREEPLAY_FITTED(coder.min_bout_s, Log, 1.0, 30.0);
  FREEPLAY_FITTED(coder.attitude_min_bout_s, Log, 1.0, 30.0);
  FREEPLAY_FITTED(coder.anchoring, Log, 0.01, 1.0);
  FREEPLAY_FITTED(coder.watch_share, Logit, 0.05, 0.95);
#undef FREEPLAY_FITTED
  const auto coupling = [&out](SocialEngagement label, Feature feature, const char* name) {
    const auto j = static_cast<std::size_t>(label);
    const auto k = static_cast<std::size_t>(feature);
    out.push_back({name, [j, k](ChildModelParams& p) -> double& {
                     return p.axis(Axis::SocialEngagement).coupling[j][k];
                   },
                   Scale::Linear, -3.0, 6.0});
  };
  coupling(SocialEngagement::Associative, Feature::PartnerJoint, "social_engagement.coupling.associative.partner_joint");
  coupling(SocialEngagement::Cooperative, Feature::PartnerJoint, "social_engagement.coupling.cooperative.partner_joint");
  return out;
}

}  // namespace

double fit_loss(const std::vector<ComparisonRow>& rows, int* outside) {
  double loss = 0.0;
  int out = 0;
  for (const ComparisonRow& r : rows) {
    const bool child_child = r.group.rfind("cc", 0) == 0;
    const bool robot_duration = r.group.rfind("cr duration", 0) == 0;
    if (!child_child && !robot_duration) continue;
    if (!r.checked) {
      if (child_child && r.group.find("changes") != std::string::npos && r.target > 0.0) {
        const double z = (r.simulated - r.target) / (0.25 * r.target);
        loss += 0.3 * z * z;
      }
      continue;
    }
    const double half = std::max(r.simulated > r.target ? r.hi - r.target : r.target - r.lo, 1e-3);
    const double z = (r.simulated - r.target) / half;
    loss += z * z + 10.0 * std::pow(std::max(0.0, std::fabs(z) - kSteepFrom), 2);
    if (!r.within()) ++out;
  }
  if (outside != nullptr) *outside = out;
  return loss;
}

std::vector<std::string> fit_parameter_names() {
  std::vector<std::string> names;
  for (const Fitted& f : fitted_parameters()) names.push_back(f.name);
  return names;
}

FitResult fit_child_model(const ChildModelParams& start, const FitOptions& options) {
  FitResult result;
  std::vector<Fitted> fitted = fitted_parameters();
  if (!options.only.empty()) {
    const std::vector<std::string> all = fit_parameter_names();
    for (const std::string& name : options.only) {
      if (std::find(all.begin(), all.end(), name) == all.end()) {
        throw InputError(fmt::format("'{}' is not a fitted parameter", name), "--fit-only",
                         fmt::format("{}", fmt::join(all, ", ")));
      }
    }
    std::erase_if(fitted, [&](const Fitted& f) {
      return std::find(options.only.begin(), options.only.end(), f.name) == options.only.end();
    });
  }
  const auto log = [&](const std::string& line) {
    if (options.log) options.log(line);
  };
  const auto apply = [&](const std::vector<double>& x) {
    ChildModelParams p = start;
    for (std::size_t i = 0; i < fitted.size(); ++i) fitted[i].ref(p) = from_search(fitted[i], x[i]);
    return p;
  };
  const auto evaluate = [&](const ChildModelParams& p, int& outside) {
    result.simulations += 2 * options.sessions;
    if (options.simulate) {
      const auto [cc, cr] = options.simulate(p);
      return fit_loss(compare_with_targets(&cc, &cr), &outside);
    }
    const PopulationStats cc = summarise(
        simulate_population(p, Condition::ChildChild, options.sessions, options.seed, options.threads),
        Condition::ChildChild);
    const PopulationStats cr = summarise(
        simulate_population(p, Condition::ChildRobot, options.sessions, options.seed, options.threads),
        Condition::ChildRobot);
    return fit_loss(compare_with_targets(&cc, &cr), &outside);
  };

  std::vector<double> x;
  std::vector<double> step;
  for (const Fitted& f : fitted) {
    ChildModelParams copy = start;
    x.push_back(to_search(f, std::clamp(f.ref(copy), f.lo, f.hi)));  // a start outside the bounds begins at them
    step.push_back(f.scale == Scale::Linear ? 0.5 : 0.3);
  }
  int outside = 0;
  double best = evaluate(apply(x), outside);
  result.loss_before = best;
  result.outside_before = outside;
  log(fmt::format("start: loss {:.2f}, {} checked rows outside", best, outside));
  for (int round = 0; round < options.rounds; ++round) {
    for (std::size_t i = 0; i < fitted.size(); ++i) {
      bool improved = false;
      for (const double direction : {1.0, -1.0}) {
        std::vector<double> trial = x;
        trial[i] += direction * step[i];
        int trial_outside = 0;
        const double loss = evaluate(apply(trial), trial_outside);
        if (loss < best) {
          best = loss;
          outside = trial_outside;
          x = trial;
          improved = true;
          log(fmt::format("round {}: {} = {:.4g}: loss {:.2f}, {} outside", round + 1, fitted[i].name,
                          from_search(fitted[i], x[i]), best, outside));
          break;
        }
      }
      step[i] *= improved ? 1.5 : 0.6;
    }
    log(fmt::format("round {} done: loss {:.2f}, {} checked rows outside", round + 1, best, outside));
  }
  result.params = apply(x);
  result.loss_after = best;
  result.outside_after = outside;
  return result;
}

}  // namespace freeplay::agents
