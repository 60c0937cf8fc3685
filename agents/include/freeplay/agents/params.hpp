#pragma once
// The child model's parameters (immutable, loaded and validated from assets/agents/child-model.yaml). Each struct's
// `visit` lists its keys and ranges once (core/settings_archive.hpp); the lists are defined in agents/src/params.cpp,
// the one place that reads and writes the YAML, so this header stays free of YAML.

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "freeplay/agents/labels.hpp"

namespace freeplay::agents {

/// What the label transition weights of a child depend on (each feature is roughly in [−1, 1]).
enum class Feature : std::uint8_t {
  Motivation,        ///< motivation drive − 0.5
  Age,               ///< (age − 6) / 2
  Sociability,       ///< 2 × sociability − 1
  Assertiveness,     ///< 2 × assertiveness − 1
  Tablet,            ///< tablet familiarity − 1 (0 when unknown)
  PartnerActive,     ///< how much the partner has been touching the screen lately, [0, 1]
  PartnerJoint,      ///< how much the partner has been acting where I act lately, [0, 1]
  PartnerAttention,  ///< how much the partner has lately answered my bids by looking at me or talking to me, [0, 1]
  Grievance,         ///< recent unfairness (items taken from me), [0, 1]
  TaskNoPlay,        ///< 1 while my task engagement is `noplay`
  Together,          ///< 1 while my social engagement is `associative` or `cooperative`
  Count
};

/// Number of features.
inline constexpr std::size_t kFeatureCount = static_cast<std::size_t>(Feature::Count);

/// The semi-Markov process of one axis: log-normal dwell times and feature-modulated transition weights.
struct AxisModel {
  std::array<double, kMaxLabels> dwell_median_s{};  ///< median bout duration per label (s)
  std::array<double, kMaxLabels> dwell_sigma{};     ///< log-normal σ of the bout duration per label
  std::array<std::array<double, kMaxLabels>, kMaxLabels> transition{};  ///< base weight row → column (diag unused)
  std::array<double, kMaxLabels> bias{};            ///< fitted log-weight offset of entering each label
  std::array<std::array<double, kFeatureCount>, kMaxLabels> coupling{};  ///< log-weight per label and feature

  /// The keys of `axes.<axis>:` with their ranges, a value per label of `axis` (params.cpp).
  template <typename Archive>
  void visit(Archive& a, Axis axis);
  /// Equal when every parameter is.
  bool operator==(const AxisModel&) const = default;
};

/// Slow latent drives and the quit hazard they set.
struct DriveParams {
  double initial_motivation_mean = 0.8;   ///< motivation at the start of the session (mean)
  double initial_motivation_sd = 0.1;     ///< spread of the initial motivation across children
  double decay_per_min = 0.2;             ///< motivation decay rate without stimulation (1/min)
  double attention_effect = 0.5;          ///< decay × exp(−attention_effect × (2·attention_span − 1))
  double play_gain_per_min = 0.1;         ///< sustaining effect of own goal-oriented play (1/min, × (1 − M))
  double contingency_gain = 0.05;         ///< motivation rise per contingent partner response (× contingency × (1 − M))
  double unanswered_bid_drop = 0.02;      ///< motivation fall when a bid to the partner gets no response (× M)
  double unfairness_drop = 0.1;           ///< motivation fall when an item is taken from me (× M)
  double novelty_gain_per_min = 0.3;      ///< stimulation from a robot partner at t = 0 (1/min, × (1 − M))
  double novelty_tau_min = 4.0;           ///< time constant of the robot's novelty wearing off (min)
  double boredom_rate_per_min = 0.05;     ///< boredom growth rate × (1 − M) (1/min)
  double quit_hazard_per_min = 0.01;      ///< quit hazard at zero boredom and M = 0.5 (1/min)
  double quit_boredom_slope = 1.0;        ///< hazard × exp(slope × boredom)
  double quit_motivation_slope = 2.0;     ///< hazard × exp(−slope × (M − 0.5))
  double partner_quit_factor = 20.0;      ///< hazard multiplier once the partner has announced it wants to stop
  double grievance_tau_s = 60.0;          ///< decay time of the grievance memory (s)
  double attention_tau_s = 30.0;          ///< averaging time of the partner-behaviour features (s)

