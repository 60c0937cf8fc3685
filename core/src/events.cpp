#include "freeplay/core/events.hpp"

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace freeplay::events {

namespace {

using nlohmann::json;

/// The holder fields of a grab or a release: {"holder": "robot"} or {"holder": "finger", "finger": n}.
json holder_data(const std::optional<int>& finger) {
  if (!finger) return {{"holder", "robot"}};
  return {{"holder", "finger"}, {"finger", *finger}};
}

json data(const ItemGrabbed& e) {
  json d = holder_data(e.finger);
  d["item"] = e.item;
  d["shared_with"] = e.shared_with;
  return d;
}
json data(const ItemReleased& e) {
  json d = holder_data(e.finger);
  d["item"] = e.item;
  d["reason"] = e.reason;
  return d;
}
json data(const StrokeStarted& e) { return {{"finger", e.finger}, {"colour", e.colour}}; }
json data(const StrokeFinished& e) { return {{"finger", e.finger}}; }
json data(const InteractionEvent& e) { return {{"message", e.message}}; }
json data(const BackgroundDrawing& e) { return {{"enabled", e.enabled}}; }
json data(const BackgroundPublished& e) { return {{"version", e.version}}; }
json data(const StateChanged& e) { return {{"state", e.state}}; }
json data(const GameSignal& e) { return {{"name", e.name}}; }
json data(const Palette& e) { return {{"colour", e.colour}}; }
json data(const TouchMissed& e) { return {{"x", e.x}, {"y", e.y}}; }
json data(const TouchDown& e) { return {{"finger", e.finger}, {"x", e.x}, {"y", e.y}, {"outcome", e.outcome}}; }
json data(const TouchUp& e) { return {{"finger", e.finger}}; }
json data(const ChildSpeech& e) {
  return {{"kind", e.kind}, {"to", e.to}, {"duration_s", e.duration_s}, {"syllables", e.syllables}};
}
json data(const ChildGaze& e) {
  json d{{"target", e.target}};
  if (e.item) d["item"] = *e.item;
  return d;
}
json data(const WantsToStop&) { return nullptr; }
json data(const Say& e) { return {{"text", e.text}, {"to", e.to}, {"duration_s", e.duration_s}}; }
json data(const MoveGoal& e) { return {{"item", e.item}, {"x", e.x}, {"y", e.y}}; }
json data(const LookAt& e) {
  if (e.child) return {{"child", *e.child}};
  json d{{"x", e.x}, {"y", e.y}, {"z", e.z}};
  if (e.item) d["item"] = *e.item;
  return d;
}
json data(const PointAt& e) { return {{"x", e.x}, {"y", e.y}}; }
json data(const Cancel&) { return nullptr; }
/// Sets `d[key]` when `value` is there.
template <class T>
void put(json& d, const char* key, const std::optional<T>& value) {
  if (value) d[key] = *value;
}
json data(const MoveResult& e) {
  json d{{"item", e.item},       {"status", e.status}, {"reason", e.reason}, {"target_in_reach", e.target_in_reach},
         {"poses", e.poses}, {"stolen_by_child", e.stolen_by_child}};
  put(d, "path_length_m", e.path_length_m);
  put(d, "min_clearance_mm", e.min_clearance_mm);
  put(d, "sync_error_mm_mean", e.sync_error_mm_mean);
  put(d, "sync_error_mm_max", e.sync_error_mm_max);
  put(d, "sync_lag_ms", e.sync_lag_ms);
  put(d, "duration_s", e.duration_s);
  return d;
}
json data(const TargetStart& e) { return {{"index", e.index}, {"kind", e.kind}}; }
/// Calls `f(key, field)` for every optional measure of a target's end, in one place for the writer and the reader.
template <class E, class F>
bool each_measure(E& e, F&& f) {
  return f("point", e.point) && f("reachable", e.reachable) && f("ik_error_mm", e.ik_error_mm) &&
         f("look", e.look) && f("clamped", e.clamped) && f("gaze_error_deg", e.gaze_error_deg) &&
         f("posture", e.posture) && f("joint_error_rad", e.joint_error_rad) && f("wait_s", e.wait_s) &&
         f("item", e.item) && f("to", e.to) && f("status", e.status) && f("reason", e.reason) &&
         f("poses", e.poses) && f("error_mm", e.error_mm) && f("sync_error_mm_mean", e.sync_error_mm_mean) &&
         f("sync_error_mm_max", e.sync_error_mm_max) && f("sync_lag_ms", e.sync_lag_ms) &&
         f("unreachable_poses", e.unreachable_poses) && f("placement_error_mm", e.placement_error_mm) &&
         f("settled", e.settled) && f("settle_s", e.settle_s);
}
json data(const TargetEnd& e) {
  json d{{"index", e.index}, {"kind", e.kind}, {"t_start", e.t_start}, {"t_end", e.t_end}};
  each_measure(e, [&](const char* key, const auto& value) {
    put(d, key, value);
    return true;
  });
  return d;
}
json data(const Stage& e) { return {{"stage", e.stage}}; }
json data(const SignalReceived& e) { return {{"name", e.name}, {"stage", e.stage}}; }
json data(const FreeplayEnded& e) { return {{"ended_by", e.ended_by}, {"duration_s", e.duration_s}}; }
json data(const Other& e) { return e.data; }

// The JSON type each field type is read from (a double is a float, as the log writes it, so that the field writes
// back the same text).
bool has_type(const json& v, const std::string*) { return v.is_string(); }
bool has_type(const json& v, const int*) { return v.is_number_integer(); }
bool has_type(const json& v, const std::uint64_t*) { return v.is_number_unsigned(); }
bool has_type(const json& v, const double*) { return v.is_number_float(); }
bool has_type(const json& v, const bool*) { return v.is_boolean(); }
bool has_type(const json& v, const std::vector<std::string>*) {
  return v.is_array() && std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_string(); });
}
bool has_type(const json& v, const std::vector<double>*) {
  return v.is_array() && std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number_float(); });
}

