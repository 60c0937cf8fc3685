#include "freeplay/agents/params.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <vector>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/core/yaml_schema.hpp"

namespace freeplay::agents {
namespace {

constexpr std::array<std::string_view, kFeatureCount> kFeatureNames = {
    "motivation",      "age",           "sociability",       "assertiveness", "tablet",      "partner_active",
    "partner_joint",   "partner_attention", "grievance",   "task_noplay",   "together"};

/// The labels of `axis`, in the order of the coding scheme (the keys of a value per label).
std::vector<std::string> label_list(Axis axis) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < label_count(axis); ++i) out.emplace_back(label_name(axis, i));
  return out;
}

/// A map with a value in [lo, hi] for every label of `axis`.
std::shared_ptr<const Schema> per_label(Axis axis, double lo, double hi) {
  return named_map(label_list(axis), Schema::number(lo, hi), KeyCoverage::All);
}

}  // namespace

template <typename Archive>
void AxisModel::visit(Archive& a, Axis axis) {
  const std::vector<std::string> labels = label_list(axis);
  const std::vector<std::string> features(kFeatureNames.begin(), kFeatureNames.end());
  a.required("dwell_median_s", dwell_median_s, per_label(axis, 0.5, 3600.0));
  a.required("dwell_sigma", dwell_sigma, per_label(axis, 0.05, 3.0));
  a.required("bias", bias, per_label(axis, -20.0, 20.0));
  a.required("transitions", transition,
             named_map(labels, named_map(labels, Schema::number(0.0, 1e6), KeyCoverage::Some), KeyCoverage::All),
             "a row per label: the weights of moving to the other labels (absent: 0; its own label is ignored)");
  a.optional("coupling", coupling,
             named_map(labels, named_map(features, Schema::number(-20.0, 20.0), KeyCoverage::Some), KeyCoverage::Some),
             "a row per label: log-weight of entering it per feature (absent: 0)");
}

template <typename Archive>
void DriveParams::visit(Archive& a) {
  a.required("initial_motivation_mean", initial_motivation_mean, Schema::number(0, 1));
  a.required("initial_motivation_sd", initial_motivation_sd, Schema::number(0, 1));
  a.required("decay_per_min", decay_per_min, Schema::number(0, 100));
  a.required("attention_effect", attention_effect, Schema::number(-10, 10));
  a.required("play_gain_per_min", play_gain_per_min, Schema::number(0, 100));
  a.required("contingency_gain", contingency_gain, Schema::number(0, 1));
  a.required("unanswered_bid_drop", unanswered_bid_drop, Schema::number(0, 1));
  a.required("unfairness_drop", unfairness_drop, Schema::number(0, 1));
  a.required("novelty_gain_per_min", novelty_gain_per_min, Schema::number(0, 100));
  a.required("novelty_tau_min", novelty_tau_min, Schema::number(0.01, 1000));
  a.required("boredom_rate_per_min", boredom_rate_per_min, Schema::number(0, 100));
  a.required("quit_hazard_per_min", quit_hazard_per_min, Schema::number(0, 100));
  a.required("quit_boredom_slope", quit_boredom_slope, Schema::number(0, 100));
  a.required("quit_motivation_slope", quit_motivation_slope, Schema::number(-100, 100));
  a.required("partner_quit_factor", partner_quit_factor, Schema::number(1, 1e6));
  a.required("grievance_tau_s", grievance_tau_s, Schema::number(0.1, 3600));
  a.required("attention_tau_s", attention_tau_s, Schema::number(0.1, 3600));
}

