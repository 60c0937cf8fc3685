#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "freeplay/core/event_log.hpp"

using namespace freeplay;
using nlohmann::json;

namespace {

/// One typed event and the `data` object the string-typed emitter wrote for it.
struct Sample {
  events::EventPayload payload;  // the typed event
  std::string type;              // its type as the log writes it
  json data;                     // the data the string-typed event carried
};

events::MoveResult move_failed() {
  events::MoveResult e;
  e.item = "zebra";
  e.status = "aborted";
  e.reason = "no path";
  return e;
}

events::MoveResult move_succeeded() {
  events::MoveResult e;
  e.item = "ball";
  e.status = "succeeded";
  e.target_in_reach = true;
  e.poses = 12;
  e.path_length_m = 0.25;
  e.min_clearance_mm = 31.5;
  e.sync_error_mm_mean = 4.5;
  e.sync_error_mm_max = 9.25;
  e.sync_lag_ms = 100.0;
  e.duration_s = 1.2;
  e.stolen_by_child = true;
  return e;
}

events::TargetEnd point_target_end() {
  events::TargetEnd e;
  e.kind = "point";
  e.t_start = 0.5;
  e.t_end = 2.0;
  e.point = std::vector<double>{0.1, -0.2};
  e.reachable = true;
  e.ik_error_mm = 0.5;
  e.error_mm = 1.5;
  e.settled = true;
  e.settle_s = 0.75;
  return e;
}

events::TargetEnd wait_target_end() {
  events::TargetEnd e;
  e.index = 1;
  e.kind = "wait";
  e.t_start = 2.0;
  e.t_end = 3.0;
  e.wait_s = 1.0;
  return e;
}

std::vector<Sample> samples() {
  return {
      {events::ItemGrabbed{"zebra", 3, {"robot", "touch4"}}, "item_grabbed",
       {{"holder", "finger"}, {"finger", 3}, {"item", "zebra"}, {"shared_with", {"robot", "touch4"}}}},
      {events::ItemGrabbed{"ball", std::nullopt, {}}, "item_grabbed",
       {{"holder", "robot"}, {"item", "ball"}, {"shared_with", json::array()}}},
      {events::ItemReleased{"ball", std::nullopt, "timeout"}, "item_released",
       {{"holder", "robot"}, {"item", "ball"}, {"reason", "timeout"}}},
      {events::ItemReleased{"ball", 2, "touch_up"}, "item_released",
       {{"holder", "finger"}, {"finger", 2}, {"item", "ball"}, {"reason", "touch_up"}}},
      {events::StrokeStarted{4, "blue"}, "stroke_started", {{"finger", 4}, {"colour", "blue"}}},
      {events::StrokeFinished{4}, "stroke_finished", {{"finger", 4}}},
      {events::InteractionEvent{"releasing_zebra"}, "interaction_event", {{"message", "releasing_zebra"}}},
      {events::BackgroundDrawing{true}, "background_drawing", {{"enabled", true}}},
      {events::BackgroundPublished{7}, "background_published", {{"version", std::uint64_t{7}}}},
      {events::StateChanged{"freeplay"}, "state_changed", {{"state", "freeplay"}}},
      {events::GameSignal{"items_to_stash"}, "signal", {{"name", "items_to_stash"}}},
      {events::Palette{"red"}, "palette", {{"colour", "red"}}},
      {events::TouchMissed{-0.01, 0.25}, "touch_missed", {{"x", -0.01}, {"y", 0.25}}},
      {events::TouchDown{5, 0.3, -0.2, "item"}, "touch_down", {{"finger", 5}, {"x", 0.3}, {"y", -0.2}, {"outcome", "item"}}},
      {events::TouchUp{5}, "touch_up", {{"finger", 5}}},
      {events::ChildSpeech{"comment", "partner", 1.25, 4}, "speech",
       {{"kind", "comment"}, {"to", "partner"}, {"duration_s", 1.25}, {"syllables", 4}}},
      {events::ChildGaze{"item", "zebra"}, "gaze", {{"target", "item"}, {"item", "zebra"}}},
      {events::ChildGaze{"away", std::nullopt}, "gaze", {{"target", "away"}}},
      {events::WantsToStop{}, "wants_to_stop", nullptr},
      {events::Say{"Hello \"you\"\n", "", 2.0}, "say", {{"text", "Hello \"you\"\n"}, {"to", ""}, {"duration_s", 2.0}}},
      {events::MoveGoal{"zebra", 0.1, -0.15}, "move_goal", {{"item", "zebra"}, {"x", 0.1}, {"y", -0.15}}},
      {events::LookAt{"purple", 0.0, 0.0, 0.0, std::nullopt}, "look_at", {{"child", "purple"}}},
      {events::LookAt{std::nullopt, 0.2, -0.1, 0.0, "ball"}, "look_at",
       {{"x", 0.2}, {"y", -0.1}, {"z", 0.0}, {"item", "ball"}}},
      {events::LookAt{std::nullopt, 0.2, -0.1, 0.5, std::nullopt}, "look_at", {{"x", 0.2}, {"y", -0.1}, {"z", 0.5}}},
      {events::PointAt{0.4, -0.3}, "point_at", {{"x", 0.4}, {"y", -0.3}}},
      {events::Cancel{}, "cancel", nullptr},
      {events::Stage{"freeplay"}, "stage", {{"stage", "freeplay"}}},
      {events::SignalReceived{"start_freeplay", "tutorial"}, "signal_received",
       {{"name", "start_freeplay"}, {"stage", "tutorial"}}},
      {events::FreeplayEnded{"cap", 1200.0}, "freeplay_ended", {{"ended_by", "cap"}, {"duration_s", 1200.0}}},
      {events::Other{"web_command", {{"item", "zebra"}, {"status", "succeeded"}}}, "web_command",
       {{"item", "zebra"}, {"status", "succeeded"}}},
      {move_failed(), "move_result",
       {{"item", "zebra"}, {"status", "aborted"}, {"reason", "no path"}, {"target_in_reach", false},
        {"poses", std::size_t{0}}, {"stolen_by_child", false}}},
      {move_succeeded(), "move_result",
       {{"item", "ball"}, {"status", "succeeded"}, {"reason", ""}, {"target_in_reach", true},
        {"poses", std::size_t{12}}, {"path_length_m", 0.25}, {"min_clearance_mm", 31.5},
        {"sync_error_mm_mean", 4.5}, {"sync_error_mm_max", 9.25}, {"sync_lag_ms", 100.0}, {"duration_s", 1.2},
        {"stolen_by_child", true}}},
      {events::TargetStart{3, "point"}, "target_start", {{"index", std::size_t{3}}, {"kind", "point"}}},
      {point_target_end(), "target_end",
       {{"index", std::size_t{0}}, {"kind", "point"}, {"t_start", 0.5}, {"t_end", 2.0}, {"point", {0.1, -0.2}},
        {"reachable", true}, {"ik_error_mm", 0.5}, {"error_mm", 1.5}, {"settled", true}, {"settle_s", 0.75}}},
      {wait_target_end(), "target_end",
       {{"index", std::size_t{1}}, {"kind", "wait"}, {"t_start", 2.0}, {"t_end", 3.0}, {"wait_s", 1.0}}},
  };
}

}  // namespace

