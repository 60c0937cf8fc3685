// The episode stepper behind freeplay.Env (env_episode.hpp): the real episode loop runs on a worker thread; its policy
// posts each decision's observation (with the observable events and coded labels since the previous one) and waits
// for the actions that `act` hands over. The GIL is released while C++ runs.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "bindings.hpp"
#include "env_channel.hpp"
#include "env_episode.hpp"
#include "freeplay/agents/labels.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/suite.hpp"

namespace freeplay::python {

namespace {

/// How long a thread that waits for the other side of an episode (the stepping thread for the next decision, the
/// worker for the actions) polls before it sleeps on the condition variable. A decision costs about 10 µs of
/// simulation and a sleep-and-wake costs about as much again on each side, so polling first halves a step's
/// hand-over when every thread has a core of its own; a long wait (Python thinking, an idle env) still sleeps.
constexpr auto kPollBeforeSleep = std::chrono::microseconds(100);

/// Episode worker threads alive in this process (all Envs and VecEnvs together).
std::atomic<unsigned> g_live_workers{0};

/// True when the episode workers fit on the machine's cores: only then does polling pay. The stepping thread is not
/// counted: it waits while the workers simulate and they wait while it works, and each poll yields the core between
/// tries, so a waiting side gives way to a working one (2 environments on 2 cores: 0.36x -> 1.1-1.2x, docs/python.md).
bool threads_fit_cores() {
  static const unsigned cores = std::max(1U, std::thread::hardware_concurrency());
  return g_live_workers.load(std::memory_order_relaxed) <= cores;
}

/// Polls `done` (yielding the core between tries) for at most kPollBeforeSleep, when threads fit the cores; true
/// when `done` became true.
template <class Done>
bool poll_briefly(Done done) {
  if (!threads_fit_cores()) return done();
  const auto until = std::chrono::steady_clock::now() + kPollBeforeSleep;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::yield();
  }
  return true;
}

}  // namespace

bool poll_before_sleeping(const std::function<bool()>& done) { return poll_briefly(done); }

namespace {

/// True when two zone lists are the same (colours, centroids and polygons).
bool same_zones(const std::vector<policies::ZoneObservation>& a, const std::vector<policies::ZoneObservation>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t z = 0; z < a.size(); ++z) {
    if (a[z].colour != b[z].colour || a[z].centroid != b[z].centroid || a[z].polygon != b[z].polygon) return false;
  }
  return true;
}

thread_local EnvEpisode* t_env_episode = nullptr;  // the episode the current worker thread runs, if any

/// The observer that feeds events and coded labels to an EnvEpisode's decisions.
class DecisionObserver final : public runner::EpisodeObserver {
 public:
  explicit DecisionObserver(EnvEpisode& episode) : episode_(episode) {}
  void observe(const runner::EpisodeSnapshot& snapshot) override { episode_.observe(snapshot); }

 private:
  EnvEpisode& episode_;
};

}  // namespace

EnvEpisode::EnvEpisode(const std::string& file, const std::vector<std::string>& overrides, bool perceives_children,
                       bool privileged)
    : perceives_children_(perceives_children), privileged_(privileged) {
  auto suite = scenario::single_scenario_suite(file, overrides, python_vocabulary());
  scenario_ = std::move(suite.variants.front().scenario);
  if (scenario_.condition != scenario::Condition::ChildRobot) {
    throw InputError(fmt::format("freeplay.Env steps the robot, but scenario '{}' is {}", scenario_.name,
                                 scenario::to_string(scenario_.condition)),
                     "condition", std::string(scenario::to_string(scenario::Condition::ChildRobot)), {file, 1, 1});
  }
  scenario_.robot.policy = std::string(policies::kPythonPolicyPrefix) + "env";
}

EnvEpisode::~EnvEpisode() { stop_worker(); }

void EnvEpisode::start(std::uint64_t seed) {
  stop_worker();
  {
    std::lock_guard lock(mutex_);
    state_ = State::Running;
    result_.reset();
    error_ = nullptr;
    pending_ = Decision{};
    stop_.store(false);
  }
  worker_ = std::thread([this, seed] { work(seed); });
  wait();
}

