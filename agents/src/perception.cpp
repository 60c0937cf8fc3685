#include "freeplay/agents/perception.hpp"

#include <stdexcept>

namespace freeplay::agents {

int item_index(std::string_view name) {
  for (std::size_t i = 0; i < kItemNames.size(); ++i) {
    if (kItemNames[i] == name) return static_cast<int>(i);
  }
  return -1;
}

double item_size_m(int item) {
  // Real game `scale` per item (free-play-sandbox.md §3.3) × the 0.03375 m base box.
  static constexpr std::array<double, 10> kScale = {1.0, 1.5, 0.7, 1.0, 1.5, 2.5, 1.0, 1.5, 1.0, 1.0};
  if (item < 0 || item >= static_cast<int>(kScale.size())) return sim::kItemBaseSideM;
  return kScale[static_cast<std::size_t>(item)] * sim::kItemBaseSideM;
}

void ChildActions::push_touch(const TouchCommand& command) {
  if (touch_count >= static_cast<int>(touches.size())) throw std::length_error("ChildActions: too many touches");
  touches[static_cast<std::size_t>(touch_count++)] = command;
}

namespace {
constexpr std::array<std::string_view, 6> kGazeNames = {"away", "partner", "item", "tray", "robot", "experimenter"};
constexpr std::array<std::string_view, 6> kUtteranceNames = {"comment", "proposal", "question",
                                                             "protest", "request",  "announce_stop"};
constexpr std::array<std::string_view, 3> kAddresseeNames = {"nobody", "partner", "experimenter"};

template <typename Enum, std::size_t N>
std::optional<Enum> parse_name(const std::array<std::string_view, N>& names, std::string_view name) {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  return std::nullopt;
}
}  // namespace

std::string_view gaze_kind_name(GazeKind kind) { return kGazeNames.at(static_cast<std::size_t>(kind)); }
std::string_view utterance_name(Utterance kind) { return kUtteranceNames.at(static_cast<std::size_t>(kind)); }
std::string_view addressee_name(Addressee to) { return kAddresseeNames.at(static_cast<std::size_t>(to)); }
std::optional<GazeKind> parse_gaze_kind(std::string_view name) { return parse_name<GazeKind>(kGazeNames, name); }
std::optional<Utterance> parse_utterance(std::string_view name) { return parse_name<Utterance>(kUtteranceNames, name); }
std::optional<Addressee> parse_addressee(std::string_view name) { return parse_name<Addressee>(kAddresseeNames, name); }


double depth_from_seat(Seat seat, const Vec2& p) {
  return seat == Seat::Bottom ? p.y() + sim::kScreenHeightM : -p.y();
}

}  // namespace freeplay::agents
