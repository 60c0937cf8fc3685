#pragma once
// The robot's play policy interface: observations hold only what the real robot could sense; actions are the
// real system's outputs (move_sandbox_items goals, gaze, pointing, speech, waiting).
//
// Boundary: this library links only freeplay_core. It cannot see the children's internal state (agents) or the
// game's internals (sim): everything arrives through `Observation`, filled by the episode loop from sensors.

#include <yaml-cpp/yaml.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "freeplay/core/geometry.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::policies {

/// An item as the robot sees it on `/tf` (pose) plus what the game's touch frames reveal.
struct ItemObservation {
  std::string name;              ///< TF frame name
  Pose2 pose;                    ///< centre in `sandtray`
  bool touched_by_child = false; ///< a `touchN` frame lies on it (a child is dragging it)
  bool held_by_robot = false;    ///< the robot's finger is dragging it
  bool visible = true;           ///< shown on screen (hidden items still publish TF)
};

/// A colour zone from `/zones` (name = colour, polygon and vertex-mean centroid in `sandtray`).
struct ZoneObservation {
  std::string colour;  ///< "green", "blue", …
  Polygon2 polygon;    ///< closed polygon, last vertex not repeated
  Vec2 centroid;       ///< vertex mean, as the real play node computes it
};

/// An active finger on the screen (`touchN` frames).
struct TouchObservation {
  int finger = 0;     ///< 1…6
  Vec2 position;      ///< in `sandtray`
};

/// Where a perceived child seems to look (from head pose, as gazr would estimate it).
enum class PerceivedGaze { Unknown, Robot, Partner, Screen, Away };

/// A child as the robot's perception pipeline reports it (noisy, late, sometimes missing).
struct PerceivedChild {
  std::string seat;                    ///< "purple" or "yellow"
  bool face_detected = false;          ///< face found in this frame
  PerceivedGaze gaze = PerceivedGaze::Unknown;  ///< estimated gaze target
  std::optional<Vec2> gaze_on_screen;  ///< estimated gaze point on the screen, when looking at it
  bool speaking = false;               ///< voice activity detected
  bool addressing_robot = false;       ///< speech seems addressed to the robot (gaze at robot while speaking)
  double seconds_since_touch = 1e9;    ///< time since this child's last touch began
  std::optional<std::string> moving_item;  ///< item this child is dragging, if any
};

/// The robot's own state (proprioception and its action server's feedback).
struct RobotSelf {
  bool moving_item = false;     ///< a move_sandbox_items goal is running
  std::string current_item;     ///< item being moved
  bool speaking = false;        ///< a Say is running
  Vec2 arm_reach_centre;        ///< RShoulder projected on the table (`arm_reach` frame x, y)
  double arm_reach_radius = 0;  ///< radius of the reachable disc at table level (`arm_reach` frame z)
  bool arm_reach_known = false; ///< the `arm_reach` frame is published (robot localised)
};

/// Everything a policy may observe at one decision tick.
struct Observation {
  double t = 0.0;                                ///< simulated seconds since the start of free play
  std::vector<ItemObservation> items;            ///< every item's TF
  std::vector<ZoneObservation> zones;            ///< current `/zones`
  std::vector<TouchObservation> touches;         ///< active fingers
  std::vector<std::string> interaction_events;   ///< `sandtray/interaction_events` since the last tick
  std::vector<PerceivedChild> children;          ///< perceived children (empty for a policy that does not perceive)
  RobotSelf self;                                ///< own state

  /// The observation of item `name`, or nullptr.
  const ItemObservation* item(const std::string& name) const;
};

/// Start a `move_sandbox_items` goal: drag `item` to `target` (in `sandtray`).
struct MoveItem {
  std::string item;  ///< item name
  Vec2 target;       ///< goal point
};
/// Look at a point in `sandtray` (z above the screen) or at a child's face.
struct LookAt {
  std::optional<Eigen::Vector3d> point;  ///< a 3-D point in `sandtray`
  std::optional<std::string> child;      ///< "purple"/"yellow": look at that child's face
};
/// Point at a screen point with the right arm.
struct PointAt {
  Vec2 point;  ///< in `sandtray`
};
/// Say something (its duration follows from the articulation rate).
struct Say {
  std::string text;        ///< utterance
  std::string addressee;   ///< "purple", "yellow" or "" (both)
};
/// Do nothing new for a while.
struct Wait {
  double seconds = 0.0;  ///< how long
};
/// Cancel the running move (pre-emption: the item stays, the 1 s auto-release follows).
struct CancelMove {};