template <typename Archive>
void ReactionParams::visit(Archive& a) {
  a.required("take_reaction_probability", take_reaction_probability, Schema::number(0, 1));
  a.required("unanswered_frustration_probability", unanswered_frustration_probability, Schema::number(0, 1));
  a.required("frustrated_weight", frustrated_weight, Schema::number(0, 1e3));
  a.required("adversarial_weight", adversarial_weight, Schema::number(0, 1e3));
  a.required("assertive_weight", assertive_weight, Schema::number(0, 1e3));
  a.required("retaliation_probability", retaliation_probability, Schema::number(0, 1));
  a.required("imitation_probability", imitation_probability, Schema::number(0, 1));
  a.required("ownership_memory_s", ownership_memory_s, Schema::number(0, 3600));
  a.required("look_weight", look_weight, Schema::number(0, 10));
  a.required("talk_weight", talk_weight, Schema::number(0, 10));
  a.required("act_weight", act_weight, Schema::number(0, 10));
}

template <typename Archive>
void MotorParams::visit(Archive& a) {
  a.required("fitts_a_s", fitts_a_s, Schema::number(0, 10));
  a.required("fitts_b_s_per_bit", fitts_b_s_per_bit, Schema::number(0, 10));
  a.required("age_slowdown_per_year", age_slowdown_per_year, Schema::number(0, 1));
  a.required("endpoint_sd_m", endpoint_sd_m, Schema::number(0, 0.1));
  a.required("tap_min_s", tap_min_s, Schema::number(0.01, 5));
  a.required("tap_max_s", tap_max_s, Schema::number(0.01, 5), "at least tap_min_s");
  a.required("reach_depth_m", reach_depth_m, Schema::number(0.05, 1));
  a.required("reach_per_year_m", reach_per_year_m, Schema::number(0, 0.1));
  a.required("action_gap_sigma", action_gap_sigma, Schema::number(0, 3));
  a.required("stroke_duration_s", stroke_duration_s, Schema::number(0.1, 60));
  a.required("action_gap_median_s", action_gap_median_s, per_label(Axis::TaskEngagement, 0.0, 3600.0));
}

template <typename Archive>
void ExpressionParams::visit(Archive& a) {
  a.required("glance_median_s", glance_median_s, Schema::number(0.05, 60));
  a.required("glance_sigma", glance_sigma, Schema::number(0, 3));
  a.required("adult_speech_per_min", adult_speech_per_min, Schema::number(0, 60));
  a.required("robot_curiosity_per_min", robot_curiosity_per_min, Schema::number(0, 60));
  a.required("robot_novelty_face_share", robot_novelty_face_share, Schema::number(0, 1));
  a.required("noplay_watch_share", noplay_watch_share, Schema::number(0, 1));
  a.required("noplay_speech_share", noplay_speech_share, Schema::number(0, 1));
  a.required("syllables_mean", syllables_mean, Schema::number(1, 50));
  a.required("articulation_rate_at_3", articulation_rate_at_3, Schema::number(0.5, 10));
  a.required("articulation_rate_per_year", articulation_rate_per_year, Schema::number(0, 1));
  a.required("partner_face_share", partner_face_share, per_label(Axis::SocialEngagement, 0.0, 1.0));
  a.required("speech_per_min", speech_per_min, per_label(Axis::SocialEngagement, 0.0, 60.0));
  a.required("proposal_share", proposal_share, per_label(Axis::SocialAttitude, 0.0, 1.0));
}

template <typename Archive>
void TraitParams::visit(Archive& a) {
  a.required("sociability_mean", sociability_mean, Schema::number(0, 1));
  a.required("sociability_sd", sociability_sd, Schema::number(0, 1));
  a.required("assertiveness_mean", assertiveness_mean, Schema::number(0, 1));
  a.required("assertiveness_sd", assertiveness_sd, Schema::number(0, 1));
  a.required("attention_mean", attention_mean, Schema::number(0, 1));
  a.required("attention_sd", attention_sd, Schema::number(0, 1));
  a.required("attention_per_year", attention_per_year, Schema::number(-0.5, 0.5));
}

