#include "freeplay/runner/event_coding.hpp"

#include <fmt/format.h>

#include <array>
#include <fstream>
#include <map>

#include "freeplay/agents/coder.hpp"
#include "freeplay/core/error.hpp"
#include "sim_world.hpp"

namespace freeplay::runner {
namespace {

using detail::kTickS;  // the game's 10 Hz tick (sim_world.hpp)

/// One player's visible state as the log has it so far.
struct PlayerState {
  std::map<int, agents::SeenTouch> fingers;  // finger → press point and item (the robot's virtual finger: 0)
  bool started = false;
  agents::GazeTarget gaze;
  std::optional<agents::SpeechEvent> speech;
  std::optional<sim::PaletteColour> colour;  // a palette swatch tapped since the last tick

  agents::ObservedPlayer observe() {
    agents::ObservedPlayer o;
    o.touching = !fingers.empty();
    if (o.touching) {
      o.touch_point = fingers.begin()->second.point;
      o.touch_item = fingers.begin()->second.item;
    }
    o.touch_started = started;
    o.gaze = gaze;
    o.speech = speech;
    o.stroke_colour = colour;
    started = false;
    speech.reset();
    colour.reset();
    return o;
  }
};

}  // namespace

std::vector<Event> read_event_log(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the event log", "", "", {path.string(), 0, 0});
  std::vector<Event> events;
  std::string line;
  int number_of_line = 0;
  while (std::getline(in, line)) {
    ++number_of_line;
    if (line.empty()) continue;
    const auto j = nlohmann::json::parse(line, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("t") || !j["t"].is_number() || !j.contains("source") || !j["source"].is_string() ||
        !j.contains("type") || !j["type"].is_string()) {
      throw InputError("not an event (expected an object with t, source, type, data)", "", "",
                       {path.string(), number_of_line, 1});
    }
    events.push_back({j["t"].get<double>(), j["source"].get<std::string>(), j["type"].get<std::string>(),
                      j.contains("data") ? j["data"] : nlohmann::json()});
  }
  return events;
}

agents::SessionAnnotations code_event_log(const std::vector<Event>& events, const agents::CoderParams& params) {
  double start = -1.0;
  double end = -1.0;
  bool robot = true;
  for (const Event& e : events) {
    if (const auto* stage = e.get<events::Stage>(); stage && stage->stage == "freeplay") start = e.t;
    if (e.get<events::FreeplayEnded>() != nullptr) end = e.t;
    if (e.source == "child.yellow") robot = false;
  }
  if (start < 0.0) throw InputError("the event log has no free-play stage", "stage", "freeplay");
  if (end < start) end = events.empty() ? start : events.back().t;

  agents::PairCoder coder(params, robot);
  std::array<PlayerState, 2> players;
  const auto player_of = [&](const std::string& source) -> PlayerState* {
    if (source == "child.purple") return &players[0];
    if (source == "child.yellow" || source == "robot") return &players[1];
    return nullptr;
  };
  const auto apply = [&](const Event& e) {
    PlayerState* p = player_of(e.source);
    if (const auto* grab = e.get<events::ItemGrabbed>(); grab && e.source == "sandtray") {
      // The item under a finger that just pressed; the robot's grab is its virtual finger going down.
      const int item = agents::item_index(grab->item);
      if (grab->finger) {
        // Fingers 1–3 are purple's, 4–6 yellow's (the episode's touch1…touch6); logs carry the global number.
        const int finger = *grab->finger;
        PlayerState& owner = finger <= agents::kFingersPerChild ? players[0] : players[1];
        if (owner.fingers.count(finger)) owner.fingers[finger].item = item;
      }
      return;
    }
    // The robot's virtual finger is on the screen from a move's goal to its result.
    if (const auto* goal = e.get<events::MoveGoal>(); goal && e.source == "robot") {
      const int item = agents::item_index(goal->item);
      players[1].fingers[0] = {{goal->x, goal->y}, item};
      players[1].started = true;
      players[1].gaze = agents::GazeTarget{};  // the robot looks at what it moves
      players[1].gaze.kind = agents::GazeKind::Item;
      players[1].gaze.item = item;
      return;
    }
    // By type, not by payload: a move's result in an older log (without today's fields) is read as events::Other.
    if (e.source == "robot" && e.type() == events::MoveResult::kType) {
      players[1].fingers.erase(0);
      players[1].gaze = agents::GazeTarget{};
      players[1].gaze.kind = agents::GazeKind::Tray;
      return;
    }
    if (p == nullptr) return;
    if (const auto* down = e.get<events::TouchDown>()) {
      p->fingers[down->finger] = {{down->x, down->y}, -1};
      p->started = true;
    } else if (const auto* up = e.get<events::TouchUp>()) {
      p->fingers.erase(up->finger);
    } else if (const auto* gaze = e.get<events::ChildGaze>()) {
      p->gaze = agents::GazeTarget{};
      p->gaze.kind = agents::parse_gaze_kind(gaze->target).value_or(agents::GazeKind::Away);
      p->gaze.item = agents::item_index(gaze->item.value_or(""));
    } else if (const auto* palette = e.get<events::Palette>()) {
      p->colour = sim::palette_from_name(palette->colour);
    } else if (const auto* said = e.get<events::ChildSpeech>()) {
      agents::SpeechEvent speech;
      speech.kind = agents::parse_utterance(said->kind).value_or(agents::Utterance::Comment);
      speech.to = agents::parse_addressee(said->to).value_or(agents::Addressee::Nobody);
      p->speech = speech;
    } else if (const auto* look = e.get<events::LookAt>()) {
      p->gaze = agents::GazeTarget{};
      if (look->child && !look->child->empty()) {
        p->gaze.kind = agents::GazeKind::PartnerFace;
      } else {
        const std::string item = look->item.value_or("");
        p->gaze.kind = item.empty() ? agents::GazeKind::Tray : agents::GazeKind::Item;
        p->gaze.item = agents::item_index(item);
        p->gaze.point = {look->x, look->y};
        if (p->fingers.count(0)) p->fingers[0].point = p->gaze.point;  // the robot looks at its finger
      }
    } else if (const auto* say = e.get<events::Say>()) {  // a child hears whatever the robot says as said to it
      p->speech = agents::SpeechEvent{agents::Utterance::Comment, agents::Addressee::Partner, say->duration_s, 0};
    }
  };

  std::size_t next = 0;
  while (next < events.size() && events[next].t < start - 1e-9) ++next;
  for (long tick = 0;; ++tick) {
    const double t = static_cast<double>(tick) * kTickS;
    if (start + t >= end - 1e-9) break;
    while (next < events.size() && events[next].t <= start + t + 1e-9) apply(events[next++]);
    const agents::ObservedPlayer first = players[0].observe();
    const agents::ObservedPlayer second = players[1].observe();
    coder.observe(t, first, second);
  }
  coder.finish(end - start);
  agents::SessionAnnotations out;
  out.purple = coder.timeline(0);
  if (!robot) out.yellow = coder.timeline(1);
  return out;
}

}  // namespace freeplay::runner
