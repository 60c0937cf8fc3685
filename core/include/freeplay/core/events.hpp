#pragma once
// The typed events of the game and the episode: one struct per event type, each with its event-log name (kType) and
// the fields of its `data` object. An Event carries one of them (EventPayload); its JSON is written from the struct,
// byte for byte what the string-typed events wrote (README, `events/<episode>.jsonl`).

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace freeplay::events {

// --- the game (source "sandtray") ---

/// A finger or the robot takes hold of an item; `finger` is empty for the robot's virtual finger.
struct ItemGrabbed {
  static constexpr std::string_view kType = "item_grabbed";  ///< its event-log type
  std::string item;                      ///< the item's name
  std::optional<int> finger;             ///< the touch's finger (1…6); empty: the robot holds it
  std::vector<std::string> shared_with;  ///< the other holders: "robot" or a touch frame ("touch3")
};

/// A finger or the robot lets go of an item; `finger` is empty for the robot's virtual finger.
struct ItemReleased {
  static constexpr std::string_view kType = "item_released";  ///< its event-log type
  std::string item;           ///< the item's name
  std::optional<int> finger;  ///< the touch's finger (1…6); empty: the robot held it
  std::string reason;         ///< why, e.g. "touch_up"
};

/// A finger starts a stroke on the background.
struct StrokeStarted {
  static constexpr std::string_view kType = "stroke_started";  ///< its event-log type
  int finger = 0;       ///< the touch's finger
  std::string colour;   ///< the palette colour's name
};

/// A finger ends its stroke.
struct StrokeFinished {
  static constexpr std::string_view kType = "stroke_finished";  ///< its event-log type
  int finger = 0;  ///< the touch's finger
};

/// A message the game publishes on /sandtray/interaction_events (e.g. `releasing_zebra`).
struct InteractionEvent {
  static constexpr std::string_view kType = "interaction_event";  ///< its event-log type
  std::string message;  ///< the message
};

/// Drawing on the background is switched on or off.
struct BackgroundDrawing {
  static constexpr std::string_view kType = "background_drawing";  ///< its event-log type
  bool enabled = false;  ///< drawing is on
};

/// The game publishes a new background image.
struct BackgroundPublished {
  static constexpr std::string_view kType = "background_published";  ///< its event-log type
  std::uint64_t version = 0;  ///< the background's version (1, 2, …)
};

/// The game's state changes.
struct StateChanged {
  static constexpr std::string_view kType = "state_changed";  ///< its event-log type
  std::string state;  ///< the new state's name
};

/// The game handles a signal of /sandtray/signals.
struct GameSignal {
  static constexpr std::string_view kType = "signal";  ///< its event-log type
  std::string name;  ///< the signal's name
};

// --- a child (source "child.<seat>") ---

/// A child taps a palette swatch.
struct Palette {
  static constexpr std::string_view kType = "palette";  ///< its event-log type
  std::string colour;  ///< the colour's name
};

/// A child's touch lands off the screen.
struct TouchMissed {
  static constexpr std::string_view kType = "touch_missed";  ///< its event-log type
  double x = 0.0;  ///< where (m, sandtray frame)
  double y = 0.0;  ///< where (m, sandtray frame)
};

/// A child's finger goes down on the screen.
struct TouchDown {
  static constexpr std::string_view kType = "touch_down";  ///< its event-log type
  int finger = 0;       ///< the touch's finger (1…6)
  double x = 0.0;       ///< where (m, sandtray frame)
  double y = 0.0;       ///< where (m, sandtray frame)
  std::string outcome;  ///< "item", "stroke" or "ignored"
};

/// A child's finger lifts.
struct TouchUp {
  static constexpr std::string_view kType = "touch_up";  ///< its event-log type
  int finger = 0;  ///< the touch's finger (1…6)
};

/// A child speaks.
struct ChildSpeech {
  static constexpr std::string_view kType = "speech";  ///< its event-log type
  std::string kind;         ///< the utterance's kind
  std::string to;           ///< the addressee
  double duration_s = 0.0;  ///< how long
  int syllables = 0;        ///< how many syllables
};

/// A child's gaze target changes.
struct ChildGaze {
  static constexpr std::string_view kType = "gaze";  ///< its event-log type
  std::string target;                ///< the gaze kind's name ("away", "partner", "item", …)
  std::optional<std::string> item;   ///< the item looked at, for an item gaze
};

/// A child wants to stop playing.
struct WantsToStop {
  static constexpr std::string_view kType = "wants_to_stop";  ///< its event-log type
};

// --- the robot (source "robot") ---

/// The robot says something (also the experimenter's `say`).
struct Say {
  static constexpr std::string_view kType = "say";  ///< its event-log type
  std::string text;         ///< what is said
  std::string to;           ///< to whom ("" for nobody in particular)
  double duration_s = 0.0;  ///< how long
};

/// The robot starts moving an item.
struct MoveGoal {
  static constexpr std::string_view kType = "move_goal";  ///< its event-log type
  std::string item;  ///< the item
  double x = 0.0;    ///< the target (m, sandtray frame)
  double y = 0.0;    ///< the target (m, sandtray frame)
};

/// The robot looks at a child's face or at a point (and the item there, if any).
struct LookAt {
  static constexpr std::string_view kType = "look_at";  ///< its event-log type
  std::optional<std::string> child;  ///< the child's seat; when set, no point
  double x = 0.0;                    ///< the point (m, sandtray frame)
  double y = 0.0;                    ///< the point (m, sandtray frame)
  double z = 0.0;                    ///< the point (m, sandtray frame)
  std::optional<std::string> item;   ///< the item at the point
};

/// The robot points at a point of the screen.
struct PointAt {
  static constexpr std::string_view kType = "point_at";  ///< its event-log type
  double x = 0.0;  ///< the point (m, sandtray frame)
  double y = 0.0;  ///< the point (m, sandtray frame)
};

/// The robot's running action is cancelled.
struct Cancel {
  static constexpr std::string_view kType = "cancel";  ///< its event-log type
};

/// The robot's move ends: how, and what the move executor measured (docs/planning.md); the optional measures are
/// present when there is something to measure.
struct MoveResult {
  static constexpr std::string_view kType = "move_result";  ///< its event-log type
  std::string item;                         ///< the item
  std::string status;                       ///< how it ended (planning::move_status_name)
  std::string reason;                       ///< why it failed ("" when it did not)
  bool target_in_reach = false;             ///< the target lies in the arm's reach
  std::size_t poses = 0;                    ///< finger poses sent
  std::optional<double> path_length_m;      ///< the plan's length (when a plan was found)
  std::optional<double> min_clearance_mm;   ///< the plan's smallest clearance (when a plan was found)
  std::optional<double> sync_error_mm_mean;  ///< mean finger-to-pose distance (when the arm followed poses)
  std::optional<double> sync_error_mm_max;   ///< largest finger-to-pose distance (same)
  std::optional<double> sync_lag_ms;         ///< lag of the arm behind the poses (same)
  std::optional<double> duration_s;          ///< time from the first to the last pose (when poses were sent)
  bool stolen_by_child = false;             ///< a child took the item during the move
};

// --- a controller scenario (source "controller") ---

/// A target of a controller scenario starts.
struct TargetStart {
  static constexpr std::string_view kType = "target_start";  ///< its event-log type
  std::size_t index = 0;  ///< its place in the sequence
  std::string kind;       ///< "point", "look", "move", "posture" or "wait"
};

/// A target of a controller scenario ends, with what was measured; which measures are present depends on its kind
/// (docs/controller.md).
struct TargetEnd {
  static constexpr std::string_view kType = "target_end";  ///< its event-log type
  std::size_t index = 0;                       ///< its place in the sequence
  std::string kind;                            ///< "point", "look", "move", "posture" or "wait"
  double t_start = 0.0;                        ///< when it started (s)
  double t_end = 0.0;                          ///< when it ended (s)
  std::optional<std::vector<double>> point;    ///< point: the screen point (m)
  std::optional<bool> reachable;               ///< point: the arm's IK reached it
  std::optional<double> ik_error_mm;           ///< point: the IK's fingertip error
  std::optional<std::vector<double>> look;     ///< look: the gaze point (m)
  std::optional<bool> clamped;                 ///< look: the head's limits clamped the gaze
  std::optional<double> gaze_error_deg;        ///< look: angle between the gaze and the point
  std::optional<std::string> posture;          ///< posture: its NAOqi name
  std::optional<double> joint_error_rad;       ///< posture: the joints' error to it
  std::optional<double> wait_s;                ///< wait: how long
  std::optional<std::string> item;             ///< move: the item
  std::optional<std::vector<double>> to;       ///< move: the target (m)
  std::optional<std::string> status;           ///< move: how the move ended
  std::optional<std::string> reason;           ///< move: why it failed
  std::optional<std::size_t> poses;            ///< move: finger poses sent
  std::optional<double> error_mm;              ///< point, move: the fingertip's error once settled
  std::optional<double> sync_error_mm_mean;    ///< move: mean finger-to-pose distance
  std::optional<double> sync_error_mm_max;     ///< move: largest finger-to-pose distance
  std::optional<double> sync_lag_ms;           ///< move: lag of the arm behind the poses
  std::optional<std::size_t> unreachable_poses;  ///< move: poses the arm could not reach
  std::optional<double> placement_error_mm;    ///< move: the item's distance to the target once released (NaN: not)
  std::optional<bool> settled;                 ///< point, look, posture, move: the robot settled in time
  std::optional<double> settle_s;              ///< when it settled (NaN: it did not)
};

// --- the protocol (source "protocol") ---

/// A protocol stage starts.
struct Stage {
  static constexpr std::string_view kType = "stage";  ///< its event-log type
  std::string stage;  ///< the stage's name ("greeting", "tutorial", "freeplay", "debriefing", …)
};

/// The protocol receives a signal (and either jumps to a stage or passes it to the game).
struct SignalReceived {
  static constexpr std::string_view kType = "signal_received";  ///< its event-log type
  std::string name;   ///< the signal's name
  std::string stage;  ///< the stage it arrived in
};

/// Free play ends.
struct FreeplayEnded {
  static constexpr std::string_view kType = "freeplay_ended";  ///< its event-log type
  std::string ended_by;     ///< why ("cap", "children", …)
  double duration_s = 0.0;  ///< how long free play lasted
};

/// Any other event (the web page's, one read from a file that no struct writes back byte for byte): its type and
/// data as they are.
struct Other {
  std::string type;     ///< its event-log type
  nlohmann::json data;  ///< its data (object or null)
};

/// What an event carries.
using EventPayload =
    std::variant<ItemGrabbed, ItemReleased, StrokeStarted, StrokeFinished, InteractionEvent, BackgroundDrawing,
                 BackgroundPublished, StateChanged, GameSignal, Palette, TouchMissed, TouchDown, TouchUp, ChildSpeech,
                 ChildGaze, WantsToStop, Say, MoveGoal, LookAt, PointAt, Cancel, MoveResult, TargetStart, TargetEnd,
                 Stage, SignalReceived, FreeplayEnded, Other>;

/// The event-log type of `payload`.
std::string_view type_of(const EventPayload& payload);
/// The `data` object of `payload` as the event log writes it.
nlohmann::json data_of(const EventPayload& payload);
/// The payload of an event of `type` with `data`: the typed struct when `data` is exactly what that struct writes,
/// otherwise Other.
EventPayload payload_of(std::string_view type, nlohmann::json data);

}  // namespace freeplay::events
