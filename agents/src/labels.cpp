#include "freeplay/agents/labels.hpp"

#include <stdexcept>

namespace freeplay::agents {
namespace {

constexpr std::array<std::string_view, 4> kTask = {"goaloriented", "aimless", "adultseeking", "noplay"};
constexpr std::array<std::string_view, 5> kSocial = {"solitary", "onlooker", "parallel", "associative",
                                                     "cooperative"};
constexpr std::array<std::string_view, 5> kAttitude = {"prosocial", "adversarial", "assertive", "frustrated",
                                                       "passive"};

}  // namespace

std::string_view label_name(Axis axis, std::size_t index) {
  switch (axis) {
    case Axis::TaskEngagement:
      if (index < kTask.size()) return kTask[index];
      break;
    case Axis::SocialEngagement:
      if (index < kSocial.size()) return kSocial[index];
      break;
    case Axis::SocialAttitude:
      if (index < kAttitude.size()) return kAttitude[index];
      break;
  }
  throw std::out_of_range("label_name: label index out of range for its axis");
}

std::string_view axis_name(Axis axis) {
  switch (axis) {
    case Axis::TaskEngagement: return "task_engagement";
    case Axis::SocialEngagement: return "social_engagement";
    case Axis::SocialAttitude: return "social_attitude";
  }
  return "";
}

std::optional<std::pair<Axis, std::size_t>> parse_label(std::string_view label) {
  for (const Axis axis : kAxes) {
    for (std::size_t i = 0; i < label_count(axis); ++i) {
      if (label_name(axis, i) == label) return std::pair{axis, i};
    }
  }
  return std::nullopt;
}

std::string_view label_names(Axis axis) {
  switch (axis) {
    case Axis::TaskEngagement: return "goaloriented, aimless, adultseeking, noplay";
    case Axis::SocialEngagement: return "solitary, onlooker, parallel, associative, cooperative";
    case Axis::SocialAttitude: return "prosocial, adversarial, assertive, frustrated, passive";
  }
  return "";
}

std::size_t LabelState::index(Axis axis) const {
  switch (axis) {
    case Axis::TaskEngagement: return static_cast<std::size_t>(task);
    case Axis::SocialEngagement: return static_cast<std::size_t>(social);
    case Axis::SocialAttitude: return static_cast<std::size_t>(attitude);
  }
  return 0;
}

void LabelState::set(Axis axis, std::size_t label) {
  switch (axis) {
    case Axis::TaskEngagement: task = static_cast<TaskEngagement>(label); break;
    case Axis::SocialEngagement: social = static_cast<SocialEngagement>(label); break;
    case Axis::SocialAttitude: attitude = static_cast<SocialAttitude>(label); break;
  }
}

}  // namespace freeplay::agents
