#include "freeplay/web/commands.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "freeplay/scenario/scenario.hpp"
#include "freeplay/scenario/settings.hpp"
#include "freeplay/sim/sandtray.hpp"
#include "freeplay/sim/screen.hpp"
#include "freeplay/stage/camera_names.hpp"
#include "freeplay/web/robot_mode.hpp"

namespace freeplay::web {
namespace {

constexpr std::size_t kMaxTextChars = 500;  // one utterance, note or marker text

// The fields of one command object, checked one by one; unknown keys are refused at the end.
class Fields {
 public:
  Fields(const nlohmann::json& object, std::string type) : object_(object), type_(std::move(type)) {}

  double number(const std::string& key, double lo, double hi) {
    const auto& v = get(key);
    if (!v.is_number()) fail(key, "is not a number", fmt::format("a number in [{}, {}]", lo, hi));
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi) {
      fail(key, fmt::format("= {} is out of range", v.dump()), fmt::format("[{}, {}]", lo, hi));
    }
    return x;
  }

  int integer(const std::string& key, int lo, int hi) {
    const auto& v = get(key);
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi) {
      fail(key, fmt::format("= {} is not allowed", v.dump()), fmt::format("an integer in [{}, {}]", lo, hi));
    }
    return v.get<int>();
  }

  std::string text(const std::string& key, bool allow_empty = false) {
    const auto& v = get(key);
    if (!v.is_string()) fail(key, "is not a string", fmt::format("text of 1…{} characters", kMaxTextChars));
    auto s = v.get<std::string>();
    if ((s.empty() && !allow_empty) || s.size() > kMaxTextChars) {
      fail(key, fmt::format("has {} characters", s.size()), fmt::format("1…{} characters", kMaxTextChars));
    }
    return s;
  }

  std::string one_of(const std::string& key, const std::vector<std::string>& allowed) {
    const auto& v = get(key);
    if (!v.is_string() || std::find(allowed.begin(), allowed.end(), v.get<std::string>()) == allowed.end()) {
      fail(key, fmt::format("= {} is not allowed", v.dump()), fmt::format("{}", fmt::join(allowed, ", ")));
    }
    return v.get<std::string>();
  }

  bool has(const std::string& key) const { return object_.contains(key); }

  const nlohmann::json& object(const std::string& key) {
    const auto& v = get(key);
    if (!v.is_object()) fail(key, "is not an object", "an object");
    return v;
  }

  // Refuses keys that no check read.
  void no_other_keys() const {
    for (const auto& [key, value] : object_.items()) {
      if (key != "type" && !seen_.contains(key)) {
        fail(key, "is not a field of this command", seen_.empty() ? "no fields" : fmt::format("{}", fmt::join(seen_, ", ")));
      }
    }
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem, const std::string& allowed) const {
    throw CommandError(400, fmt::format("command '{}': '{}' {} (allowed: {})", type_, key, problem, allowed));
  }

 private:
  const nlohmann::json& get(const std::string& key) {
    seen_.insert(key);
    if (!object_.contains(key)) fail(key, "is missing", "see docs/web.md");
    return object_.at(key);
  }

  const nlohmann::json& object_;
  std::string type_;
  std::set<std::string> seen_;
};

Vec2 screen_point(Fields& f) {
  return {f.number("x", 0.0, sim::kScreenWidthM), f.number("y", -sim::kScreenHeightM, 0.0)};
}

nlohmann::json child_record(const nlohmann::json& object, const std::string& seat) {
  Fields f(object, "demographics." + seat);
  nlohmann::json out{{"age", f.integer("age", 3, 8)},
                     {"gender", f.one_of("gender", {"male", "female"})},
                     {"tablet_familiarity", f.one_of("tablet_familiarity", {"na", "0", "1", "2"})}};
  f.no_other_keys();
  return out;
}

// The JSON parser's message without its "[json.exception.<kind>.<id>] " prefix; it quotes the bytes it read last,
// so only printable ASCII of them is kept ('?' for the rest: a reply never echoes ill-formed UTF-8).
std::string parser_message(const nlohmann::json::exception& e) {
  std::string message = e.what();
  if (message.starts_with("[json.exception.")) {
    if (const auto end = message.find("] "); end != std::string::npos) message.erase(0, end + 2);
  }
  for (char& ch : message) {
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f) ch = '?';
  }
  return message;
}

const std::vector<std::string>& types() {
  static const std::vector<std::string> kTypes = {"move", "say", "look_at", "point_at", "stop", "mode", "sparc",
                                                  "sparc_timeout", "signal", "condition", "demographics", "marker",
                                                  "note", "likert", "finalise", "camera", "component"};
  return kTypes;
}

}  // namespace

std::string command_types() { return fmt::format("{}", fmt::join(types(), ", ")); }