  /// The keys of `drives:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const DriveParams&) const = default;
};

/// Reactions to what the partner does.
struct ReactionParams {
  double take_reaction_probability = 0.6;  ///< chance an item taken from me switches my attitude at once
  double unanswered_frustration_probability = 0.0;  ///< chance a bid of mine left unanswered makes me frustrated
  double frustrated_weight = 1.0;          ///< weight of `frustrated` in that switch
  double adversarial_weight = 0.5;         ///< weight of `adversarial` (× exp(assertiveness feature))
  double assertive_weight = 1.0;           ///< weight of `assertive` (× exp(assertiveness feature))
  double retaliation_probability = 0.3;    ///< chance an adversarial child takes back/away a partner item
  double imitation_probability = 0.3;      ///< chance a parallel child copies the partner's last kind of action
  double ownership_memory_s = 90.0;        ///< how long an item I placed still feels like mine (s)
  double look_weight = 0.4;                ///< contingency weight of the partner looking at me
  double talk_weight = 0.7;                ///< contingency weight of the partner talking to me
  double act_weight = 1.0;                 ///< contingency weight of the partner acting on my play

  /// The keys of `reactions:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const ReactionParams&) const = default;
};

/// Touch kinematics and action pacing.
struct MotorParams {
  double fitts_a_s = 0.3;              ///< Fitts intercept at 6 years (s)
  double fitts_b_s_per_bit = 0.25;     ///< Fitts slope at 6 years (s/bit)
  double age_slowdown_per_year = 0.12; ///< duration × (1 + slowdown × (6 − age)) for younger children
  double endpoint_sd_m = 0.004;        ///< end-point scatter of drags and taps (m)
  double tap_min_s = 0.10;             ///< shortest tap contact (s)
  double tap_max_s = 0.20;             ///< longest tap contact (s)
  double reach_depth_m = 0.22;         ///< reachable depth from the child's long side at 6 years (m)
  double reach_per_year_m = 0.015;     ///< extra reach per year of age (m)
  std::array<double, 4> action_gap_median_s{3.0, 2.5, 12.0, 0.0};  ///< median pause between actions per task label (0 = none)
  double action_gap_sigma = 0.8;       ///< log-normal σ of the pause
  double stroke_duration_s = 2.0;      ///< median duration of a drawing stroke (s)

  /// The keys of `motor:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const MotorParams&) const = default;
};

/// Gaze and speech behaviour.
struct ExpressionParams {
  double glance_median_s = 1.5;                     ///< median duration of one gaze fixation (s)
  double glance_sigma = 0.6;                        ///< log-normal σ of a fixation
  std::array<double, 5> partner_face_share{0.05, 0.10, 0.08, 0.15, 0.22};  ///< P(look at partner) per social label
  std::array<double, 5> speech_per_min{0.4, 0.3, 1.0, 3.0, 4.0};          ///< utterances to the partner per social label
  double adult_speech_per_min = 3.0;                ///< utterances to the experimenter while adult seeking
  double robot_curiosity_per_min = 2.0;             ///< extra utterances to a robot at t = 0 (wears off with novelty)
  double robot_novelty_face_share = 0.3;            ///< extra P(look at a robot partner) at t = 0, wearing off with
                                                    ///< novelty (Kanda et al. 2004; Tanaka et al. 2007)
  double noplay_watch_share = 0.5;                  ///< P(a child out of the game watches where the partner just played)
  double noplay_speech_share = 1.0;                 ///< a child out of the game talks to (and answers) its partner at this share of its rate
  double syllables_mean = 6.0;                      ///< mean syllables per utterance
  double articulation_rate_at_3 = 2.7;              ///< syllables/s at 3 years
  double articulation_rate_per_year = 0.12;         ///< increase per year (3.3 at 8 years)
  std::array<double, 5> proposal_share{0.3, 0.3, 0.7, 0.1, 0.1};  ///< share of proposals among utterances to the partner, per own social attitude

