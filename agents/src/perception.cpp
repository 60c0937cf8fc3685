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

double seat_edge_y(Seat seat) { return seat == Seat::Bottom ? -sim::kScreenHeightM : 0.0; }

double depth_from_seat(Seat seat, const Vec2& p) {
  return seat == Seat::Bottom ? p.y() + sim::kScreenHeightM : -p.y();
}

}  // namespace freeplay::agents