/// Reads field `key` of `d` into `out`: true when it is there with the field's JSON type.
template <class T>
bool read(const json& d, const char* key, T& out) {
  const auto it = d.find(key);
  if (it == d.end() || !has_type(*it, &out)) return false;
  out = it->template get<T>();
  return true;
}

/// An optional field: absent is fine, present must read.
template <class T>
bool read_optional(const json& d, const char* key, std::optional<T>& out) {
  if (!d.contains(key)) return true;
  out.emplace();
  return read(d, key, *out);
}
bool read_holder(const json& d, std::optional<int>& finger) {
  std::string holder;
  if (!read(d, "holder", holder)) return false;
  if (holder == "robot") return true;
  finger.emplace();
  return holder == "finger" && read(d, "finger", *finger);
}

// Decoders: true when `d` holds every field of the struct (payload_of then checks that it writes `d` back).
bool decode(const json& d, ItemGrabbed& e) {
  return d.is_object() && read_holder(d, e.finger) && read(d, "item", e.item) && read(d, "shared_with", e.shared_with);
}
bool decode(const json& d, ItemReleased& e) {
  return d.is_object() && read_holder(d, e.finger) && read(d, "item", e.item) && read(d, "reason", e.reason);
}
bool decode(const json& d, StrokeStarted& e) {
  return d.is_object() && read(d, "finger", e.finger) && read(d, "colour", e.colour);
}
bool decode(const json& d, StrokeFinished& e) { return d.is_object() && read(d, "finger", e.finger); }
bool decode(const json& d, InteractionEvent& e) { return d.is_object() && read(d, "message", e.message); }
bool decode(const json& d, BackgroundDrawing& e) { return d.is_object() && read(d, "enabled", e.enabled); }
bool decode(const json& d, BackgroundPublished& e) { return d.is_object() && read(d, "version", e.version); }
bool decode(const json& d, StateChanged& e) { return d.is_object() && read(d, "state", e.state); }
bool decode(const json& d, GameSignal& e) { return d.is_object() && read(d, "name", e.name); }
bool decode(const json& d, Palette& e) { return d.is_object() && read(d, "colour", e.colour); }
bool decode(const json& d, TouchMissed& e) { return d.is_object() && read(d, "x", e.x) && read(d, "y", e.y); }
bool decode(const json& d, TouchDown& e) {
  return d.is_object() && read(d, "finger", e.finger) && read(d, "x", e.x) && read(d, "y", e.y) &&
         read(d, "outcome", e.outcome);
}
bool decode(const json& d, TouchUp& e) { return d.is_object() && read(d, "finger", e.finger); }
bool decode(const json& d, ChildSpeech& e) {
  return d.is_object() && read(d, "kind", e.kind) && read(d, "to", e.to) && read(d, "duration_s", e.duration_s) &&
         read(d, "syllables", e.syllables);
}
bool decode(const json& d, ChildGaze& e) {
  return d.is_object() && read(d, "target", e.target) && read_optional(d, "item", e.item);
}
bool decode(const json& d, WantsToStop&) { return d.is_null(); }
bool decode(const json& d, Say& e) {
  return d.is_object() && read(d, "text", e.text) && read(d, "to", e.to) && read(d, "duration_s", e.duration_s);
}
bool decode(const json& d, MoveGoal& e) {
  return d.is_object() && read(d, "item", e.item) && read(d, "x", e.x) && read(d, "y", e.y);
}
bool decode(const json& d, LookAt& e) {
  if (!d.is_object()) return false;
  if (d.contains("child")) return read_optional(d, "child", e.child);
  return read(d, "x", e.x) && read(d, "y", e.y) && read(d, "z", e.z) && read_optional(d, "item", e.item);
}
bool decode(const json& d, PointAt& e) { return d.is_object() && read(d, "x", e.x) && read(d, "y", e.y); }
bool decode(const json& d, Cancel&) { return d.is_null(); }
bool decode(const json& d, MoveResult& e) {
  return d.is_object() && read(d, "item", e.item) && read(d, "status", e.status) && read(d, "reason", e.reason) &&
         read(d, "target_in_reach", e.target_in_reach) && read(d, "poses", e.poses) &&
         read(d, "stolen_by_child", e.stolen_by_child) && read_optional(d, "path_length_m", e.path_length_m) &&
         read_optional(d, "min_clearance_mm", e.min_clearance_mm) &&
         read_optional(d, "sync_error_mm_mean", e.sync_error_mm_mean) &&
         read_optional(d, "sync_error_mm_max", e.sync_error_mm_max) &&
         read_optional(d, "sync_lag_ms", e.sync_lag_ms) && read_optional(d, "duration_s", e.duration_s);
}
bool decode(const json& d, TargetStart& e) {
  return d.is_object() && read(d, "index", e.index) && read(d, "kind", e.kind);
}
bool decode(const json& d, TargetEnd& e) {
  return d.is_object() && read(d, "index", e.index) && read(d, "kind", e.kind) && read(d, "t_start", e.t_start) &&
         read(d, "t_end", e.t_end) &&
         each_measure(e, [&](const char* key, auto& value) { return read_optional(d, key, value); });
}
bool decode(const json& d, Stage& e) { return d.is_object() && read(d, "stage", e.stage); }
bool decode(const json& d, SignalReceived& e) {
  return d.is_object() && read(d, "name", e.name) && read(d, "stage", e.stage);
}
bool decode(const json& d, FreeplayEnded& e) {
  return d.is_object() && read(d, "ended_by", e.ended_by) && read(d, "duration_s", e.duration_s);
}

