#include "freeplay/agents/annotations.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>

#include "freeplay/core/error.hpp"
#include "freeplay/core/yaml_schema.hpp"

namespace freeplay::agents {
namespace {

void write_child(std::string& out, const char* key, const ChildTimeline& timeline, double time_base) {
  ChildTimeline sorted = timeline;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const LabelInterval& a, const LabelInterval& b) { return a.start < b.start; });
  if (sorted.empty()) {
    out += fmt::format("{}: []\n", key);
    return;
  }
  out += fmt::format("{}:\n", key);
  for (const LabelInterval& bout : sorted) {
    out += fmt::format("  - {}: [{}, {}]\n", bout.name(), time_base + bout.start, time_base + bout.stop);
  }
}

ChildTimeline read_child(const YAML::Node& list, const std::string& file, const std::string& key, double time_base) {
  if (list.IsNull()) return {};
  if (!list.IsSequence()) throw InputError("expected a list of '- <label>: [start, stop]'", key, "",
                                           location_of(list, file));
  ChildTimeline timeline;
  std::size_t index = 0;
  for (const auto& entry : list) {
    const std::string path = fmt::format("{}[{}]", key, index++);
    if (!entry.IsMap() || entry.size() != 1) {
      throw InputError("expected a single-key map '<label>: [start, stop]'", path, "", location_of(entry, file));
    }
    const auto kv = *entry.begin();
    if (!kv.first.IsScalar()) throw InputError("a label must be a name", path, "", location_of(kv.first, file));
    const std::string label = kv.first.Scalar();
    if (label == "?") continue;  // the annotator's conflict placeholder carries no state
    const auto parsed = parse_label(label);
    if (!parsed) {
      throw InputError("unknown label '" + label + "'", path,
                       "goaloriented, aimless, adultseeking, noplay, solitary, onlooker, parallel, associative, "
                       "cooperative, prosocial, adversarial, assertive, frustrated, passive",
                       location_of(kv.first, file));
    }
    const YAML::Node span = kv.second;
    if (!span.IsSequence() || span.size() != 2) {
      throw InputError("expected [start, stop]", path + "." + label, "", location_of(span, file));
    }
    double start = 0.0;
    double stop = 0.0;
    try {
      start = span[0].as<double>();
      stop = span[1].as<double>();
    } catch (const YAML::Exception&) {
      throw InputError("start and stop must be numbers (seconds)", path + "." + label, "", location_of(span, file));
    }
    if (!(stop >= start)) throw InputError("stop is before start", path + "." + label, "", location_of(span, file));
    timeline.push_back({parsed->first, static_cast<std::uint8_t>(parsed->second), start - time_base, stop - time_base});
  }
  return timeline;
}

}  // namespace

std::string to_pinsoro_yaml(const SessionAnnotations& annotations, double time_base, std::string_view header) {
  std::string out;
  if (!header.empty()) out += fmt::format("# {}\n", header);
  if (annotations.purple) write_child(out, "purple", *annotations.purple, time_base);
  if (annotations.yellow) write_child(out, "yellow", *annotations.yellow, time_base);
  return out;
}

SessionAnnotations parse_pinsoro_yaml(std::string_view yaml_text, const std::string& file, double time_base) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {  // syntax errors, unknown aliases, nesting too deep
    throw InputError(e.msg, "", "", SourceLocation{file, e.mark.is_null() ? 0 : e.mark.line + 1,
                                                   e.mark.is_null() ? 0 : e.mark.column + 1});
  }
  if (!root.IsMap()) throw InputError("expected a map with 'purple' and/or 'yellow'", "", "purple, yellow",
                                      location_of(root, file));
  SessionAnnotations result;
  for (const auto& entry : root) {
    if (!entry.first.IsScalar()) throw InputError("a key must be a name", "", "purple, yellow",
                                                  location_of(entry.first, file));
    const std::string key = entry.first.Scalar();
    if (key == "purple") {
      result.purple = read_child(entry.second, file, key, time_base);
    } else if (key == "yellow") {
      result.yellow = read_child(entry.second, file, key, time_base);
    } else {
      throw InputError("unknown key", key, "purple, yellow", location_of(entry.first, file));
    }
  }
  return result;
}

std::array<double, kMaxLabels> label_shares(const ChildTimeline& timeline, Axis axis) {
  std::array<double, kMaxLabels> shares{};
  double total = 0.0;
  for (const LabelInterval& bout : timeline) {
    if (bout.axis != axis) continue;
    shares[bout.label] += bout.stop - bout.start;
    total += bout.stop - bout.start;
  }
  if (total > 0.0) {
    for (double& s : shares) s /= total;
  }
  return shares;
}

}  // namespace freeplay::agents
