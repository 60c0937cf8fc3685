#pragma once
// The children's settings (a scenario's `children:` block), declared by the library whose child model uses them:
// which population the children are sampled from and any explicit profile fields, with their keys, ranges and help
// (core/settings_archive.hpp). Header-only, so that the scenario parser reads them without linking the agents; the
// runner turns them into profiles (runner/src/sim_world.cpp).

#include <optional>
#include <string>
#include <string_view>

#include "freeplay/core/enum_names.hpp"
#include "freeplay/core/settings_archive.hpp"

namespace freeplay::agents {

/// Which demographics the children are sampled from (`children.population`).
enum class PopulationName {
  pinsoro,     ///< PInSoRo's population of the scenario's condition ("pinsoro")
  pinsoro_cc,  ///< PInSoRo's child-child population, whatever the condition ("pinsoro-cc")
  pinsoro_cr,  ///< PInSoRo's child-robot population, whatever the condition ("pinsoro-cr")
};

/// The name scenarios use for a population ("pinsoro", "pinsoro-cc", "pinsoro-cr").
constexpr std::string_view to_string(PopulationName population) {
  switch (population) {
    case PopulationName::pinsoro: return "pinsoro";
    case PopulationName::pinsoro_cc: return "pinsoro-cc";
    case PopulationName::pinsoro_cr: return "pinsoro-cr";
  }
  return "pinsoro";
}

/// Sets `population` to the one named `text`; false (and `population` unchanged) when `text` names none.
constexpr bool from_string(std::string_view text, PopulationName& population) {
  return enum_from_string(text, {PopulationName::pinsoro, PopulationName::pinsoro_cc, PopulationName::pinsoro_cr},
                          population);
}

/// An explicit child profile (absent fields are sampled from the population).
struct ChildSpec {
  std::optional<int> age;                    ///< years, 4–8
  std::optional<std::string> gender;         ///< "female" | "male"
  std::optional<double> sociability;         ///< 0–1
  std::optional<double> assertiveness;       ///< 0–1
  std::optional<double> attention_span;      ///< 0–1
  std::optional<int> tablet_familiarity;     ///< 0, 1, 2

  /// The keys of `children.purple` / `children.yellow`.
  template <typename Archive>
  void visit(Archive& a) {
    a.optional("age", age, Schema::integer(4, 8), "years");
    a.optional("gender", gender, Schema::enumeration({"female", "male"}));
    a.optional("sociability", sociability, Schema::number(0, 1));
    a.optional("assertiveness", assertiveness, Schema::number(0, 1));
    a.optional("attention_span", attention_span, Schema::number(0, 1));
    a.optional("tablet_familiarity", tablet_familiarity, Schema::integer(0, 2), "0 not familiar, 1 somewhat, 2 familiar");
  }
};

/// `children:` who plays: the population and any explicit profile fields.
struct ChildrenSettings {
  PopulationName population = PopulationName::pinsoro;  ///< population the children are sampled from
  ChildSpec purple;                                     ///< explicit purple profile fields
  ChildSpec yellow;                                     ///< explicit yellow profile fields (child-child only)

  /// The keys of `children:`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("population", population,
            Schema::enumeration(enum_names({PopulationName::pinsoro, PopulationName::pinsoro_cc,
                                            PopulationName::pinsoro_cr})),
            "population the children are sampled from");
    a.optional("purple", purple, settings_schema<ChildSpec>(), "explicit fields of the purple child's profile");
    a.optional("yellow", yellow, settings_schema<ChildSpec>(),
               "explicit fields of the yellow child's profile (child-child)");
  }
};

}  // namespace freeplay::agents
