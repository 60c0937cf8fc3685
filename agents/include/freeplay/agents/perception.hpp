#pragma once
// What a child can see and hear (ChildPerception) and what it can do (ChildActions): plain values, no game state.
//
// A child never receives a pointer to the game: the episode loop fills a ChildPerception from the sandtray and
// the partner's visible behaviour, and applies the ChildActions through the same channels as a real child
// (fingers on the screen, the palette, gaze, speech, telling the experimenter it wants to stop).

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "freeplay/agents/item_names.hpp"
#include "freeplay/core/geometry.hpp"
#include "freeplay/sim/screen.hpp"

namespace freeplay::agents {

using sim::PaletteColour;

/// Most items a perception can hold.
inline constexpr std::size_t kMaxSeenItems = 16;
/// Most zones a perception can hold.
inline constexpr std::size_t kMaxSeenZones = 24;
/// Fingers of one child (local numbering 1…kFingersPerChild; the episode loop maps them to touch1…touch6).
inline constexpr int kFingersPerChild = 3;

/// Index of an item name in kItemNames; −1 when unknown.
int item_index(std::string_view name);
/// Side of the item's box (m), from the real game's `scale` × 0.03375 m.
double item_size_m(int item);

/// Who holds an item, from the perceiving child's point of view.
enum class HolderView : std::uint8_t { Nobody, Me, Partner, Robot };

/// One item as a child sees it.
struct SeenItem {
  int item = -1;                        ///< index into kItemNames
  Vec2 position{0.0, 0.0};              ///< centre in the `sandtray` frame (m)
  HolderView holder = HolderView::Nobody;  ///< who is dragging it now
  bool in_stash = false;                ///< lies in the stash strip
};

/// A colour zone as a child sees it (an approximating disc: centroid and radius).
struct SeenZone {
  PaletteColour colour = PaletteColour::Green;  ///< zone class
  Vec2 centroid{0.0, 0.0};                      ///< `sandtray` frame (m)
  double radius_m = 0.05;                       ///< rough extent
};

/// Where a child (or the partner) is looking.
enum class GazeKind : std::uint8_t { Away, PartnerFace, Item, Tray, Robot, Experimenter };
/// Who an utterance is for.
enum class Addressee : std::uint8_t { Nobody, Partner, Experimenter };
/// What kind of utterance it is (the content is not modelled).
enum class Utterance : std::uint8_t { Comment, Proposal, Question, Protest, Request, AnnounceStop };

/// The event-log name of a gaze kind ("away", "partner", "item", "tray", "robot", "experimenter").
std::string_view gaze_kind_name(GazeKind kind);
/// The event-log name of an utterance kind ("comment", "proposal", "question", "protest", "request", "announce_stop").
std::string_view utterance_name(Utterance kind);
/// The event-log name of an addressee ("nobody", "partner", "experimenter").
std::string_view addressee_name(Addressee to);
/// The gaze kind named `name` in an event log; nullopt when unknown.
std::optional<GazeKind> parse_gaze_kind(std::string_view name);
/// The utterance kind named `name` in an event log; nullopt when unknown.
std::optional<Utterance> parse_utterance(std::string_view name);
/// The addressee named `name` in an event log; nullopt when unknown.
std::optional<Addressee> parse_addressee(std::string_view name);

/// A gaze target: kind plus the item or point looked at when relevant.
struct GazeTarget {
  GazeKind kind = GazeKind::Away;  ///< what is looked at
  int item = -1;                   ///< item index when kind == Item
  Vec2 point{0.0, 0.0};            ///< screen point when kind == Tray or Item
};

/// One speech event (starts at the tick it is emitted).
struct SpeechEvent {
  Utterance kind = Utterance::Comment;      ///< what kind of utterance
  Addressee to = Addressee::Nobody;         ///< who it is for
  double duration_s = 0.0;                  ///< syllables / articulation rate
  int syllables = 0;                        ///< length of the utterance
};

/// One finger of the partner as seen (touch points are public: TF `touchN`).
struct SeenTouch {
  Vec2 point{0.0, 0.0};  ///< `sandtray` frame
  int item = -1;         ///< item being dragged, −1 when drawing or nothing
};

/// The partner's visible behaviour (child or robot).
struct PartnerView {
  bool present = false;                   ///< somebody sits opposite
  bool is_robot = false;                  ///< the partner is the robot
  std::array<SeenTouch, 6> touches{};     ///< active fingers (the robot's virtual finger counts as one)
  int touch_count = 0;                    ///< number of valid entries in `touches`
  GazeTarget gaze;                        ///< where the partner looks (PartnerFace = at me)
  std::optional<SpeechEvent> speech;      ///< an utterance that started this tick
  bool speaking = false;                  ///< an utterance is under way
};

/// Everything one child perceives at one tick.
struct ChildPerception {
  std::array<SeenItem, kMaxSeenItems> items{};  ///< items (first `item_count` valid)
  int item_count = 0;                           ///< number of valid items
  std::array<SeenZone, kMaxSeenZones> zones{};  ///< colour zones (first `zone_count` valid)
  int zone_count = 0;                           ///< number of valid zones
  PartnerView partner;                          ///< the other player
  bool experimenter_present = true;             ///< an adult is in the room
};

/// Phase of a touch command.
enum class TouchPhase : std::uint8_t { Down, Move, Up };

/// One finger command in the `sandtray` frame (finger is local to the child, 1…kFingersPerChild).
struct TouchCommand {
  int finger = 1;                 ///< local finger number
  TouchPhase phase = TouchPhase::Down;  ///< press, drag or lift
  Vec2 point{0.0, 0.0};           ///< position (ignored for Up)
};

/// What a child does during one tick.
struct ChildActions {
  std::array<TouchCommand, 4> touches{};        ///< touch commands in order (first `touch_count` valid)
  int touch_count = 0;                          ///< number of valid commands
  std::optional<PaletteColour> select_colour;   ///< a tap on a palette swatch
  GazeTarget gaze;                              ///< where the child looks now
  std::optional<SpeechEvent> speech;            ///< an utterance that starts now
  bool quit = false;                            ///< the child wants to stop (stays true once set)

  /// Appends a touch command (at most 4 per tick).
  void push_touch(const TouchCommand& command);
};

/// Which long side of the screen a child sits on.
enum class Seat : std::uint8_t { Bottom, Top };

/// Distance of `p` from the seat's screen edge (m).
double depth_from_seat(Seat seat, const Vec2& p);

}  // namespace freeplay::agents