TEST(Events, EveryTypedEventWritesTheLineOfItsStringTypedEvent) {
  for (const auto& s : samples()) {
    EventLog log;
    log.emit({12.5, "child.purple", s.payload});
    const json old{{"t", 12.5}, {"source", "child.purple"}, {"type", s.type}, {"data", s.data}};
    EXPECT_EQ(log.to_jsonl(), old.dump() + "\n") << s.type;
  }
}

TEST(Events, AStringTypedEventIsReadBackAsItsTypedEvent) {
  for (const auto& s : samples()) {
    const Event e{1.0, "robot", s.type, s.data};
    EXPECT_EQ(e.payload.index(), s.payload.index()) << s.type << " " << s.data.dump();
    EXPECT_EQ(e.type(), s.type);
    EXPECT_EQ(e.data(), s.data);
  }
  const Event release{1.0, "sandtray", "interaction_event", {{"message", "releasing_zebra"}}};
  ASSERT_NE(release.get<events::InteractionEvent>(), nullptr);
  EXPECT_EQ(release.get<events::InteractionEvent>()->message, "releasing_zebra");
  EXPECT_EQ(release.get<events::Stage>(), nullptr);
}

TEST(Events, DataThatATypedEventWouldWriteDifferentlyStaysOther) {
  const std::vector<std::pair<std::string, json>> odd = {
      {"touch_down", {{"finger", 1}, {"x", 1}, {"y", 0.5}, {"outcome", "item"}}},  // an integer where a double is
      {"stage", {{"stage", "freeplay"}, {"extra", 1}}},                          // a key the struct does not have
      {"stage", nullptr},                                                         // no object
      {"item_grabbed", {{"holder", "hand"}, {"item", "ball"}, {"shared_with", json::array()}}},  // an unknown holder
      {"cancel", {{"why", "x"}}},                                                 // data where there is none
      {"releasing_zebra", nullptr},                                               // an unknown type
      {"move_result", {{"by", "wizard"}, {"item", "ball"}, {"status", "succeeded"}, {"target", {0.1, 0.2}}}},  // the wizard's
      {"target_end", {{"index", 0}, {"kind", "point"}, {"t_start", 0.5}, {"t_end", 1.0}, {"settle_s", nullptr}}},  // NaN
  };
  for (const auto& [type, data] : odd) {
    const Event e{0.5, "x", type, data};
    ASSERT_NE(e.get<events::Other>(), nullptr) << type << " " << data.dump();
    EXPECT_EQ(e.type(), type);
    EXPECT_EQ(e.to_json().dump(), json({{"t", 0.5}, {"source", "x"}, {"type", type}, {"data", data}}).dump());
  }
}
