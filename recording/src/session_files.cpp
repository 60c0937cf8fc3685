#include "freeplay/recording/session_files.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>

namespace freeplay::recording {

namespace {

void participant(YAML::Emitter& out, const char* key, const Participant& p) {
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "id" << YAML::Value << p.id;
  out << YAML::Key << "age" << YAML::Value << p.age;
  out << YAML::Key << "gender" << YAML::Value << p.gender;
  out << YAML::Key << "details" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "tablet-familiarity" << YAML::Value << p.tablet_familiarity;
  out << YAML::EndMap << YAML::EndMap;
}

}  // namespace

std::optional<int> social_engagement_likert(const agents::SessionAnnotations& annotations) {
  double sum = 0.0;
  int children = 0;
  for (const auto* timeline : {annotations.purple ? &*annotations.purple : nullptr,
                               annotations.yellow ? &*annotations.yellow : nullptr}) {
    if (timeline == nullptr || timeline->empty()) continue;
    const auto shares = agents::label_shares(*timeline, agents::Axis::SocialEngagement);
    for (std::size_t i = 0; i < agents::label_count(agents::Axis::SocialEngagement); ++i) {
      const auto name = agents::label_name(agents::Axis::SocialEngagement, i);
      if (name == "associative" || name == "cooperative") sum += shares[i];
    }
    ++children;
  }
  if (children == 0) return std::nullopt;
  return 1 + static_cast<int>(std::lround(4.0 * sum / children));
}

std::string to_experiment_yaml(const ExperimentInfo& info) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "timestamp" << YAML::Value << info.timestamp_ns;
  out << YAML::Key << "condition" << YAML::Value << std::string(agents::pinsoro_name(info.condition));
  if (info.purple) participant(out, "purple-participant", *info.purple);
  if (info.yellow) participant(out, "yellow-participant", *info.yellow);
  out << YAML::Key << "markers" << YAML::Value << YAML::BeginMap;
  for (const auto& [t, kind] : info.markers) out << YAML::Key << fmt::format("{:.1f}", t) << YAML::Value << kind;
  out << YAML::EndMap;
  out << YAML::Key << "notes" << YAML::Value << YAML::BeginMap;
  for (const auto& [key, text] : info.notes) out << YAML::Key << key << YAML::Value << text;
  out << YAML::EndMap;
  if (info.social_engagement) {
    out << YAML::Key << "extras" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "social-engagement" << YAML::Value << *info.social_engagement << YAML::EndMap;
  }
  if (!info.issues.empty()) out << YAML::Key << "issues" << YAML::Value << info.issues;
  out << YAML::EndMap;
  return fmt::format("# {}\n{}\n", info.header, out.c_str());
}

}  // namespace freeplay::recording
