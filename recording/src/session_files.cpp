#include "freeplay/recording/session_files.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

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

std::string to_experiment_yaml(const ExperimentInfo& info) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "timestamp" << YAML::Value << info.timestamp_ns;
  out << YAML::Key << "condition" << YAML::Value << info.condition;
  if (info.purple) participant(out, "purple-participant", *info.purple);
  if (info.yellow) participant(out, "yellow-participant", *info.yellow);
  out << YAML::Key << "markers" << YAML::Value << YAML::BeginMap;
  for (const auto& [t, kind] : info.markers) out << YAML::Key << fmt::format("{:.1f}", t) << YAML::Value << kind;
  out << YAML::EndMap;
  out << YAML::Key << "notes" << YAML::Value << YAML::BeginMap;
  for (const auto& [key, text] : info.notes) out << YAML::Key << key << YAML::Value << text;
  out << YAML::EndMap;
  if (!info.issues.empty()) out << YAML::Key << "issues" << YAML::Value << info.issues;
  out << YAML::EndMap;
  return fmt::format("# {}\n{}\n", info.header, out.c_str());
}

}  // namespace freeplay::recording
