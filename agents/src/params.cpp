#include "freeplay/agents/params.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>
#include <vector>

#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"

namespace freeplay::agents {
namespace {

constexpr std::array<std::string_view, kFeatureCount> kFeatureNames = {
    "motivation",      "age",           "sociability",       "assertiveness", "tablet",      "partner_active",
    "partner_joint",   "partner_attention", "partner_robot", "grievance",     "task_noplay", "together"};

/// Reads validated values from one YAML document, naming file:line:column and the key path on errors.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& problem,
                         const std::string& allowed = {}) const {
    SourceLocation where{file_, 0, 0};
    if (node.IsDefined()) {
      const YAML::Mark mark = node.Mark();
      if (mark.line >= 0) where.line = mark.line + 1;
      if (mark.column >= 0) where.column = mark.column + 1;
    }
    throw InputError(problem, key, allowed, where);
  }

  /// The child `name` of map `node`; fails naming the key when missing.
  YAML::Node child(const YAML::Node& node, const std::string& path, const std::string& name) const {
    if (!node.IsMap()) fail(node, path, "expected a map");
    const YAML::Node value = node[name];
    if (!value.IsDefined()) fail(node, path.empty() ? name : path + "." + name, "missing key");
    return value;
  }

  /// Fails when `node` has a key not in `allowed`.
  void check_keys(const YAML::Node& node, const std::string& path, const std::vector<std::string>& allowed) const {
    if (!node.IsMap()) fail(node, path, "expected a map");
    for (const auto& entry : node) {
      const std::string key = entry.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(entry.first, path.empty() ? key : path + "." + key, "unknown key", list);
      }
    }
  }

  double number(const YAML::Node& node, const std::string& key, double lo, double hi) const {
    if (!node.IsScalar()) fail(node, key, "expected a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, key, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!(value >= lo && value <= hi)) fail(node, key, fmt::format("value {} out of range", value), fmt::format("{}…{}", lo, hi));
    return value;
  }

 private:
  std::string file_;
};

/// A named scalar field of a parameter section with its allowed range.
struct Field {
  std::string name;
  double* value;
  double lo;
  double hi;
};

void read_fields(const Reader& r, const YAML::Node& section, const std::string& path, std::vector<Field> fields,
                 const std::vector<std::string>& extra_keys = {}) {
  std::vector<std::string> allowed = extra_keys;
  for (const auto& f : fields) allowed.push_back(f.name);
  r.check_keys(section, path, allowed);
  for (const auto& f : fields) *f.value = r.number(r.child(section, path, f.name), path + "." + f.name, f.lo, f.hi);
}

std::vector<std::string> label_list(Axis axis) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < label_count(axis); ++i) out.emplace_back(label_name(axis, i));
  return out;
}

/// A map label → number covering every label of `axis` (required) or some labels (optional, others stay).
void read_label_map(const Reader& r, const YAML::Node& node, const std::string& path, Axis axis,
                    std::array<double, kMaxLabels>& out, double lo, double hi, bool require_all) {
  r.check_keys(node, path, label_list(axis));
  for (std::size_t i = 0; i < label_count(axis); ++i) {
    const std::string name(label_name(axis, i));
    if (!require_all && !node[name].IsDefined()) continue;
    out[i] = r.number(r.child(node, path, name), path + "." + name, lo, hi);
  }
}

