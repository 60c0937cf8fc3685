#pragma once
// Who a synthetic child is (age, gender, traits) and the populations children are drawn from.

#include <array>
#include <cstdint>
#include <string_view>

#include "freeplay/agents/params.hpp"
#include "freeplay/core/rng.hpp"

namespace freeplay::agents {

/// Gender as recorded in the dataset's experiment.yaml.
enum class Gender : std::uint8_t { Female, Male };

/// Tablet familiarity as in experiment.yaml (`0`, `1`, `2`, `na`).
enum class TabletFamiliarity : std::uint8_t { None = 0, Some = 1, Daily = 2, Unknown = 3 };

/// One child's fixed characteristics.
struct ChildProfile {
  int age_years = 6;                                        ///< 4…8
  Gender gender = Gender::Female;                           ///< as in the dataset
  double sociability = 0.5;                                 ///< [0, 1]
  double assertiveness = 0.5;                               ///< [0, 1]
  double attention_span = 0.5;                              ///< [0, 1]
  TabletFamiliarity tablet = TabletFamiliarity::Daily;      ///< 0/1/2/na

  /// Throws InputError naming the field when a value is out of range.
  void validate() const;
};

/// Demographics children are sampled from (counts, not probabilities, so published tables paste in).
struct Population {
  std::array<double, 5> age_counts{};      ///< children aged 4, 5, 6, 7, 8
  double female = 1.0;                     ///< female count
  double male = 1.0;                       ///< male count
  std::array<double, 4> tablet_counts{};   ///< familiarity 0, 1, 2, na

  /// PInSoRo child-child demographics (pinsoro-targets §1): ages 20/1/17/40/12, 43 F / 47 M, tablet 9/9/66/6.
  static Population pinsoro_child_child();
  /// PInSoRo child-robot demographics: ages 1/1/4/18/6, 12 F / 18 M (tablet familiarity as in child-child).
  static Population pinsoro_child_robot();
  /// Every child the given age, other fields as in the child-child population.
  static Population fixed_age(int age_years);

  /// Draws one profile: demographics from the counts, traits from `traits` (attention span grows with age).
  ChildProfile sample(const TraitParams& traits, Rng& rng) const;
};

/// Lower-case gender string ("female" / "male").
std::string_view gender_name(Gender gender);

}  // namespace freeplay::agents