  /// The keys of `expression:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const ExpressionParams&) const = default;
};

/// How the personality traits of a sampled child are distributed (normal, clamped to [0, 1]).
struct TraitParams {
  double sociability_mean = 0.5;        ///< mean sociability
  double sociability_sd = 0.2;          ///< spread of sociability
  double assertiveness_mean = 0.5;      ///< mean assertiveness
  double assertiveness_sd = 0.2;        ///< spread of assertiveness
  double attention_mean = 0.5;          ///< mean attention span at 6 years
  double attention_sd = 0.2;            ///< spread of attention span
  double attention_per_year = 0.06;     ///< attention span gained per year of age

  /// The keys of `traits:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const TraitParams&) const = default;
};

/// Reciprocity: how a child answers its partner's bids and how joint play depends on being answered.
struct PartnershipParams {
  std::array<double, 5> answer_probability{0.25, 0.45, 0.45, 0.85, 0.9};  ///< P(answer a bid) per own social label
  double answer_age_logit = 0.4;        ///< logit shift of answering per (age − 6)/2
  double answer_sociability_logit = 0.8;///< logit shift of answering per (2·sociability − 1)
  double answer_delay_median_s = 1.0;   ///< median delay of an answer (children answer slower than adults' 200 ms)
  double join_probability = 0.8;        ///< chance that answering a joint bid also joins the bidder's joint play
  double reciprocity_window_s = 10.0;   ///< joint play ends when the partner has not answered for this long (s, 6 y)
  double window_per_year = 0.15;        ///< relative change of that window per year of age (older sustain longer)
  double expectation_exponent = 2.0;    ///< joint-play transition weights × contingency^exponent
  double bid_floor = 0.2;               ///< bid rates × (floor + (1 − floor) × contingency)
  double watch_window_s = 4.0;          ///< onlooking ends when the partner has not acted for this long (s)
  double onlooking_after_s = 8.0;       ///< watching the partner's play this long without acting is onlooking (s)

  /// The keys of `partnership:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const PartnershipParams&) const = default;
};

/// Contingency detection (docs/agents.md, "Contingency"): when a partner's act answers a bid, how the child
/// estimates the partner's contingency, habituation to non-contingent attention, and interruptions of its play.
struct ContingencyParams {
  double response_window_s = 3.0;       ///< a partner act answers my bid only within this time after it (s)
  double about_distance_m = 0.12;       ///< a partner act on the tray this close to my act is about it (m)
  double memory_s = 300.0;              ///< forgetting time constant of the bid and base-rate counts (s)
  double prior_bids = 2.0;              ///< weight of the prior answered share, in bids
  double prior_answered_share = 0.5;    ///< prior P(a bid is answered)
  double prior_free_time_s = 20.0;      ///< weight of the prior base rate, in seconds of probe windows
  double prior_base_rate_per_min = 3.0; ///< prior rate of the partner's acts that could answer me (1/min)
  double prior_link_probability = 0.5; ///< prior P(the partner responds to me at all), before any evidence
  double non_contingent_weight = 0.3;   ///< motivating effect of fresh non-contingent attention, relative to a response
  double habituation_rate = 0.3;        ///< each non-contingent stimulus multiplies its salience by (1 − rate)
  double habituation_recovery_s = 600.0;///< salience recovers towards 1 with this time constant (s)
  double interruption_tau_s = 60.0;     ///< time constant of the interruption level (s)
  double interruption_threshold = 4.0;  ///< interruption level tolerated before each further one lowers motivation
  double interruption_drop = 0.05;      ///< motivation fall per interruption above the threshold (× M)