/// One action a policy asks for.
using Action = std::variant<MoveItem, LookAt, PointAt, Say, Wait, CancelMove>;

/// How a finished action ended.
struct ActionResult {
  enum class Kind { MoveSucceeded, MoveFailed, MoveCancelled, SpeechFinished } kind = Kind::MoveSucceeded;  ///< outcome
  std::string item;     ///< for moves
  std::string reason;   ///< failure reason (planner, unreachable, …)
};

/// What a policy is told once per episode.
struct PolicyContext {
  std::string robot_seat = "yellow";  ///< the robot replaces the yellow child
  std::vector<std::string> item_names;  ///< every item of the game
  int episode_index = 0;                ///< index of the episode in its run (a yoked policy replays that episode)
};

/// A robot play policy, called at the decision rate (10 Hz) by the episode loop.
class PlayPolicy {
 public:
  virtual ~PlayPolicy() = default;
  /// Registered name.
  virtual std::string name() const = 0;
  /// Prepares for a new episode with its own random stream.
  virtual void reset(const PolicyContext& context, Rng rng) = 0;
  /// Decides at one tick: returns the actions to start now (often none).
  virtual std::vector<Action> decide(const Observation& observation) = 0;
  /// Reports the end of a move or an utterance.
  virtual void on_result(const ActionResult& result) { (void)result; }
  /// True when the policy uses perceived children (an asocial policy does not: perception can be skipped).
  virtual bool perceives_children() const { return false; }
  /// Checks, before a run starts, that the policy can play episodes 0 … `episodes` − 1 (a yoked policy needs its
  /// source's episodes); throws InputError naming what is missing.
  virtual void check_run(int episodes) const { (void)episodes; }
};

/// Builds a policy from its validated parameters.
using PolicyFactory = std::function<std::unique_ptr<PlayPolicy>(const YAML::Node& params)>;

/// One registered policy.
struct PolicyInfo {
  std::string name;         ///< e.g. "asocial"
  std::string description;  ///< one line
  PolicyFactory make;       ///< factory
};

/// All registered policies, by name.
const std::vector<PolicyInfo>& registered_policies();
/// Registers a policy (use FREEPLAY_REGISTER_POLICY). Returns true so it can initialise a static.
bool register_policy(PolicyInfo info);
/// Creates the policy `name`; throws InputError listing the registered names when unknown.
std::unique_ptr<PlayPolicy> make_policy(const std::string& name, const YAML::Node& params = {});
/// Names of every registered policy.
std::vector<std::string> policy_names();

/// Builds a policy of a family from its full name (e.g. "python:module:Class") and its parameters.
using PolicyFamilyFactory = std::function<std::unique_ptr<PlayPolicy>(const std::string& name, const YAML::Node& params)>;
/// The prefix of the names of policies written in Python ("python:module:Class"); only the Python module builds them.
inline constexpr const char* kPythonPolicyPrefix = "python:";
/// Installs the builder of every policy whose name starts with `prefix` (a front such as the Python module calls
/// it before running episodes); replaces an earlier builder of the same prefix.
void register_policy_family(std::string prefix, PolicyFamilyFactory make);
/// Name patterns a scenario may use besides the registered names ("python:*": accepted by every front, built only
/// where a family builder is installed).
std::vector<std::string> policy_name_patterns();
/// Throws InputError when this program cannot build policy `name` (unknown, or a Python policy outside Python).
void check_policy_available(const std::string& name);

/// Registers `Class` (constructible from `const YAML::Node&`) under `name`: one line per new policy.
#define FREEPLAY_REGISTER_POLICY(Class, name, description)                                                   \
  static const bool freeplay_policy_registered_##Class = ::freeplay::policies::register_policy(             \
      {name, description, [](const YAML::Node& params) -> std::unique_ptr<::freeplay::policies::PlayPolicy> { \
         return std::make_unique<Class>(params);                                                             \
       }})

}  // namespace freeplay::policies