void EnvEpisode::hand(std::vector<policies::Action> actions) {
  std::lock_guard lock(mutex_);
  if (state_ != State::Deciding) throw InputError("step() after the episode ended: call reset()", "step", "reset(), then step()");
  actions_ = std::move(actions);
  state_ = State::Running;
  cv_.notify_all();
}

void EnvEpisode::wait() {
  poll_briefly([&] { return state_.load() != State::Running; });
  std::unique_lock lock(mutex_);
  cv_.wait(lock, [&] { return state_ != State::Running; });
  if (error_) {
    auto error = error_;
    error_ = nullptr;
    std::rethrow_exception(error);
  }
}

std::vector<policies::Action> EnvEpisode::decide(const policies::Observation& observation) {
  // decided_ is written only on this thread, so reading it here needs no lock; comparing the zones here keeps the
  // comparison off the stepping thread, which then compares version numbers.
  const bool zones_changed = !same_zones(observation.zones, decided_.observation.zones);
  std::unique_lock lock(mutex_);
  pending_.observation = observation;  // reuses the buffers of the decision before the last one
  pending_.zones_version = decided_.zones_version + (zones_changed ? 1U : 0U);
  std::swap(decided_, pending_);
  pending_.events.clear();
  pending_.results.clear();
  pending_.coded.clear();
  pending_.privileged.clear();
  state_ = State::Deciding;
  cv_.notify_all();
  lock.unlock();
  if (signal_) signal_->post();
  poll_briefly([&] { return state_.load() != State::Deciding || stop_.load(); });
  lock.lock();
  cv_.wait(lock, [&] { return state_ != State::Deciding || stop_.load(); });
  return stop_.load() ? std::vector<policies::Action>{} : std::move(actions_);
}

void EnvEpisode::result(const policies::ActionResult& r) {
  std::lock_guard lock(mutex_);
  pending_.results.push_back(r);
}

void EnvEpisode::observe(const runner::EpisodeSnapshot& snapshot) {
  std::lock_guard lock(mutex_);
  for (const auto& e : snapshot.new_events) pending_.events.push_back(e.to_json());
  if (snapshot.stage != "freeplay") return;
  for (const auto& child : snapshot.children) {
    auto& labels = pending_.coded[child.seat];
    labels.assign(child.coded.begin(), child.coded.end());
    if (privileged_) pending_.privileged[child.seat] = child.hidden;
  }
}

void EnvEpisode::reset_policy(const policies::PolicyContext& context, Rng rng) {
  std::lock_guard lock(mutex_);
  context_ = context;
  policy_rng_ = rng;
}

void EnvEpisode::work(std::uint64_t seed) {
  t_env_episode = this;
  g_live_workers.fetch_add(1);
  std::optional<runner::EpisodeResult> result;
  std::exception_ptr error;
  try {
    runner::EpisodeObservers observers;
    observers.push_back(std::make_unique<DecisionObserver>(*this));
    result = runner::run_episode({.scenario = scenario_, .seed = seed, .stop = stop_, .id = scenario_.name + "-env"},
                                 runner::observed_by(observers));
  } catch (...) {
    error = std::current_exception();
  }
  t_env_episode = nullptr;
  g_live_workers.fetch_sub(1);
  std::lock_guard lock(mutex_);
  if (result && !result->aborted) result_ = std::move(result);
  error_ = error;
  if (!pending_.events.empty() || !pending_.results.empty()) {  // what happened after the last decision
    for (auto& e : pending_.events) decided_.events.push_back(std::move(e));
    for (auto& r : pending_.results) decided_.results.push_back(r);
    for (auto& [seat, labels] : pending_.coded) decided_.coded[seat] = labels;
    for (auto& [seat, hidden] : pending_.privileged) decided_.privileged[seat] = hidden;
  }
  state_ = State::Finished;
  cv_.notify_all();
  if (signal_) signal_->post();
}