template <typename Archive>
void PartnershipParams::visit(Archive& a) {
  a.required("answer_age_logit", answer_age_logit, Schema::number(-20, 20));
  a.required("answer_sociability_logit", answer_sociability_logit, Schema::number(-20, 20));
  a.required("answer_delay_median_s", answer_delay_median_s, Schema::number(0.05, 60));
  a.required("join_probability", join_probability, Schema::number(0, 1));
  a.required("reciprocity_window_s", reciprocity_window_s, Schema::number(0.5, 600));
  a.required("window_per_year", window_per_year, Schema::number(-0.5, 0.5));
  a.required("expectation_exponent", expectation_exponent, Schema::number(0, 20));
  a.required("bid_floor", bid_floor, Schema::number(0, 1));
  a.required("watch_window_s", watch_window_s, Schema::number(0.5, 600));
  a.required("onlooking_after_s", onlooking_after_s, Schema::number(0.5, 600));
  a.required("answer_probability", answer_probability, per_label(Axis::SocialEngagement, 0.0, 1.0));
}

template <typename Archive>
void ContingencyParams::visit(Archive& a) {
  a.required("response_window_s", response_window_s, Schema::number(0.1, 60));
  a.required("about_distance_m", about_distance_m, Schema::number(0, 1));
  a.required("memory_s", memory_s, Schema::number(1, 3600));
  a.required("prior_bids", prior_bids, Schema::number(0, 1000));
  a.required("prior_answered_share", prior_answered_share, Schema::number(0, 1));
  a.required("prior_free_time_s", prior_free_time_s, Schema::number(0, 3600));
  a.required("prior_base_rate_per_min", prior_base_rate_per_min, Schema::number(0, 600));
  a.required("prior_link_probability", prior_link_probability, Schema::number(0.001, 0.999));
  a.required("non_contingent_weight", non_contingent_weight, Schema::number(0, 10));
  a.required("habituation_rate", habituation_rate, Schema::number(0, 1));
  a.required("habituation_recovery_s", habituation_recovery_s, Schema::number(0, 36000));
  a.required("interruption_tau_s", interruption_tau_s, Schema::number(0.1, 3600));
  a.required("interruption_threshold", interruption_threshold, Schema::number(0, 1000));
  a.required("interruption_drop", interruption_drop, Schema::number(0, 1));
}

template <typename Archive>
void CoderParams::visit(Archive& a) {
  a.required("answer_window_s", answer_window_s, Schema::number(0.1, 600));
  a.required("follow_window_s", follow_window_s, Schema::number(0.1, 600));
  a.required("joint_distance_m", joint_distance_m, Schema::number(0, 1));
  a.required("talk_play_window_s", talk_play_window_s, Schema::number(0.1, 600));
  a.required("interaction_window_s", interaction_window_s, Schema::number(0.1, 600));
  a.required("cooperation_window_s", cooperation_window_s, Schema::number(0.1, 600));
  a.required("cooperation_hold_s", cooperation_hold_s, Schema::number(0, 600));
  a.required("discussion_hold_s", discussion_hold_s, Schema::number(0, 600));
  a.required("active_window_s", active_window_s, Schema::number(0.1, 600));
  a.required("watch_share", watch_share, Schema::number(0, 1));
  a.required("watch_window_s", watch_window_s, Schema::number(0.1, 600));
  a.required("min_bout_s", min_bout_s, Schema::number(0, 600));
  a.required("task_min_bout_s", task_min_bout_s, Schema::number(0, 600));
  a.required("stroke_min_s", stroke_min_s, Schema::number(0, 60));
  a.required("evidence_hold_s", evidence_hold_s, Schema::number(0.1, 600));
  a.required("judgement_window_s", judgement_window_s, Schema::number(0.1, 600));
  a.required("play_share", play_share, Schema::number(0, 1));
  a.required("friendly_share", friendly_share, Schema::number(0, 1));
  a.required("interaction_hold_s", interaction_hold_s, Schema::number(0.1, 600));
  a.required("adult_hold_s", adult_hold_s, Schema::number(0.1, 600));
  a.required("attitude_min_bout_s", attitude_min_bout_s, Schema::number(0, 600));
  a.required("salient_min_bout_s", salient_min_bout_s, Schema::number(0, 600));
  a.required("anchoring", anchoring, Schema::number(0, 2));
  a.required("take_window_s", take_window_s, Schema::number(0.1, 600));
  a.required("adversarial_hold_s", adversarial_hold_s, Schema::number(0.1, 600));
  a.required("frustrated_hold_s", frustrated_hold_s, Schema::number(0.1, 600));
  a.required("assertive_hold_s", assertive_hold_s, Schema::number(0.1, 600));
}