  /// The keys of `contingency:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const ContingencyParams&) const = default;
};

/// The coder (annotator): how observable behaviour becomes labels (docs/agents.md, "The coder").
struct CoderParams {
  double answer_window_s = 5.0;      ///< words to the other within this time after its words answer them (s)
  double follow_window_s = 10.0;     ///< an act on what the other just moved, or at the spot it just played, within
                                     ///< this time follows its activity (s)
  double joint_distance_m = 0.08;    ///< a spot this close to the other's is the other's spot (m)
  double talk_play_window_s = 10.0;  ///< words to the other are about the play while either played this recently (s)
  double interaction_window_s = 20.0;///< associative: the child's acts of interaction are judged over this window (s)
  double cooperation_window_s = 20.0;///< cooperative: turn-taking on one scene is judged over this window (s)
  double cooperation_hold_s = 10.0; ///< cooperation goes on while both followed or spoke to the other this recently (s)
  double discussion_hold_s = 10.0;   ///< taking part in talk about what to do next shows cooperation this long (s)
  double active_window_s = 6.0;      ///< a child touched the screen within this time counts as playing (s)
  double watch_share = 0.5;          ///< share of the last `watch_window_s` spent watching the other's play
  double watch_window_s = 4.0;       ///< window of that share (s)
  double min_bout_s = 3.0;           ///< a new label must hold this long before the coder switches to it (s)
  double task_min_bout_s = 4.5;      ///< task engagement: a new label must hold this long before the coder switches (s)
  double stroke_min_s = 0.4;         ///< a touch on the map held this long draws (in the last colour picked) (s)
  double evidence_hold_s = 3.0;      ///< an act (a drag, a scribble, a friendly word) counts as recent this long (s)
  double judgement_window_s = 10.0;  ///< the coder judges play and attitude over running shares of this window (s)
  double play_share = 0.2;           ///< below this running share of recent play (of any kind) a child is not playing
  double friendly_share = 0.3;       ///< from this running share of recent friendly acts on, the attitude is prosocial
  double interaction_hold_s = 20.0;  ///< an act of interaction shows a prosocial (or assertive) attitude this long (s)
  double adult_hold_s = 5.0;         ///< a look or a word to the experimenter shows adult seeking this long (s)
  double attitude_min_bout_s = 6.0;  ///< social attitude: a new label must hold this long before the coder switches (s)
  double salient_min_bout_s = 2.0;   ///< the same for the salient attitudes, frustrated and adversarial (s)
  double anchoring = 0.0;            ///< a new label must also hold this share of the bout it ends (long bouts anchor)
  double take_window_s = 10.0;       ///< an item the other player held this recently is still the other's (s)
  double adversarial_hold_s = 6.0;   ///< taking the other's item shows an adversarial attitude this long (s)
  double frustrated_hold_s = 3.0;    ///< a protest shows frustration this long (s)
  double assertive_hold_s = 6.0;     ///< a proposal or request to the other (directing its play) shows assertiveness (s)

  /// The keys of `coder:` with their ranges (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const CoderParams&) const = default;
};

/// Every parameter of the child model (immutable once loaded).
struct ChildModelParams {
  std::array<AxisModel, kAxisCount> axes{};  ///< indexed by Axis
  DriveParams drives;                        ///< latent drives and quit hazard
  ReactionParams reactions;                  ///< reactions to the partner
  MotorParams motor;                         ///< touches
  ExpressionParams expression;               ///< gaze and speech
  TraitParams traits;                        ///< personality traits of sampled children
  PartnershipParams partnership;             ///< reciprocity and answering
  ContingencyParams contingency;             ///< contingency detection, habituation, interruptions
  CoderParams coder;                         ///< the annotator's rules
  double session_cap_s = 2400.0;             ///< the protocol's 40-minute cap (s)

  /// The axis model of `axis`.
  const AxisModel& axis(Axis a) const { return axes[static_cast<std::size_t>(a)]; }
  /// Mutable axis model of `axis` (used by the fitting procedure).
  AxisModel& axis(Axis a) { return axes[static_cast<std::size_t>(a)]; }

  /// The keys of the whole file (params.cpp).
  template <typename Archive>
  void visit(Archive& a);
  /// Equal when every parameter is.
  bool operator==(const ChildModelParams&) const = default;
};

/// Parses and validates parameters from YAML text; `file` names the source in errors (InputError file:line:col).
ChildModelParams parse_child_model_params(std::string_view yaml_text, const std::string& file = "<string>");
/// Loads and validates a parameter file.
ChildModelParams load_child_model_params(const std::filesystem::path& path);
/// Loads the shipped parameters (assets/agents/child-model.yaml).
ChildModelParams default_child_model_params();
/// The parameters as YAML text that `parse_child_model_params` reads back identically; `header` becomes a comment.
std::string child_model_params_to_yaml(const ChildModelParams& params, std::string_view header = {});

}  // namespace freeplay::agents
