#pragma once
// The three axes of the PInSoRo coding scheme and their exact label strings (annotator:src/annotation.hpp).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <utility>

namespace freeplay::agents {

/// One of the three annotation axes of the PInSoRo coding scheme.
enum class Axis : std::uint8_t { TaskEngagement = 0, SocialEngagement = 1, SocialAttitude = 2 };

/// Number of axes.
inline constexpr std::size_t kAxisCount = 3;
/// Largest number of labels on one axis.
inline constexpr std::size_t kMaxLabels = 5;

/// Task engagement labels, in the order of the coding scheme.
enum class TaskEngagement : std::uint8_t { GoalOriented, Aimless, AdultSeeking, NoPlay };
/// Social engagement labels (Parten's stages minus "unoccupied"), in the order of the coding scheme.
enum class SocialEngagement : std::uint8_t { Solitary, Onlooker, Parallel, Associative, Cooperative };
/// The social-engagement labels that count as playing together (joint play: associative and cooperative).
inline constexpr std::array<SocialEngagement, 2> kJointPlay = {SocialEngagement::Associative,
                                                               SocialEngagement::Cooperative};
/// Social attitude labels, in the order of the coding scheme.
enum class SocialAttitude : std::uint8_t { Prosocial, Adversarial, Assertive, Frustrated, Passive };

/// Every axis, in the order task, social engagement, social attitude.
inline constexpr std::array<Axis, kAxisCount> kAxes = {Axis::TaskEngagement, Axis::SocialEngagement,
                                                       Axis::SocialAttitude};

/// Number of labels on `axis` (4, 5 or 5).
constexpr std::size_t label_count(Axis axis) { return axis == Axis::TaskEngagement ? 4 : 5; }

/// The exact label string of label `index` on `axis` (e.g. "goaloriented"); throws std::out_of_range if invalid.
std::string_view label_name(Axis axis, std::size_t index);
/// The axis name as in the dataset's CSV suffix ("task_engagement", "social_engagement", "social_attitude").
std::string_view axis_name(Axis axis);
/// The axis and label index of an exact label string; nullopt when the string is not a coding-scheme label.
std::optional<std::pair<Axis, std::size_t>> parse_label(std::string_view label);
/// Comma-separated list of every label of `axis` (for error messages).
std::string_view label_names(Axis axis);

/// Exact label string of a task engagement label.
inline std::string_view name(TaskEngagement l) { return label_name(Axis::TaskEngagement, static_cast<std::size_t>(l)); }
/// Exact label string of a social engagement label.
inline std::string_view name(SocialEngagement l) {
  return label_name(Axis::SocialEngagement, static_cast<std::size_t>(l));
}
/// Exact label string of a social attitude label.
inline std::string_view name(SocialAttitude l) { return label_name(Axis::SocialAttitude, static_cast<std::size_t>(l)); }

/// A child's internal state on the three axes at one instant.
struct LabelState {
  TaskEngagement task = TaskEngagement::NoPlay;          ///< annotator reset value
  SocialEngagement social = SocialEngagement::Solitary;  ///< annotator reset value
  SocialAttitude attitude = SocialAttitude::Passive;     ///< annotator reset value

  /// Label index on `axis`.
  std::size_t index(Axis axis) const;
  /// Sets the label index on `axis` (caller guarantees it is in range).
  void set(Axis axis, std::size_t label);
};

}  // namespace freeplay::agents