void read_axis(const Reader& r, const YAML::Node& node, const std::string& path, Axis axis, AxisModel& m) {
  r.check_keys(node, path, {"dwell_median_s", "dwell_sigma", "transitions", "bias", "coupling"});
  read_label_map(r, r.child(node, path, "dwell_median_s"), path + ".dwell_median_s", axis, m.dwell_median_s, 0.5,
                 3600.0, true);
  read_label_map(r, r.child(node, path, "dwell_sigma"), path + ".dwell_sigma", axis, m.dwell_sigma, 0.05, 3.0, true);
  read_label_map(r, r.child(node, path, "bias"), path + ".bias", axis, m.bias, -20.0, 20.0, true);
  const YAML::Node transitions = r.child(node, path, "transitions");
  const std::string tpath = path + ".transitions";
  r.check_keys(transitions, tpath, label_list(axis));
  for (std::size_t i = 0; i < label_count(axis); ++i) {
    const std::string from(label_name(axis, i));
    const YAML::Node row = r.child(transitions, tpath, from);
    std::array<double, kMaxLabels> values{};
    read_label_map(r, row, tpath + "." + from, axis, values, 0.0, 1e6, false);
    values[i] = 0.0;
    double total = 0.0;
    for (double v : values) total += v;
    if (!(total > 0.0)) r.fail(row, tpath + "." + from, "a row needs at least one positive weight to another label");
    m.transition[i] = values;
  }
  m.coupling = {};
  if (node["coupling"].IsDefined()) {
    const YAML::Node coupling = node["coupling"];
    const std::string cpath = path + ".coupling";
    r.check_keys(coupling, cpath, label_list(axis));
    std::vector<std::string> features(kFeatureNames.begin(), kFeatureNames.end());
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      const std::string label(label_name(axis, i));
      if (!coupling[label].IsDefined()) continue;
      const YAML::Node row = coupling[label];
      const std::string rpath = cpath + "." + label;
      r.check_keys(row, rpath, features);
      for (std::size_t k = 0; k < kFeatureCount; ++k) {
        const std::string f(kFeatureNames[k]);
        if (row[f].IsDefined()) m.coupling[i][k] = r.number(row[f], rpath + "." + f, -20.0, 20.0);
      }
    }
  }
}

