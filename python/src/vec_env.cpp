// freeplay.VecEnv's step in one call (docs/python.md, "VecEnv: the batched layout"): hands every environment its
// actions with the GIL released, waits for all of them and fills batched arrays (leading dimension: the environment)
// of the observations, rewards, terminated, truncated and infos, so that no Python runs once per environment unless
// the reward is a Python callable. Also the home of the built-in rewards of freeplay.rewards (Env calls them too).

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "bindings.hpp"
#include "env_episode.hpp"
#include "freeplay/agents/labels.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/sim/item_catalogue.hpp"

namespace freeplay::python {
namespace {

using policies::Action;
using policies::Observation;

/// Fingers the game tracks (`touch1` … `touch6`): the rows of the touch arrays.
constexpr py::ssize_t kFingers = 6;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A built-in reward of freeplay.rewards, computed here for Env (one step at a time) and VecEnv (all at once).
enum class BuiltinReward { Zero, SessionLength, CodedJointPlay };

/// The built-in reward called `name`; throws InputError naming the built-in rewards otherwise.
BuiltinReward builtin_reward_named(const std::string& name) {
  if (name == "zero") return BuiltinReward::Zero;
  if (name == "session_length") return BuiltinReward::SessionLength;
  if (name == "coded_joint_play") return BuiltinReward::CodedJointPlay;
  throw InputError(fmt::format("no built-in reward '{}'", name), "reward", "zero, session_length, coded_joint_play");
}

/// True for a social-engagement label of joint play (agents::kJointPlay; freeplay.rewards.JOINT_PLAY).
bool joint_play(std::string_view social_engagement) {
  for (const auto label : agents::kJointPlay) {
    if (social_engagement == agents::name(label)) return true;
  }
  return false;
}

/// The reward `kind` of one step of `dt` simulated seconds; `for_each_social(add)` calls `add` with each child's
/// coded social-engagement label ("" before the child is coded).
template <class ForEachSocial>
double builtin_reward(BuiltinReward kind, double dt, ForEachSocial for_each_social) {
  switch (kind) {
    case BuiltinReward::Zero: return 0.0;
    case BuiltinReward::SessionLength: return dt;
    case BuiltinReward::CodedJointPlay: {
      bool together = false;
      for_each_social([&](std::string_view label) { together = together || joint_play(label); });
      return together ? dt : 0.0;
    }
  }
  return 0.0;
}

/// What the rows of a VecEnv's batch hold: the items and child seats in a fixed order.
struct BatchLayout {
  std::vector<std::string> items;  ///< item names, the order of the item axis (the policy context's item_names)
  std::vector<std::string> seats;  ///< child seats, the order of the seat axis
  bool children = false;           ///< the observation has the perceived children's fields
  bool privileged = false;         ///< the infos have the children's hidden state
  std::unordered_map<std::string, std::int16_t> item_rows;  ///< item name → its index on the item axis

  /// The index of item `name` on the item axis, or -1; `hint` is tried first (observations list items in order).
  std::int16_t item_row(const std::string& name, std::size_t hint) const {
    if (hint < items.size() && items[hint] == name) return static_cast<std::int16_t>(hint);
    const auto found = item_rows.find(name);
    return found == item_rows.end() ? std::int16_t{-1} : found->second;
  }
  /// The index of child seat `seat` on the seat axis, or -1.
  int seat_row(const std::string& seat) const {
    for (std::size_t s = 0; s < seats.size(); ++s) {
      if (seats[s] == seat) return static_cast<int>(s);
    }
    return -1;
  }
};

/// One array of a batch: made with a leading environment dimension of `n` and stored under `key` (`make`), or the
/// one already stored there; returns its data.
template <class T>
T* column(py::dict& d, const char* key, py::ssize_t n, std::initializer_list<py::ssize_t> row, bool make) {
  if (make) {
    std::vector<py::ssize_t> shape{n};
    shape.insert(shape.end(), row);
    py::array_t<T> array(shape);
    d[key] = array;
    return array.mutable_data();
  }
  const py::object stored = d[key];
  if (!py::isinstance<py::array_t<T>>(stored)) {
    throw InputError(fmt::format("VecEnv batch entry '{}' is not the array it made", key), key, "the step's own dict");
  }
  return static_cast<T*>(py::reinterpret_borrow<py::array>(stored).mutable_data());
}

/// An object array of `n` Nones.
py::array none_array(py::ssize_t n) {
  py::array array(py::dtype("O"), std::vector<py::ssize_t>{n});
  auto** data = static_cast<PyObject**>(array.mutable_data());
  for (py::ssize_t i = 0; i < n; ++i) {
    Py_XDECREF(data[i]);
    data[i] = py::none().release().ptr();
  }
  return array;
}

/// Puts `value` at index `i` of object array `array`.
void set_object(py::array& array, std::size_t i, py::object value) {
  auto** data = static_cast<PyObject**>(array.mutable_data());
  PyObject* old = data[i];
  data[i] = value.release().ptr();
  Py_XDECREF(old);
}

/// The arrays of one batched step (the observation dict, the info dict, rewards, terminated, truncated) and their
/// data: every field is listed once, in `Batch::Batch`.
struct Batch {
  py::dict obs;    ///< the batched observation
  py::dict infos;  ///< the batched infos
  py::array_t<double> rewards;
  py::array_t<bool> terminated;
  py::array_t<bool> truncated;
  py::array events;   ///< infos["events"]: per environment a list of event dicts, or None
  py::array results;  ///< infos["results"]: per environment a list of ActionResults, or None

