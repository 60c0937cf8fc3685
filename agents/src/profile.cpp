#include "freeplay/agents/profile.hpp"

#include <algorithm>
#include <string>

#include "freeplay/core/error.hpp"

namespace freeplay::agents {

void ChildProfile::validate() const {
  if (age_years < 4 || age_years > 8) throw InputError("age out of range", "profile.age", "4…8");
  const auto unit = [](double v, const char* key) {
    if (!(v >= 0.0 && v <= 1.0)) throw InputError("trait out of range", key, "0…1");
  };
  unit(sociability, "profile.sociability");
  unit(assertiveness, "profile.assertiveness");
  unit(attention_span, "profile.attention_span");
}

Population Population::pinsoro_child_child() {
  Population p;
  p.age_counts = {20, 1, 17, 40, 12};
  p.female = 43;
  p.male = 47;
  p.tablet_counts = {9, 9, 66, 6};
  return p;
}

Population Population::pinsoro_child_robot() {
  Population p = pinsoro_child_child();
  p.age_counts = {1, 1, 4, 18, 6};
  p.female = 12;
  p.male = 18;
  return p;
}

Population Population::fixed_age(int age_years) {
  if (age_years < 4 || age_years > 8) throw InputError("age out of range", "age", "4…8");
  Population p = pinsoro_child_child();
  p.age_counts = {0, 0, 0, 0, 0};
  p.age_counts[static_cast<std::size_t>(age_years - 4)] = 1;
  return p;
}

ChildProfile Population::sample(const TraitParams& traits, Rng& rng) const {
  ChildProfile profile;
  std::vector<double> weights(age_counts.begin(), age_counts.end());
  profile.age_years = 4 + static_cast<int>(rng.categorical(weights));
  profile.gender = rng.uniform() * (female + male) < female ? Gender::Female : Gender::Male;
  weights.assign(tablet_counts.begin(), tablet_counts.end());
  profile.tablet = static_cast<TabletFamiliarity>(rng.categorical(weights));
  profile.sociability = std::clamp(rng.normal(traits.sociability_mean, traits.sociability_sd), 0.0, 1.0);
  profile.assertiveness = std::clamp(rng.normal(traits.assertiveness_mean, traits.assertiveness_sd), 0.0, 1.0);
  const double attention_mean = traits.attention_mean + traits.attention_per_year * (profile.age_years - 6);
  profile.attention_span = std::clamp(rng.normal(attention_mean, traits.attention_sd), 0.0, 1.0);
  return profile;
}

std::string_view gender_name(Gender gender) { return gender == Gender::Female ? "female" : "male"; }

}  // namespace freeplay::agents