Command parse_command(const std::string& body, const std::vector<std::string>& item_names) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(body);
  } catch (const nlohmann::json::out_of_range& e) {  // valid JSON syntax, but a number like 1e999 overflows a double
    throw CommandError(400, fmt::format("the body has a number out of range: {} (allowed: magnitudes up to {:g})",
                                        parser_message(e), std::numeric_limits<double>::max()));
  } catch (const nlohmann::json::exception& e) {  // a syntax error or ill-formed UTF-8
    throw CommandError(400, fmt::format("the body is not JSON: {}", parser_message(e)));
  }
  if (!json.is_object() || !json.contains("type") || !json["type"].is_string()) {
    throw CommandError(400, fmt::format("a command is a JSON object with a string 'type' (allowed: {})", command_types()));
  }
  Command c;
  c.type = json["type"].get<std::string>();
  if (std::find(types().begin(), types().end(), c.type) == types().end()) {
    throw CommandError(400, fmt::format("unknown command type '{}' (allowed: {})", c.type, command_types()));
  }
  Fields f(json, c.type);
  auto& a = c.args = nlohmann::json::object();
  if (c.type == "move") {
    a["item"] = f.one_of("item", item_names);
    a["frame"] = f.has("frame") ? f.one_of("frame", {"sandtray", "item"}) : "sandtray";
    if (a["frame"] == "sandtray") {
      const auto p = screen_point(f);
      a["x"] = p.x();
      a["y"] = p.y();
    } else {  // relative to the item (sparc/selected_action): checked on the screen once converted
      a["x"] = f.number("x", -sim::kScreenWidthM, sim::kScreenWidthM);
      a["y"] = f.number("y", -sim::kScreenHeightM, sim::kScreenHeightM);
    }
  } else if (c.type == "say") {
    a["text"] = f.text("text");
    a["to"] = f.has("to") ? f.one_of("to", {"", "purple", "yellow"}) : "";
  } else if (c.type == "look_at") {
    if (f.has("child")) {
      a["child"] = f.one_of("child", {"purple", "yellow"});
    } else if (f.has("item")) {
      a["item"] = f.one_of("item", item_names);
    } else {
      const auto p = screen_point(f);
      a["x"] = p.x();
      a["y"] = p.y();
      a["z"] = f.has("z") ? f.number("z", 0.0, 1.0) : 0.0;
    }
  } else if (c.type == "point_at") {
    if (f.has("item")) {
      a["item"] = f.one_of("item", item_names);
    } else {
      const auto p = screen_point(f);
      a["x"] = p.x();
      a["y"] = p.y();
    }
  } else if (c.type == "mode") {
    a["mode"] = f.one_of("mode", robot_mode_names());
  } else if (c.type == "sparc") {
    a["decision"] = f.one_of("decision", {"accept", "veto"});
  } else if (c.type == "sparc_timeout") {
    a["seconds"] = f.number("seconds", 0.1, 60.0);
  } else if (c.type == "signal") {
    const auto name = f.text("name");
    if (!sim::signal_from_name(name)) f.fail("name", fmt::format("= \"{}\" is not a signal", name), sim::signal_names());
    a["name"] = name;
  } else if (c.type == "condition") {
    a["condition"] = f.one_of("condition", {std::string(scenario::pinsoro_name(scenario::Condition::ChildChild)),
                                            std::string(scenario::pinsoro_name(scenario::Condition::ChildRobot))});
  } else if (c.type == "demographics") {
    a["purple"] = child_record(f.object("purple"), "purple");
    if (f.has("yellow")) a["yellow"] = child_record(f.object("yellow"), "yellow");
  } else if (c.type == "marker") {
    a["kind"] = f.one_of("kind", {"note", "interesting", "issue", "screenshot"});
    a["text"] = f.has("text") ? f.text("text", true) : "";
  } else if (c.type == "note") {
    a["text"] = f.text("text");
  } else if (c.type == "camera") {
    auto names = stage::real_camera_names();
    names.emplace_back("off");
    a["name"] = f.one_of("name", names);
  } else if (c.type == "component") {
    a["name"] = f.one_of("name", {"robot", "recorder", "cameras"});
    a["action"] = f.one_of("action", {"start", "stop"});
  } else if (c.type == "likert") {
    a["social_engagement"] = f.integer("social_engagement", 1, 5);
  }
  if (f.has("via")) a["via"] = f.text("via");  // where a command came from, when not from a page
  f.no_other_keys();
  static const std::set<std::string> kProtocol = {"signal"};
  static const std::set<std::string> kExperiment = {"condition", "demographics", "marker", "note", "likert", "finalise", "camera"};
  c.target = c.type == "component"            ? CommandTarget::Component
             : c.type == "camera"             ? CommandTarget::View
             : kProtocol.contains(c.type) ? CommandTarget::Protocol
             : kExperiment.contains(c.type) ? CommandTarget::Experiment
                                            : CommandTarget::Robot;
  return c;
}

}  // namespace freeplay::web