  double* t = nullptr;
  double* item_pose = nullptr;
  bool* item_touched = nullptr;
  bool* item_held = nullptr;
  bool* item_visible = nullptr;
  bool* touch_active = nullptr;
  double* touch_position = nullptr;
  bool* child_perceived = nullptr;
  bool* child_face = nullptr;
  std::int8_t* child_gaze = nullptr;
  double* child_gaze_on_screen = nullptr;
  bool* child_speaking = nullptr;
  bool* child_addressing = nullptr;
  double* child_since_touch = nullptr;
  std::int16_t* child_moving_item = nullptr;
  bool* self_moving = nullptr;
  std::int16_t* self_item = nullptr;
  bool* self_speaking = nullptr;
  double* self_reach_centre = nullptr;
  double* self_reach_radius = nullptr;
  bool* self_reach_known = nullptr;
  std::int64_t* episode = nullptr;
  std::uint64_t* seed = nullptr;
  std::int8_t* coded = nullptr;
  bool* has_events = nullptr;
  bool* has_results = nullptr;
  std::int8_t* hidden_labels = nullptr;
  double* motivation = nullptr;
  double* boredom = nullptr;
  double* answer_expectation = nullptr;
  bool* wants_to_stop = nullptr;

  /// Makes the arrays of a batch of `n` environments (`make`), or binds those of `obs` and `infos` as a step made
  /// them (to rewrite one row after an automatic reset).
  Batch(const BatchLayout& layout, py::ssize_t n, bool make, py::dict obs_ = {}, py::dict infos_ = {})
      : obs(make ? py::dict() : obs_), infos(make ? py::dict() : infos_) {
    const auto items = static_cast<py::ssize_t>(layout.items.size());
    const auto seats = static_cast<py::ssize_t>(layout.seats.size());
    constexpr auto axes = static_cast<py::ssize_t>(agents::kAxisCount);
    t = column<double>(obs, "t", n, {}, make);
    item_pose = column<double>(obs, "item_pose", n, {items, 3}, make);
    item_touched = column<bool>(obs, "item_touched_by_child", n, {items}, make);
    item_held = column<bool>(obs, "item_held_by_robot", n, {items}, make);
    item_visible = column<bool>(obs, "item_visible", n, {items}, make);
    touch_active = column<bool>(obs, "touch_active", n, {kFingers}, make);
    touch_position = column<double>(obs, "touch_position", n, {kFingers, 2}, make);
    if (layout.children) {
      child_perceived = column<bool>(obs, "child_perceived", n, {seats}, make);
      child_face = column<bool>(obs, "child_face_detected", n, {seats}, make);
      child_gaze = column<std::int8_t>(obs, "child_gaze", n, {seats}, make);
      child_gaze_on_screen = column<double>(obs, "child_gaze_on_screen", n, {seats, 2}, make);
      child_speaking = column<bool>(obs, "child_speaking", n, {seats}, make);
      child_addressing = column<bool>(obs, "child_addressing_robot", n, {seats}, make);
      child_since_touch = column<double>(obs, "child_seconds_since_touch", n, {seats}, make);
      child_moving_item = column<std::int16_t>(obs, "child_moving_item", n, {seats}, make);
    }
    self_moving = column<bool>(obs, "self_moving_item", n, {}, make);
    self_item = column<std::int16_t>(obs, "self_current_item", n, {}, make);
    self_speaking = column<bool>(obs, "self_speaking", n, {}, make);
    self_reach_centre = column<double>(obs, "self_arm_reach_centre", n, {2}, make);
    self_reach_radius = column<double>(obs, "self_arm_reach_radius", n, {}, make);
    self_reach_known = column<bool>(obs, "self_arm_reach_known", n, {}, make);
    if (make) {
      obs["zones"] = py::tuple(n);
      obs["interaction_events"] = py::tuple(n);
      infos["t"] = obs["t"];
      events = none_array(n);
      results = none_array(n);
      infos["events"] = events;
      infos["results"] = results;
      rewards = py::array_t<double>(n);
      terminated = py::array_t<bool>(n);
      truncated = py::array_t<bool>(n);
    } else {
      events = py::reinterpret_borrow<py::array>(py::object(infos["events"]));
      results = py::reinterpret_borrow<py::array>(py::object(infos["results"]));
    }
    episode = column<std::int64_t>(infos, "episode", n, {}, make);
    seed = column<std::uint64_t>(infos, "seed", n, {}, make);
    coded = column<std::int8_t>(infos, "coded", n, {seats, axes}, make);
    has_events = column<bool>(infos, "_events", n, {}, make);
    has_results = column<bool>(infos, "_results", n, {}, make);
    if (layout.privileged) {
      py::dict hidden = make ? py::dict() : py::reinterpret_borrow<py::dict>(py::object(infos["privileged"]));
      if (make) infos["privileged"] = hidden;
      hidden_labels = column<std::int8_t>(hidden, "labels", n, {seats, axes}, make);
      motivation = column<double>(hidden, "motivation", n, {seats}, make);
      boredom = column<double>(hidden, "boredom", n, {seats}, make);
      answer_expectation = column<double>(hidden, "answer_expectation", n, {seats}, make);
      wants_to_stop = column<bool>(hidden, "wants_to_stop", n, {seats}, make);
    }
  }
};

/// Batches whose arrays are used again once Python holds none of them: making a batch's 30 or so arrays costs about
/// as much as a decision of this scenario, and with send/recv it is paid per environment (docs/python.md, Speed).
/// A batch handed out is a fresh pair of dicts over the arrays; it is reused only when every one of its arrays is
/// back to the references the pool itself holds (no dict, view, or variable of the caller's keeps one).
class BatchPool {
 public:
  /// A batch of `n` rows to fill: a free one of the pool, or a new one (kept in the pool while it has room).
  Batch& take(const BatchLayout& layout, py::ssize_t n) {
    for (auto& entry : entries_) {
      if (entry.rows == n && entry.free()) return entry.hand_out();
    }
    if (entries_.size() >= kMaxBatches) {
      spare_ = std::make_unique<Batch>(layout, n, true);  // handed out as made: not reused
      return *spare_;
    }
    entries_.push_back(Entry(std::make_unique<Batch>(layout, n, true), n));
    return entries_.back().hand_out();
  }