void EnvEpisode::stop_worker() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_.store(true);
    cv_.notify_all();
  }
  worker_.join();
}

namespace {

/// The policy of an Env episode: forwards decisions and results to its EnvEpisode.
class ChannelPolicy final : public policies::PlayPolicy {
 public:
  explicit ChannelPolicy(EnvEpisode& episode) : episode_(episode) {}
  std::string name() const override { return "python:env"; }
  void reset(const policies::PolicyContext& context, Rng rng) override { episode_.reset_policy(context, rng); }
  std::vector<policies::Action> decide(const policies::Observation& observation) override { return episode_.decide(observation); }
  void on_result(const policies::ActionResult& result) override { episode_.result(result); }
  bool perceives_children() const override { return episode_.perceives_children(); }

 private:
  EnvEpisode& episode_;
};

py::dict decision_info(const EnvEpisode& e) {
  const auto& d = e.decision();
  py::dict info;
  py::list events;
  for (const auto& event : d.events) events.append(json_to_python(event));
  info["events"] = events;
  info["results"] = py::cast(d.results);
  info["coded"] = py::cast(d.coded);
  info["t"] = d.observation.t;
  if (e.privileged()) {
    py::dict privileged;
    for (const auto& [seat, hidden] : d.privileged) {
      py::dict labels;
      for (std::size_t a = 0; a < agents::kAxisCount; ++a) {
        labels[py::str(agents::axis_name(agents::kAxes[a]))] = py::str(hidden.labels[a]);
      }
      py::dict child;
      child["labels"] = labels;
      child["motivation"] = hidden.motivation;
      child["boredom"] = hidden.boredom;
      child["answer_expectation"] = hidden.answer_expectation;
      child["wants_to_stop"] = hidden.wants_to_stop;
      privileged[py::str(seat)] = child;
    }
    info["privileged"] = privileged;
  }
  return info;
}

}  // namespace

py::object json_to_python(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return py::none();
    case nlohmann::json::value_t::boolean: return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(value.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(value.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double x = value.get<double>();
      return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::none());  // as its JSON text reads back
    }
    case nlohmann::json::value_t::string: return py::str(value.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list list(value.size());
      std::size_t i = 0;
      for (const auto& element : value) list[i++] = json_to_python(element);
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (const auto& [key, element] : value.items()) dict[py::str(key)] = json_to_python(element);
      return dict;
    }
    default: return py::none();  // binary and discarded values do not occur in records and events
  }
}

std::unique_ptr<policies::PlayPolicy> make_env_channel_policy() {
  if (t_env_episode == nullptr) return nullptr;
  return std::make_unique<ChannelPolicy>(*t_env_episode);
}

void bind_env(py::module_& m) {
  py::class_<EnvEpisode>(m, "_EnvEpisode", "One episode stepped decision by decision (freeplay.Env uses it).")
      .def(py::init<const std::string&, const std::vector<std::string>&, bool, bool>(), py::arg("file"),
           py::arg("overrides"), py::arg("perceives_children"), py::arg("privileged") = false)
      .def("start", &EnvEpisode::start, py::arg("seed"), py::call_guard<py::gil_scoped_release>())
      .def("act", [](EnvEpisode& e, const py::handle& actions) {
        auto parsed = actions_from_python(actions, "freeplay.Env");
        py::gil_scoped_release release;
        e.hand(std::move(parsed));
        e.wait();
      }, py::arg("actions"))
      .def_property_readonly("finished", &EnvEpisode::finished)
      .def_property_readonly("hit_cap", &EnvEpisode::hit_cap)
      .def_property_readonly("observation", [](const EnvEpisode& e) { return e.decision().observation; })
      .def("info", &decision_info)
      .def_property_readonly("context", &EnvEpisode::context)
      .def_property_readonly("policy_rng", &EnvEpisode::policy_rng)
      .def("record", [](const EnvEpisode& e) { return json_to_python(e.record()); })
      .def("events_jsonl", &EnvEpisode::events_jsonl);
}

}  // namespace freeplay::python