ChildModelParams parse_document(const YAML::Node& root, const Reader& r) {
  ChildModelParams p;
  r.check_keys(root, "", {"version", "session_cap_s", "axes", "drives", "reactions", "motor", "expression", "traits",
                          "partnership", "coder"});
  const double version = r.number(r.child(root, "", "version"), "version", 1, 1);
  (void)version;
  p.session_cap_s = r.number(r.child(root, "", "session_cap_s"), "session_cap_s", 1.0, 86400.0);

  const YAML::Node axes = r.child(root, "", "axes");
  r.check_keys(axes, "axes", {"task_engagement", "social_engagement", "social_attitude"});
  for (const Axis axis : kAxes) {
    const std::string name(axis_name(axis));
    read_axis(r, r.child(axes, "axes", name), "axes." + name, axis, p.axis(axis));
  }

  DriveParams& d = p.drives;
  read_fields(r, r.child(root, "", "drives"), "drives",
              {{"initial_motivation_mean", &d.initial_motivation_mean, 0, 1},
               {"initial_motivation_sd", &d.initial_motivation_sd, 0, 1},
               {"decay_per_min", &d.decay_per_min, 0, 100},
               {"attention_effect", &d.attention_effect, -10, 10},
               {"play_gain_per_min", &d.play_gain_per_min, 0, 100},
               {"contingency_gain", &d.contingency_gain, 0, 1},
               {"unanswered_bid_drop", &d.unanswered_bid_drop, 0, 1},
               {"bid_response_window_s", &d.bid_response_window_s, 0.1, 600},
               {"unfairness_drop", &d.unfairness_drop, 0, 1},
               {"novelty_gain_per_min", &d.novelty_gain_per_min, 0, 100},
               {"novelty_tau_min", &d.novelty_tau_min, 0.01, 1000},
               {"boredom_rate_per_min", &d.boredom_rate_per_min, 0, 100},
               {"quit_hazard_per_min", &d.quit_hazard_per_min, 0, 100},
               {"quit_boredom_slope", &d.quit_boredom_slope, 0, 100},
               {"quit_motivation_slope", &d.quit_motivation_slope, -100, 100},
               {"partner_quit_factor", &d.partner_quit_factor, 1, 1e6},
               {"grievance_tau_s", &d.grievance_tau_s, 0.1, 3600},
               {"attention_tau_s", &d.attention_tau_s, 0.1, 3600}});

  ReactionParams& re = p.reactions;
  read_fields(r, r.child(root, "", "reactions"), "reactions",
              {{"take_reaction_probability", &re.take_reaction_probability, 0, 1},
               {"frustrated_weight", &re.frustrated_weight, 0, 1e3},
               {"adversarial_weight", &re.adversarial_weight, 0, 1e3},
               {"assertive_weight", &re.assertive_weight, 0, 1e3},
               {"retaliation_probability", &re.retaliation_probability, 0, 1},
               {"imitation_probability", &re.imitation_probability, 0, 1},
               {"ownership_memory_s", &re.ownership_memory_s, 0, 3600},
               {"react_distance_m", &re.react_distance_m, 0, 1},
               {"react_window_s", &re.react_window_s, 0, 600},
               {"look_weight", &re.look_weight, 0, 10},
               {"talk_weight", &re.talk_weight, 0, 10},
               {"act_weight", &re.act_weight, 0, 10}});

  MotorParams& m = p.motor;
  const YAML::Node motor = r.child(root, "", "motor");
  read_fields(r, motor, "motor",
              {{"fitts_a_s", &m.fitts_a_s, 0, 10},
               {"fitts_b_s_per_bit", &m.fitts_b_s_per_bit, 0, 10},
               {"age_slowdown_per_year", &m.age_slowdown_per_year, 0, 1},
               {"endpoint_sd_m", &m.endpoint_sd_m, 0, 0.1},
               {"tap_min_s", &m.tap_min_s, 0.01, 5},
               {"tap_max_s", &m.tap_max_s, 0.01, 5},
               {"reach_depth_m", &m.reach_depth_m, 0.05, 1},
               {"reach_per_year_m", &m.reach_per_year_m, 0, 0.1},
               {"action_gap_sigma", &m.action_gap_sigma, 0, 3},
               {"stroke_duration_s", &m.stroke_duration_s, 0.1, 60}},
              {"action_gap_median_s"});
  std::array<double, kMaxLabels> gaps{};
  read_label_map(r, r.child(motor, "motor", "action_gap_median_s"), "motor.action_gap_median_s",
                 Axis::TaskEngagement, gaps, 0.0, 3600.0, true);
  for (std::size_t i = 0; i < 4; ++i) m.action_gap_median_s[i] = gaps[i];
  if (m.tap_max_s < m.tap_min_s) r.fail(motor["tap_max_s"], "motor.tap_max_s", "must be ≥ tap_min_s");

  ExpressionParams& e = p.expression;
  const YAML::Node expression = r.child(root, "", "expression");
  read_fields(r, expression, "expression",
              {{"glance_median_s", &e.glance_median_s, 0.05, 60},
               {"glance_sigma", &e.glance_sigma, 0, 3},
               {"adult_speech_per_min", &e.adult_speech_per_min, 0, 60},
               {"robot_curiosity_per_min", &e.robot_curiosity_per_min, 0, 60},
               {"syllables_mean", &e.syllables_mean, 1, 50},
               {"articulation_rate_at_3", &e.articulation_rate_at_3, 0.5, 10},
               {"articulation_rate_per_year", &e.articulation_rate_per_year, 0, 1}},
              {"partner_face_share", "speech_per_min", "proposal_share"});
  read_label_map(r, r.child(expression, "expression", "partner_face_share"), "expression.partner_face_share",
                 Axis::SocialEngagement, e.partner_face_share, 0.0, 1.0, true);
  read_label_map(r, r.child(expression, "expression", "speech_per_min"), "expression.speech_per_min",
                 Axis::SocialEngagement, e.speech_per_min, 0.0, 60.0, true);
  read_label_map(r, r.child(expression, "expression", "proposal_share"), "expression.proposal_share",
                 Axis::SocialAttitude, e.proposal_share, 0.0, 1.0, true);

  TraitParams& t = p.traits;
  read_fields(r, r.child(root, "", "traits"), "traits",
              {{"sociability_mean", &t.sociability_mean, 0, 1},
               {"sociability_sd", &t.sociability_sd, 0, 1},
               {"assertiveness_mean", &t.assertiveness_mean, 0, 1},
               {"assertiveness_sd", &t.assertiveness_sd, 0, 1},
               {"attention_mean", &t.attention_mean, 0, 1},
               {"attention_sd", &t.attention_sd, 0, 1},
               {"attention_per_year", &t.attention_per_year, -0.5, 0.5}});

  PartnershipParams& pa = p.partnership;
  const YAML::Node partnership = r.child(root, "", "partnership");
  read_fields(r, partnership, "partnership",
              {{"answer_age_logit", &pa.answer_age_logit, -20, 20},
               {"answer_sociability_logit", &pa.answer_sociability_logit, -20, 20},
               {"answer_delay_median_s", &pa.answer_delay_median_s, 0.05, 60},
               {"join_probability", &pa.join_probability, 0, 1},
               {"reciprocity_window_s", &pa.reciprocity_window_s, 0.5, 600},
               {"window_per_year", &pa.window_per_year, -0.5, 0.5},
               {"expectation_prior", &pa.expectation_prior, 0, 1},
               {"expectation_rate", &pa.expectation_rate, 0, 1},
               {"expectation_exponent", &pa.expectation_exponent, 0, 20},
               {"bid_floor", &pa.bid_floor, 0, 1},
               {"watch_window_s", &pa.watch_window_s, 0.5, 600}},
              {"answer_probability"});
  read_label_map(r, r.child(partnership, "partnership", "answer_probability"), "partnership.answer_probability",
                 Axis::SocialEngagement, pa.answer_probability, 0.0, 1.0, true);

  CoderParams& co = p.coder;
  read_fields(r, r.child(root, "", "coder"), "coder",
              {{"answer_window_s", &co.answer_window_s, 0.1, 600},
               {"exchange_hold_s", &co.exchange_hold_s, 0.1, 600},
               {"joint_act_hold_s", &co.joint_act_hold_s, 0.1, 600},
               {"active_window_s", &co.active_window_s, 0.1, 600},
               {"watch_share", &co.watch_share, 0, 1},
               {"watch_window_s", &co.watch_window_s, 0.1, 600},
               {"min_bout_s", &co.min_bout_s, 0, 600},
               {"joint_distance_m", &co.joint_distance_m, 0, 1},
               {"task_min_bout_s", &co.task_min_bout_s, 0, 600},
               {"evidence_hold_s", &co.evidence_hold_s, 0.1, 600},
               {"judgement_window_s", &co.judgement_window_s, 0.1, 600},
               {"play_share", &co.play_share, 0, 1},
               {"friendly_share", &co.friendly_share, 0, 1},
               {"interaction_hold_s", &co.interaction_hold_s, 0.1, 600},
               {"adult_hold_s", &co.adult_hold_s, 0.1, 600},
               {"attitude_min_bout_s", &co.attitude_min_bout_s, 0, 600},
               {"salient_min_bout_s", &co.salient_min_bout_s, 0, 600},
               {"take_window_s", &co.take_window_s, 0.1, 600},
               {"adversarial_hold_s", &co.adversarial_hold_s, 0.1, 600},
               {"frustrated_hold_s", &co.frustrated_hold_s, 0.1, 600},
               {"assertive_hold_s", &co.assertive_hold_s, 0.1, 600}});
  return p;
}