 private:
  /// Batches kept for reuse (a caller that keeps the previous observations while it steps holds one or two).
  static constexpr std::size_t kMaxBatches = 4;

  /// One pooled batch: its own dicts stay here as templates, and the arrays' reference counts when nobody else
  /// holds them (the templates, the Batch's members and `arrays`).
  struct Entry {
    std::unique_ptr<Batch> batch;
    py::ssize_t rows = 0;
    py::dict obs;     ///< the batch's observation dict as made (never handed out)
    py::dict infos;   ///< the batch's info dict as made (never handed out)
    py::object hidden;  ///< infos["privileged"] as made, or None
    std::vector<std::pair<py::object, py::ssize_t>> arrays;  ///< every array and its reference count at rest

    Entry(std::unique_ptr<Batch> made, py::ssize_t n) : batch(std::move(made)), rows(n) {
      obs = batch->obs;
      infos = batch->infos;
      hidden = infos.contains("privileged") ? py::object(infos["privileged"]) : py::object(py::none());
      for (const char* key : {"zones", "interaction_events"}) PyDict_DelItemString(obs.ptr(), key);
      watch(obs);
      watch(infos);
      if (!hidden.is_none()) watch(hidden);
      for (const py::handle array :
           {py::handle(batch->rewards), py::handle(batch->terminated), py::handle(batch->truncated)}) {
        arrays.emplace_back(py::reinterpret_borrow<py::object>(array), 0);
      }
      for (auto& [array, at_rest] : arrays) at_rest = array.ref_count();
    }
    /// A shallow copy of dict `d`.
    static py::dict copy(const py::handle& d) {
      PyObject* copied = PyDict_Copy(d.ptr());
      if (copied == nullptr) throw py::error_already_set();
      return py::reinterpret_steal<py::dict>(copied);
    }
    /// Notes every array of dict `d`.
    void watch(const py::dict& d) {
      for (const auto& item : d) {
        if (py::isinstance<py::array>(item.second)) {
          arrays.emplace_back(py::reinterpret_borrow<py::object>(item.second), 0);
        }
      }
    }
    /// True when no one but the pool holds any of the batch's arrays; drops the batch's hold on the dicts it last
    /// handed out once no one else holds them.
    bool free() {
      if (batch->obs.ptr() != obs.ptr()) {  // handed out before
        if (batch->obs.ref_count() != 1 || batch->infos.ref_count() != 1) return false;
        batch->obs = py::dict();
        batch->infos = py::dict();
      }
      for (const auto& [array, at_rest] : arrays) {
        if (array.ref_count() != at_rest) return false;
      }
      return true;
    }
    /// The batch with fresh dicts over its arrays (and fresh tuples for the per-row Python objects).
    Batch& hand_out() {
      batch->obs = copy(obs);
      batch->infos = copy(infos);
      if (!hidden.is_none()) batch->infos["privileged"] = copy(hidden);
      batch->obs["zones"] = py::tuple(rows);
      batch->obs["interaction_events"] = py::tuple(rows);
      return *batch;
    }
  };