template <typename Archive>
void ChildModelParams::visit(Archive& a) {
  double version = 1;  // the file format; only 1 exists
  a.required("version", version, Schema::number(1, 1));
  a.required("session_cap_s", session_cap_s, Schema::number(1.0, 86400.0));
  a.section("axes", [this](auto& all_axes) {
    for (const Axis x : kAxes) {
      all_axes.section(std::string(axis_name(x)), [this, x](auto& one_axis) { axis(x).visit(one_axis, x); });
    }
  });
  a.required("drives", drives, settings_schema<DriveParams>());
  a.required("reactions", reactions, settings_schema<ReactionParams>());
  a.required("motor", motor, settings_schema<MotorParams>());
  a.required("expression", expression, settings_schema<ExpressionParams>());
  a.required("traits", traits, settings_schema<TraitParams>());
  a.required("partnership", partnership, settings_schema<PartnershipParams>());
  a.required("contingency", contingency, settings_schema<ContingencyParams>());
  a.required("coder", coder, settings_schema<CoderParams>());
}

namespace {

/// The rules no single key's range states: a transition row has some weight to another label (its own label's
/// weight is ignored), and tap_max_s is at least tap_min_s. `root` locates the offending key.
void check_across_keys(ChildModelParams& p, const YAML::Node& root, const std::string& file) {
  for (const Axis axis : kAxes) {
    AxisModel& m = p.axis(axis);
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      m.transition[i][i] = 0.0;
      double total = 0.0;
      for (const double v : m.transition[i]) total += v;
      if (total > 0.0) continue;
      const std::string label(label_name(axis, i));
      const YAML::Node row = root["axes"][std::string(axis_name(axis))]["transitions"][label];
      throw InputError("a row needs at least one positive weight to another label",
                       fmt::format("axes.{}.transitions.{}", axis_name(axis), label), {}, location_of(row, file));
    }
  }
  if (p.motor.tap_max_s < p.motor.tap_min_s) {
    throw InputError("must be ≥ tap_min_s", "motor.tap_max_s", {}, location_of(root["motor"]["tap_max_s"], file));
  }
}

}  // namespace

ChildModelParams parse_child_model_params(std::string_view yaml_text, const std::string& file) {
  const YamlDocument document = parse_yaml(std::string(yaml_text), file);
  ValidationErrors errors;
  settings_schema<ChildModelParams>()->validate(document.root, "", file, errors);
  errors.throw_if_any();
  ChildModelParams params = read_settings<ChildModelParams>(document.root);
  check_across_keys(params, document.root, file);
  return params;
}

ChildModelParams load_child_model_params(const std::filesystem::path& path) {
  return parse_child_model_params(read_file(path), path.string());
}

ChildModelParams default_child_model_params() { return load_child_model_params(asset_path("agents/child-model.yaml")); }

std::string child_model_params_to_yaml(const ChildModelParams& p, std::string_view header) {
  std::string text;
  if (!header.empty()) {
    std::size_t start = 0;
    while (start <= header.size()) {
      const std::size_t end = header.find('\n', start);
      text += "# " + std::string(header.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)) + "\n";
      if (end == std::string_view::npos) break;
      start = end + 1;
    }
  }
  text += write_settings(p);
  text += "\n";
  return text;
}

}  // namespace freeplay::agents