std::string num(double v) { return fmt::format("{}", v); }

void emit_label_map(YAML::Emitter& out, Axis axis, const std::array<double, kMaxLabels>& values, bool skip_zero = false,
                    std::size_t skip = kMaxLabels) {
  out << YAML::Flow << YAML::BeginMap;
  for (std::size_t i = 0; i < label_count(axis); ++i) {
    if (i == skip || (skip_zero && values[i] == 0.0)) continue;
    out << YAML::Key << std::string(label_name(axis, i)) << YAML::Value << num(values[i]);
  }
  out << YAML::EndMap;
}

}  // namespace

ChildModelParams parse_child_model_params(std::string_view yaml_text, const std::string& file) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw InputError(e.msg, "", "", SourceLocation{file, e.mark.line + 1, e.mark.column + 1});
  }
  const Reader reader(file);
  if (!root.IsMap()) reader.fail(root, "", "expected a map of parameter sections");
  return parse_document(root, reader);
}

ChildModelParams load_child_model_params(const std::filesystem::path& path) {
  return parse_child_model_params(read_file(path), path.string());
}

ChildModelParams default_child_model_params() { return load_child_model_params(asset_path("agents/child-model.yaml")); }

std::string child_model_params_to_yaml(const ChildModelParams& p, std::string_view header) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << 1;
  out << YAML::Key << "session_cap_s" << YAML::Value << num(p.session_cap_s);
  out << YAML::Key << "axes" << YAML::Value << YAML::BeginMap;
  for (const Axis axis : kAxes) {
    const AxisModel& m = p.axis(axis);
    out << YAML::Key << std::string(axis_name(axis)) << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "dwell_median_s" << YAML::Value;
    emit_label_map(out, axis, m.dwell_median_s);
    out << YAML::Key << "dwell_sigma" << YAML::Value;
    emit_label_map(out, axis, m.dwell_sigma);
    out << YAML::Key << "bias" << YAML::Value;
    emit_label_map(out, axis, m.bias);
    out << YAML::Key << "transitions" << YAML::Value << YAML::BeginMap;
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      out << YAML::Key << std::string(label_name(axis, i)) << YAML::Value;
      emit_label_map(out, axis, m.transition[i], false, i);
    }
    out << YAML::EndMap;
    out << YAML::Key << "coupling" << YAML::Value << YAML::BeginMap;
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      bool any = false;
      for (double c : m.coupling[i]) any = any || c != 0.0;
      if (!any) continue;
      out << YAML::Key << std::string(label_name(axis, i)) << YAML::Value << YAML::Flow << YAML::BeginMap;
      for (std::size_t k = 0; k < kFeatureCount; ++k) {
        if (m.coupling[i][k] != 0.0) out << YAML::Key << std::string(kFeatureNames[k]) << YAML::Value << num(m.coupling[i][k]);
      }
      out << YAML::EndMap;
    }
    out << YAML::EndMap << YAML::EndMap;
  }
  out << YAML::EndMap;

  const auto section = [&out](const char* name, const std::vector<std::pair<const char*, double>>& fields) {
    out << YAML::Key << name << YAML::Value << YAML::BeginMap;
    for (const auto& [key, value] : fields) out << YAML::Key << key << YAML::Value << num(value);
  };
  const DriveParams& d = p.drives;
  section("drives", {{"initial_motivation_mean", d.initial_motivation_mean},
                     {"initial_motivation_sd", d.initial_motivation_sd},
                     {"decay_per_min", d.decay_per_min},
                     {"attention_effect", d.attention_effect},
                     {"play_gain_per_min", d.play_gain_per_min},
                     {"contingency_gain", d.contingency_gain},
                     {"unanswered_bid_drop", d.unanswered_bid_drop},
                     {"bid_response_window_s", d.bid_response_window_s},
                     {"unfairness_drop", d.unfairness_drop},
                     {"novelty_gain_per_min", d.novelty_gain_per_min},
                     {"novelty_tau_min", d.novelty_tau_min},
                     {"boredom_rate_per_min", d.boredom_rate_per_min},
                     {"quit_hazard_per_min", d.quit_hazard_per_min},
                     {"quit_boredom_slope", d.quit_boredom_slope},
                     {"quit_motivation_slope", d.quit_motivation_slope},
                     {"partner_quit_factor", d.partner_quit_factor},
                     {"grievance_tau_s", d.grievance_tau_s},
                     {"attention_tau_s", d.attention_tau_s}});
  out << YAML::EndMap;
  const ReactionParams& re = p.reactions;
  section("reactions", {{"take_reaction_probability", re.take_reaction_probability},
                        {"frustrated_weight", re.frustrated_weight},
                        {"adversarial_weight", re.adversarial_weight},
                        {"assertive_weight", re.assertive_weight},
                        {"retaliation_probability", re.retaliation_probability},
                        {"imitation_probability", re.imitation_probability},
                        {"ownership_memory_s", re.ownership_memory_s},
                        {"react_distance_m", re.react_distance_m},
                        {"react_window_s", re.react_window_s},
                        {"look_weight", re.look_weight},
                        {"talk_weight", re.talk_weight},
                        {"act_weight", re.act_weight}});
  out << YAML::EndMap;
  const MotorParams& m = p.motor;
  section("motor", {{"fitts_a_s", m.fitts_a_s},
                    {"fitts_b_s_per_bit", m.fitts_b_s_per_bit},
                    {"age_slowdown_per_year", m.age_slowdown_per_year},
                    {"endpoint_sd_m", m.endpoint_sd_m},
                    {"tap_min_s", m.tap_min_s},
                    {"tap_max_s", m.tap_max_s},
                    {"reach_depth_m", m.reach_depth_m},
                    {"reach_per_year_m", m.reach_per_year_m},
                    {"action_gap_sigma", m.action_gap_sigma},
                    {"stroke_duration_s", m.stroke_duration_s}});
  std::array<double, kMaxLabels> gaps{};
  for (std::size_t i = 0; i < 4; ++i) gaps[i] = m.action_gap_median_s[i];
  out << YAML::Key << "action_gap_median_s" << YAML::Value;
  emit_label_map(out, Axis::TaskEngagement, gaps);
  out << YAML::EndMap;
  const ExpressionParams& e = p.expression;
  section("expression", {{"glance_median_s", e.glance_median_s},
                         {"glance_sigma", e.glance_sigma},
                         {"adult_speech_per_min", e.adult_speech_per_min},
                         {"robot_curiosity_per_min", e.robot_curiosity_per_min},
                         {"syllables_mean", e.syllables_mean},
                         {"articulation_rate_at_3", e.articulation_rate_at_3},
                         {"articulation_rate_per_year", e.articulation_rate_per_year}});
  out << YAML::Key << "partner_face_share" << YAML::Value;
  emit_label_map(out, Axis::SocialEngagement, e.partner_face_share);
  out << YAML::Key << "speech_per_min" << YAML::Value;
  emit_label_map(out, Axis::SocialEngagement, e.speech_per_min);
  out << YAML::Key << "proposal_share" << YAML::Value;
  emit_label_map(out, Axis::SocialAttitude, e.proposal_share);
  out << YAML::EndMap;
  const TraitParams& t = p.traits;
  section("traits", {{"sociability_mean", t.sociability_mean},
                     {"sociability_sd", t.sociability_sd},
                     {"assertiveness_mean", t.assertiveness_mean},
                     {"assertiveness_sd", t.assertiveness_sd},
                     {"attention_mean", t.attention_mean},
                     {"attention_sd", t.attention_sd},
                     {"attention_per_year", t.attention_per_year}});
  out << YAML::EndMap;
  const PartnershipParams& pa = p.partnership;
  section("partnership", {{"answer_age_logit", pa.answer_age_logit},
                          {"answer_sociability_logit", pa.answer_sociability_logit},
                          {"answer_delay_median_s", pa.answer_delay_median_s},
                          {"join_probability", pa.join_probability},
                          {"reciprocity_window_s", pa.reciprocity_window_s},
                          {"window_per_year", pa.window_per_year},
                          {"expectation_prior", pa.expectation_prior},
                          {"expectation_rate", pa.expectation_rate},
                          {"expectation_exponent", pa.expectation_exponent},
                          {"bid_floor", pa.bid_floor},
                          {"watch_window_s", pa.watch_window_s}});
  out << YAML::Key << "answer_probability" << YAML::Value;
  emit_label_map(out, Axis::SocialEngagement, pa.answer_probability);
  out << YAML::EndMap;
  const CoderParams& co = p.coder;
  section("coder", {{"answer_window_s", co.answer_window_s},
                    {"exchange_hold_s", co.exchange_hold_s},
                    {"joint_act_hold_s", co.joint_act_hold_s},
                    {"active_window_s", co.active_window_s},
                    {"watch_share", co.watch_share},
                    {"watch_window_s", co.watch_window_s},
                    {"min_bout_s", co.min_bout_s},
                    {"joint_distance_m", co.joint_distance_m},
                    {"task_min_bout_s", co.task_min_bout_s},
                    {"evidence_hold_s", co.evidence_hold_s},
                    {"judgement_window_s", co.judgement_window_s},
                    {"play_share", co.play_share},
                    {"friendly_share", co.friendly_share},
                    {"interaction_hold_s", co.interaction_hold_s},
                    {"adult_hold_s", co.adult_hold_s},
                    {"attitude_min_bout_s", co.attitude_min_bout_s},
                    {"salient_min_bout_s", co.salient_min_bout_s},
                    {"take_window_s", co.take_window_s},
                    {"adversarial_hold_s", co.adversarial_hold_s},
                    {"frustrated_hold_s", co.frustrated_hold_s},
                    {"assertive_hold_s", co.assertive_hold_s}});
  out << YAML::EndMap;
  out << YAML::EndMap;
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
  text += out.c_str();
  text += "\n";
  return text;
}

}  // namespace freeplay::agents