  std::vector<Entry> entries_;
  std::unique_ptr<Batch> spare_;  // the last batch made while the pool was full
};

/// The label index of `label` on axis `a`, or -1 ("" before coding, or not a label of that axis).
std::int8_t label_index(std::size_t a, std::string_view label) {
  const auto parsed = agents::parse_label(label);
  return parsed && parsed->first == agents::kAxes[a] ? static_cast<std::int8_t>(parsed->second) : std::int8_t{-1};
}

/// Which episode an environment plays: its index and root seed (VecEnv sets them at each reset).
struct EpisodeId {
  std::int64_t index = 0;
  std::uint64_t seed = 0;
};

/// Writes decision `d` of environment `i`, which plays episode `id`, into row `i` of the batch's arrays; plain C++,
/// runs without the GIL.
void fill_row(Batch& b, std::size_t i, const Decision& d, EpisodeId id, const BatchLayout& layout) {
  const Observation& o = d.observation;
  b.episode[i] = id.index;
  b.seed[i] = id.seed;
  const std::size_t items = layout.items.size();
  const std::size_t seats = layout.seats.size();
  constexpr std::size_t axes = agents::kAxisCount;
  b.t[i] = o.t;
  for (std::size_t k = 0; k < items; ++k) {  // an item the observation lacks stays NaN / false
    const std::size_t r = i * items + k;
    b.item_pose[3 * r] = b.item_pose[3 * r + 1] = b.item_pose[3 * r + 2] = kNaN;
    b.item_touched[r] = b.item_held[r] = b.item_visible[r] = false;
  }
  for (std::size_t k = 0; k < o.items.size(); ++k) {
    const auto& item = o.items[k];
    const auto row = layout.item_row(item.name, k);
    if (row < 0) continue;
    const std::size_t r = i * items + static_cast<std::size_t>(row);
    b.item_pose[3 * r] = item.pose.x;
    b.item_pose[3 * r + 1] = item.pose.y;
    b.item_pose[3 * r + 2] = item.pose.theta;
    b.item_touched[r] = item.touched_by_child;
    b.item_held[r] = item.held_by_robot;
    b.item_visible[r] = item.visible;
  }
  for (std::size_t f = 0; f < static_cast<std::size_t>(kFingers); ++f) {
    const std::size_t r = i * kFingers + f;
    b.touch_active[r] = false;
    b.touch_position[2 * r] = b.touch_position[2 * r + 1] = kNaN;
  }
  for (const auto& touch : o.touches) {
    if (touch.finger < 1 || touch.finger > kFingers) continue;
    const std::size_t r = i * kFingers + static_cast<std::size_t>(touch.finger - 1);
    b.touch_active[r] = true;
    b.touch_position[2 * r] = touch.position.x();
    b.touch_position[2 * r + 1] = touch.position.y();
  }
  if (layout.children) {
    for (std::size_t s = 0; s < seats; ++s) {
      const std::size_t r = i * seats + s;
      b.child_perceived[r] = b.child_face[r] = b.child_speaking[r] = b.child_addressing[r] = false;
      b.child_gaze[r] = static_cast<std::int8_t>(policies::PerceivedGaze::Unknown);
      b.child_gaze_on_screen[2 * r] = b.child_gaze_on_screen[2 * r + 1] = kNaN;
      b.child_since_touch[r] = kNaN;
      b.child_moving_item[r] = -1;
    }
    for (const auto& child : o.children) {
      const int s = layout.seat_row(child.seat);
      if (s < 0) continue;
      const std::size_t r = i * seats + static_cast<std::size_t>(s);
      b.child_perceived[r] = true;
      b.child_face[r] = child.face_detected;
      b.child_gaze[r] = static_cast<std::int8_t>(child.gaze);
      if (child.gaze_on_screen) {
        b.child_gaze_on_screen[2 * r] = child.gaze_on_screen->x();
        b.child_gaze_on_screen[2 * r + 1] = child.gaze_on_screen->y();
      }
      b.child_speaking[r] = child.speaking;
      b.child_addressing[r] = child.addressing_robot;
      b.child_since_touch[r] = child.seconds_since_touch;
      if (child.moving_item) b.child_moving_item[r] = layout.item_row(*child.moving_item, items);
    }
  }
  b.self_moving[i] = o.self.moving_item;
  b.self_item[i] = o.self.current_item.empty() ? std::int16_t{-1} : layout.item_row(o.self.current_item, items);
  b.self_speaking[i] = o.self.speaking;
  b.self_reach_centre[2 * i] = o.self.arm_reach_centre.x();
  b.self_reach_centre[2 * i + 1] = o.self.arm_reach_centre.y();
  b.self_reach_radius[i] = o.self.arm_reach_radius;
  b.self_reach_known[i] = o.self.arm_reach_known;

  for (std::size_t r = i * seats * axes; r < (i + 1) * seats * axes; ++r) b.coded[r] = -1;
  for (const auto& [seat, labels] : d.coded) {
    const int s = layout.seat_row(seat);
    if (s < 0) continue;
    for (std::size_t a = 0; a < axes && a < labels.size(); ++a) {
      b.coded[(i * seats + static_cast<std::size_t>(s)) * axes + a] = label_index(a, labels[a]);
    }
  }
  b.has_events[i] = !d.events.empty();
  b.has_results[i] = !d.results.empty();
  if (layout.privileged) {
    for (std::size_t s = 0; s < seats; ++s) {
      const std::size_t r = i * seats + s;
      for (std::size_t a = 0; a < axes; ++a) b.hidden_labels[r * axes + a] = -1;
      b.motivation[r] = b.boredom[r] = b.answer_expectation[r] = kNaN;
      b.wants_to_stop[r] = false;
    }
    for (const auto& [seat, hidden] : d.privileged) {
      const int s = layout.seat_row(seat);
      if (s < 0) continue;
      const std::size_t r = i * seats + static_cast<std::size_t>(s);
      for (std::size_t a = 0; a < axes; ++a) b.hidden_labels[r * axes + a] = label_index(a, hidden.labels[a]);
      b.motivation[r] = hidden.motivation;
      b.boredom[r] = hidden.boredom;
      b.answer_expectation[r] = hidden.answer_expectation;
      b.wants_to_stop[r] = hidden.wants_to_stop;
    }
  }
}

/// Hands each episode its actions, then waits for all of them (they run in parallel); rethrows the first error.
/// Call without the GIL.
void act_all(const std::vector<EnvEpisode*>& episodes, std::vector<std::vector<Action>>& actions) {
  for (std::size_t i = 0; i < episodes.size(); ++i) episodes[i]->hand(std::move(actions[i]));
  std::exception_ptr error;
  for (auto* e : episodes) {
    try {
      e->wait();
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

/// Steps the episodes of a VecEnv together and returns their decisions in the batched layout.
class VecStepper {
 public:
  /// Steps `episodes` (freeplay._EnvEpisode objects, started); rows follow `items` and `seats`; `reward` names a
  /// built-in reward computed here (None: rewards stay 0 for the caller to fill); `dt` is a step's simulated seconds.
  VecStepper(py::list episodes, std::vector<std::string> items, std::vector<std::string> seats, bool children,
             bool privileged, const std::optional<std::string>& reward, double dt)
      : owners_(std::move(episodes)),
        dt_(dt),
        zones_(owners_.size()),
        ids_(owners_.size()),
        slots_(owners_.size(), Slot::Held),
        signal_(std::make_shared<ReadySignal>()) {
    for (const auto& e : owners_) {
      episodes_.push_back(e.cast<EnvEpisode*>());
      episodes_.back()->signal_to(signal_);
    }
    layout_.items = std::move(items);
    layout_.seats = std::move(seats);
    layout_.children = children;
    layout_.privileged = privileged;
    for (std::size_t k = 0; k < layout_.items.size(); ++k) {
      layout_.item_rows.emplace(layout_.items[k], static_cast<std::int16_t>(k));
    }
    if (reward) reward_ = builtin_reward_named(*reward);
  }

  /// Hands environment i `actions[i]`, runs all of them to their next decision with the GIL released, and returns
  /// (observations, rewards, terminated, truncated, infos, indices of the environments whose episode ended).
  py::tuple step(const py::sequence& actions) {
    const auto n = episodes_.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (slots_[i] != Slot::Held) {
        throw py::value_error(fmt::format("VecEnv.step() while environment {} is sent or reset asynchronously: recv() "
                                          "it first, or reset()", i));
      }
    }
    if (static_cast<std::size_t>(py::len(actions)) != n) {
      throw InputError(fmt::format("{} action lists for {} environments", py::len(actions), n), "actions",
                       "one action list per environment");
    }
    std::vector<std::vector<Action>> parsed;
    parsed.reserve(n);
    for (const auto a : actions) parsed.push_back(actions_from_python(a, "freeplay.VecEnv"));
    Batch& b = batches_.take(layout_, static_cast<py::ssize_t>(n));
    auto* rewards = b.rewards.mutable_data();
    auto* terminated = b.terminated.mutable_data();
    auto* truncated = b.truncated.mutable_data();
    {
      py::gil_scoped_release release;
      act_all(episodes_, parsed);
      for (std::size_t i = 0; i < n; ++i) {
        const EnvEpisode& e = *episodes_[i];
        fill_row(b, i, e.decision(), ids_[i], layout_);
        rewards[i] = reward_ ? reward_of(e.decision()) : 0.0;
        terminated[i] = e.finished() && !e.hit_cap();
        truncated[i] = e.finished() && e.hit_cap();
      }
    }
    py::list finished;
    for (std::size_t i = 0; i < n; ++i) {
      fill_objects(b, i, i);
      if (episodes_[i]->finished()) finished.append(i);
    }
    return py::make_tuple(b.obs, b.rewards, b.terminated, b.truncated, b.infos, finished);
  }

  /// The current decisions (after a reset) in the batched layout: (observations, infos).
  py::tuple gather() {
    Batch& b = batches_.take(layout_, static_cast<py::ssize_t>(episodes_.size()));
    for (std::size_t i = 0; i < episodes_.size(); ++i) {
      fill_row(b, i, episodes_[i]->decision(), ids_[i], layout_);
      fill_objects(b, i, i);
    }
    return py::make_tuple(b.obs, b.infos);
  }

  /// Marks every environment as just reset: `asynchronous`, each waits to be received (async_reset), else each
  /// waits for its actions (reset).
  void begin(bool asynchronous) { slots_.assign(episodes_.size(), asynchronous ? Slot::Reset : Slot::Held); }

  /// Hands environment env_ids[j] the actions `actions[j]` and returns at once; each must have been received since
  /// its last send (or reset with reset()).
  void send(const py::sequence& actions, const std::vector<py::ssize_t>& env_ids) {
    if (static_cast<std::size_t>(py::len(actions)) != env_ids.size()) {
      throw InputError(fmt::format("{} action lists for {} environment ids", py::len(actions), env_ids.size()),
                       "actions", "one action list per environment id");
    }
    std::vector<bool> seen(episodes_.size(), false);
    for (const auto id : env_ids) {
      if (id < 0 || static_cast<std::size_t>(id) >= episodes_.size()) {
        throw py::index_error(fmt::format("no environment {}: the ids are 0 to {}", id, episodes_.size() - 1));
      }
      const auto i = static_cast<std::size_t>(id);
      if (seen[i]) throw py::value_error(fmt::format("environment {} is sent twice", id));
      seen[i] = true;
      if (slots_[i] != Slot::Held) {
        throw py::value_error(fmt::format("environment {} has not been received since its last {}: recv() it first",
                                          id, slots_[i] == Slot::Reset ? "reset" : "send"));
      }
    }
    std::vector<std::vector<Action>> parsed;
    parsed.reserve(env_ids.size());
    for (const auto a : actions) parsed.push_back(actions_from_python(a, "freeplay.VecEnv"));
    for (std::size_t j = 0; j < env_ids.size(); ++j) {
      const auto i = static_cast<std::size_t>(env_ids[j]);
      episodes_[i]->hand(std::move(parsed[j]));
      slots_[i] = Slot::Sent;
    }
  }

  /// Waits (GIL released) until `batch` of the environments sent or reset asynchronously are ready and returns
  /// them in the batched layout, rows in the order they are taken: (observations, rewards, terminated, truncated,
  /// infos with "env_id", rows whose episode ended, rows that hold a reset's first decision).
  py::tuple recv(std::size_t batch) {
    const auto pending = static_cast<std::size_t>(
        std::count_if(slots_.begin(), slots_.end(), [](Slot s) { return s != Slot::Held; }));
    if (batch < 1 || batch > pending) {
      throw py::value_error(fmt::format("recv() of {} environments while {} are sent or reset: send() first", batch,
                                        pending));
    }
    Batch& b = batches_.take(layout_, static_cast<py::ssize_t>(batch));
    py::array_t<std::int64_t> env_ids(static_cast<py::ssize_t>(batch));
    auto* ids = env_ids.mutable_data();
    auto* rewards = b.rewards.mutable_data();
    auto* terminated = b.terminated.mutable_data();
    auto* truncated = b.truncated.mutable_data();
    std::vector<std::size_t> taken;
    {
      py::gil_scoped_release release;
      taken = take_ready(batch);
      std::exception_ptr error;
      for (std::size_t row = 0; row < batch; ++row) {
        const auto i = taken[row];
        EnvEpisode& e = *episodes_[i];
        try {
          e.wait();  // returns at once (ready); rethrows what stopped the episode
        } catch (...) {
          if (!error) error = std::current_exception();
        }
        ids[row] = static_cast<std::int64_t>(i);
        fill_row(b, row, e.decision(), ids_[i], layout_);
        rewards[row] = reward_ && slots_[i] == Slot::Sent ? reward_of(e.decision()) : 0.0;
        terminated[row] = e.finished() && !e.hit_cap();
        truncated[row] = e.finished() && e.hit_cap();
      }
      if (error) {
        for (const auto i : taken) slots_[i] = Slot::Held;
        std::rethrow_exception(error);
      }
    }
    py::list finished;
    py::list reset;
    for (std::size_t row = 0; row < batch; ++row) {
      const auto i = taken[row];
      fill_objects(b, row, i);
      if (episodes_[i]->finished()) finished.append(row);
      if (slots_[i] == Slot::Reset) reset.append(row);
      slots_[i] = Slot::Held;
    }
    b.infos["env_id"] = env_ids;
    return py::make_tuple(b.obs, b.rewards, b.terminated, b.truncated, b.infos, finished, reset);
  }

  /// Notes that environment i now plays episode `index` of root seed `seed` (infos["episode"], infos["seed"]).
  void set_episode(std::size_t i, std::int64_t index, std::uint64_t seed) {
    if (i >= ids_.size()) throw py::index_error("no such environment");
    ids_[i] = {index, seed};
  }

  /// Rewrites row `row` of a step's (or a recv's) `obs` and `infos` with environment `env`'s current decision (after
  /// its reset).
  void write_row(std::size_t row, std::size_t env, py::dict obs, py::dict infos) {
    if (env >= episodes_.size()) throw py::index_error("no such environment");
    Batch b(layout_, 0, false, obs, infos);
    fill_row(b, row, episodes_[env]->decision(), ids_[env], layout_);
    fill_objects(b, row, env);
  }

 private:
  /// The built-in reward of decision `d` (its children's coded social-engagement labels).
  double reward_of(const Decision& d) const {
    return builtin_reward(*reward_, dt_, [&](auto&& add) {
      constexpr auto social = static_cast<std::size_t>(agents::Axis::SocialEngagement);
      for (const auto& [seat, labels] : d.coded) {
        add(labels.size() > social ? std::string_view(labels[social]) : std::string_view());
      }
    });
  }

  /// Where an environment stands in asynchronous stepping (send/recv).
  enum class Slot {
    Held,   ///< received (or reset synchronously): waits for its actions from send() or step()
    Sent,   ///< handed its actions: stepping, or ready to be received
    Reset,  ///< reset by async_reset: its first decision is ready to be received
  };

  /// Waits until `batch` environments that are sent or reset are ready (the caller checked that as many are) and
  /// returns their indices; the scan starts after the environment taken last, so that none waits for ever.
  std::vector<std::size_t> take_ready(std::size_t batch) {
    const auto n = episodes_.size();
    std::vector<std::size_t> taken;
    std::vector<bool> chosen(n, false);
    const auto scan = [&] {
      for (std::size_t k = 0; k < n && taken.size() < batch; ++k) {
        const auto i = (next_ + k) % n;
        if (!chosen[i] && slots_[i] != Slot::Held && episodes_[i]->ready()) {
          chosen[i] = true;
          taken.push_back(i);
        }
      }
      return taken.size() == batch;
    };
    while (true) {
      std::uint64_t seen = 0;
      {
        std::lock_guard lock(signal_->mutex);
        seen = signal_->posts;
      }
      if (scan() || poll_before_sleeping(scan)) break;
      std::unique_lock lock(signal_->mutex);
      signal_->cv.wait(lock, [&] { return signal_->posts != seen; });
    }
    next_ = (taken.back() + 1) % n;
    return taken;
  }

  /// Environment `env`'s Python-object entries, put in row `i`: its zones, interaction events, events and action
  /// results.
  void fill_objects(Batch& b, std::size_t i, std::size_t env) {
    const Decision& d = episodes_[env]->decision();
    auto& cache = zones_[env];
    if (!cache.python || cache.version != d.zones_version) {
      const auto& current = d.observation.zones;
      py::tuple zones(current.size());
      for (std::size_t z = 0; z < current.size(); ++z) zones[z] = py::cast(current[z]);
      cache.python = zones;
      cache.version = d.zones_version;
    }
    py::object interaction = empty_;
    if (!d.observation.interaction_events.empty()) interaction = py::tuple(py::cast(d.observation.interaction_events));
    set_tuple_item(b.obs, "zones", i, cache.python);
    set_tuple_item(b.obs, "interaction_events", i, interaction);
    if (!d.events.empty()) {
      py::list events(d.events.size());
      for (std::size_t k = 0; k < d.events.size(); ++k) events[k] = json_to_python(d.events[k]);
      set_object(b.events, i, events);
    } else {
      set_object(b.events, i, py::none());
    }
    set_object(b.results, i, d.results.empty() ? py::object(py::none()) : py::object(py::cast(d.results)));
  }

  /// Puts `value` at index `i` of the tuple `d[key]`: in place while the tuple is only the batch's (a step being
  /// made), else as a new tuple.
  static void set_tuple_item(py::dict& d, const char* key, std::size_t i, const py::object& value) {
    py::tuple tuple = d[key];
    if (tuple.ref_count() > 2) {  // the dict's reference and ours: otherwise someone else holds it
      py::tuple copy(tuple.size());
      for (std::size_t k = 0; k < tuple.size(); ++k) copy[k] = tuple[k];
      tuple = copy;
      d[key] = tuple;
    }
    PyObject* old = PyTuple_GET_ITEM(tuple.ptr(), static_cast<py::ssize_t>(i));
    PyTuple_SET_ITEM(tuple.ptr(), static_cast<py::ssize_t>(i), value.inc_ref().ptr());
    Py_XDECREF(old);
  }

  /// One environment's zones as last handed to Python (they change rarely: the tuple is reused until they do).
  struct ZoneCache {
    std::uint64_t version = 0;  ///< the Decision::zones_version they are
    py::object python;          ///< the tuple of ZoneObservation
  };

  py::list owners_;  // the _EnvEpisode objects (kept alive)
  std::vector<EnvEpisode*> episodes_;
  BatchLayout layout_;
  std::optional<BuiltinReward> reward_;
  double dt_ = 0.1;
  std::vector<ZoneCache> zones_;
  std::vector<EpisodeId> ids_;
  std::vector<Slot> slots_;              // per environment, its place in asynchronous stepping
  std::size_t next_ = 0;                 // where recv's next scan for ready environments starts
  std::shared_ptr<ReadySignal> signal_;  // posted to by every episode when it is ready
  py::tuple empty_;
  BatchPool batches_;  // the arrays of batches handed out, reused once Python dropped them
};

}  // namespace

void bind_vec_env(py::module_& m) {
  py::class_<VecStepper>(m, "_VecStepper", "Steps a VecEnv's episodes together into the batched layout.")
      .def(py::init<py::list, std::vector<std::string>, std::vector<std::string>, bool, bool,
                    const std::optional<std::string>&, double>(),
           py::arg("episodes"), py::arg("items"), py::arg("seats"), py::arg("children"), py::arg("privileged"),
           py::arg("reward"), py::arg("dt"))
      .def("step", &VecStepper::step, py::arg("actions"))
      .def("gather", &VecStepper::gather)
      .def("set_episode", &VecStepper::set_episode, py::arg("i"), py::arg("index"), py::arg("seed"))
      .def("write_row", &VecStepper::write_row, py::arg("row"), py::arg("env"), py::arg("obs"), py::arg("infos"))
      .def("begin", &VecStepper::begin, py::arg("asynchronous"))
      .def("send", &VecStepper::send, py::arg("actions"), py::arg("env_ids"))
      .def("recv", &VecStepper::recv, py::arg("batch"));
  m.def("_builtin_reward", [](const std::string& name, double dt, const std::vector<std::string>& social) {
    return builtin_reward(builtin_reward_named(name), dt, [&](auto&& add) {
      for (const auto& label : social) add(std::string_view(label));
    });
  }, py::arg("name"), py::arg("dt"), py::arg("social"),
        "Built-in reward `name` of a step of `dt` seconds whose children are coded with social-engagement labels "
        "`social`.");
  m.def("_vec_layout", [] {
    std::vector<std::string> items;
    for (const auto& item : runner::SharedModels::shipped().catalogue->items()) items.push_back(item.name);
    // The children of a child-robot episode sit where the robot does not (runner/src/sim_world.cpp seats them).
    std::vector<std::string> seats;
    for (const char* seat : {"purple", "yellow"}) {
      if (seat != policies::PolicyContext{}.robot_seat) seats.emplace_back(seat);
    }
    return py::make_tuple(items, seats);
  }, "(item names, child seats): the item and seat axes of VecEnv's batched arrays (an Env's episodes use the "
     "shipped catalogue, as PolicyContext.item_names lists it).");
  py::tuple labels(agents::kAxisCount);
  for (std::size_t a = 0; a < agents::kAxisCount; ++a) {
    py::tuple names(agents::label_count(agents::kAxes[a]));
    for (std::size_t k = 0; k < names.size(); ++k) {
      names[k] = py::str(std::string(agents::label_name(agents::kAxes[a], k)));
    }
    labels[a] = names;
  }
  m.attr("LABELS") = labels;  // per axis (task, social engagement, social attitude), the labels in coding order
  py::tuple joint(agents::kJointPlay.size());
  for (std::size_t k = 0; k < agents::kJointPlay.size(); ++k) {
    joint[k] = py::str(std::string(agents::name(agents::kJointPlay[k])));
  }
  m.attr("JOINT_PLAY") = joint;
}

}  // namespace freeplay::python