/// The typed payload of `type` among the alternatives I… of EventPayload (Other, the last, excluded), if `data` reads
/// as it and writes back unchanged.
template <std::size_t... I>
std::optional<EventPayload> typed_payload(std::string_view type, const json& data, std::index_sequence<I...>) {
  std::optional<EventPayload> out;
  const auto try_one = [&](auto tag) {
    using T = typename decltype(tag)::type;
    if (out || T::kType != type) return;
    T e;
    if (decode(data, e) && events::data(e) == data) out = std::move(e);
  };
  (try_one(std::type_identity<std::variant_alternative_t<I, EventPayload>>{}), ...);
  return out;
}

}  // namespace

std::string_view type_of(const EventPayload& payload) {
  return std::visit(
      [](const auto& e) -> std::string_view {
        if constexpr (std::is_same_v<std::decay_t<decltype(e)>, Other>) {
          return e.type;
        } else {
          return std::decay_t<decltype(e)>::kType;
        }
      },
      payload);
}

nlohmann::json data_of(const EventPayload& payload) {
  return std::visit([](const auto& e) { return data(e); }, payload);
}

EventPayload payload_of(std::string_view type, nlohmann::json data) {
  constexpr std::size_t kTyped = std::variant_size_v<EventPayload> - 1;  // every alternative but Other
  if (auto typed = typed_payload(type, data, std::make_index_sequence<kTyped>{})) return std::move(*typed);
  return Other{std::string(type), std::move(data)};
}

}  // namespace freeplay::events
