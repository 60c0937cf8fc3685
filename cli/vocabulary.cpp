#include "vocabulary.hpp"

#include <cstdlib>

#include "freeplay/core/assets.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/recording/record_settings.hpp"

namespace freeplay::cli {

scenario::ScenarioVocabulary scenario_vocabulary() {
  scenario::ScenarioVocabulary v;
  v.policies = policies::policy_names();
  for (auto& pattern : policies::policy_name_patterns()) v.policies.push_back(std::move(pattern));  // python:*
#ifndef FREEPLAY_WITH_ESPEAK
  v.voices = {std::string(recording::kVoiceNames[0])};  // babble only: built without the optional espeak-ng voice (voice_espeak/, docs/recording.md)
#endif
  return v;
}

std::filesystem::path scenarios_dir() {
  if (const char* env = std::getenv("FREEPLAY_SCENARIOS_DIR"); env != nullptr && *env != '\0') return env;
  return assets_dir().parent_path() / "scenarios";
}

}  // namespace freeplay::cli
