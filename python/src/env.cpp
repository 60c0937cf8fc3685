// The episode stepper behind freeplay.Env: the real episode loop runs on a worker thread; its policy posts each
// decision's observation (with the observable events and coded labels since the previous one) and waits for the
// actions that `act` hands over. The GIL is released while C++ runs.

#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "bindings.hpp"
#include "env_channel.hpp"
#include "freeplay/agents/labels.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/scenario/suite.hpp"

namespace freeplay::python {

namespace {

/// One decision handed to Python: the observation and what happened since the previous decision.
struct Decision {
  policies::Observation observation;                 ///< what the policy sees
  std::vector<nlohmann::json> events;                ///< event-log entries since the previous decision
  std::vector<policies::ActionResult> results;       ///< moves and utterances that ended since then
  std::map<std::string, std::vector<std::string>> coded;  ///< per child seat: the coder's current labels
  /// Per child seat: the child model's hidden state; filled only for an Env that asked for privileged information.
  std::map<std::string, runner::ChildHiddenState> privileged;
};

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

class EnvEpisode;
thread_local EnvEpisode* t_env_episode = nullptr;  // the episode the current worker thread runs, if any

/// One episode of an Env: a worker thread running runner::run_episode and the decision channel.
class EnvEpisode {
 public:
  /// Loads the scenario (as `freeplay run` would) for stepping; it must be a child-robot scenario.
  /// `privileged` also keeps the children's hidden state at each decision (Env(privileged=True)).
  EnvEpisode(const std::string& file, const std::vector<std::string>& overrides, bool perceives_children,
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
  ~EnvEpisode() { stop_worker(); }
  EnvEpisode(const EnvEpisode&) = delete;
  EnvEpisode& operator=(const EnvEpisode&) = delete;

  /// Starts the episode with root seed `seed` and waits for its first decision (or its end).
  void start(std::uint64_t seed) {
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

  /// Hands the actions of the current decision to the episode (returns at once).
  void hand(std::vector<policies::Action> actions) {
    std::lock_guard lock(mutex_);
    if (state_ != State::Deciding) throw InputError("step() after the episode ended: call reset()", "step", "reset(), then step()");
    actions_ = std::move(actions);
    state_ = State::Running;
    cv_.notify_all();
  }

  /// Waits until the episode asks for the next decision or ends; rethrows what stopped it.
  void wait() {
    poll_briefly([&] { return state_.load() != State::Running; });
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return state_ != State::Running; });
    if (error_) {
      auto error = error_;
      error_ = nullptr;
      std::rethrow_exception(error);
    }
  }

  /// True when the episode has ended.
  bool finished() const { return state_ == State::Finished; }
  /// The current decision (the last one once the episode ended).
  const Decision& decision() const { return decided_; }
  /// The record of the finished episode (its line of episodes.jsonl), or null.
  nlohmann::json record() const { return result_ ? result_->record : nlohmann::json(); }
  /// The finished episode's event log as JSON Lines.
  std::string events_jsonl() const { return result_ ? result_->events.to_jsonl() : std::string(); }
  /// True when free play stopped at the cap.
  bool hit_cap() const { return result_ && result_->hit_cap; }

  /// Called by the channel policy on the worker thread at each decision: posts it and waits for the actions.
  std::vector<policies::Action> decide(const policies::Observation& observation) {
    std::unique_lock lock(mutex_);
    pending_.observation = observation;
    decided_ = std::move(pending_);
    pending_ = Decision{};
    state_ = State::Deciding;
    cv_.notify_all();
    lock.unlock();
    poll_briefly([&] { return state_.load() != State::Deciding || stop_.load(); });
    lock.lock();
    cv_.wait(lock, [&] { return state_ != State::Deciding || stop_.load(); });
    return stop_.load() ? std::vector<policies::Action>{} : std::move(actions_);
  }
  /// Called by the channel policy when a move or an utterance ended.
  void result(const policies::ActionResult& r) {
    std::lock_guard lock(mutex_);
    pending_.results.push_back(r);
  }
  /// Called by the observer at every free-play tick.
  void observe(const runner::EpisodeSnapshot& snapshot) {
    std::lock_guard lock(mutex_);
    for (const auto& e : snapshot.new_events) pending_.events.push_back(e.to_json());
    if (snapshot.stage != "freeplay") return;
    for (const auto& child : snapshot.children) {
      auto& labels = pending_.coded[child.seat];
      labels.assign(child.coded.begin(), child.coded.end());
      if (privileged_) pending_.privileged[child.seat] = child.hidden;
    }
  }
  /// Called by the channel policy when the episode resets it: keeps the policy's context and random stream.
  void reset_policy(const policies::PolicyContext& context, Rng rng) {
    std::lock_guard lock(mutex_);
    context_ = context;
    policy_rng_ = rng;
  }
  /// The context the episode gave its policy.
  const policies::PolicyContext& context() const { return context_; }
  /// The policy's random stream as the episode handed it over (the same as a run's policy gets).
  Rng policy_rng() const { return policy_rng_; }
  /// The channel policy's perceives_children().
  bool perceives_children() const { return perceives_children_; }
  /// True when the decisions carry the children's hidden state.
  bool privileged() const { return privileged_; }

 private:
  enum class State { Running, Deciding, Finished };

  /// The observer that feeds events and coded labels to the decisions.
  class Observer final : public runner::EpisodeObserver {
   public:
    explicit Observer(EnvEpisode& episode) : episode_(episode) {}
    void observe(const runner::EpisodeSnapshot& snapshot) override { episode_.observe(snapshot); }

   private:
    EnvEpisode& episode_;
  };

  void work(std::uint64_t seed) {
    t_env_episode = this;
    g_live_workers.fetch_add(1);
    std::optional<runner::EpisodeResult> result;
    std::exception_ptr error;
    try {
      runner::EpisodeObservers observers;
      observers.push_back(std::make_unique<Observer>(*this));
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
  }

  void stop_worker() {
    if (!worker_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      stop_.store(true);
      cv_.notify_all();
    }
    worker_.join();
  }

  scenario::Scenario scenario_;
  bool perceives_children_ = false;
  bool privileged_ = false;
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::atomic<State> state_ = State::Finished;  // written under mutex_, polled without it
  std::atomic<bool> stop_{false};
  Decision pending_;
  Decision decided_;
  std::vector<policies::Action> actions_;
  std::optional<runner::EpisodeResult> result_;
  std::exception_ptr error_;
  policies::PolicyContext context_;
  Rng policy_rng_;
};

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
  if (!d.events.empty()) {
    const auto loads = py::module_::import("json").attr("loads");
    for (const auto& event : d.events) events.append(loads(event.dump()));
  }
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
      .def("record", [](const EnvEpisode& e) { return py::module_::import("json").attr("loads")(e.record().dump()); })
      .def("events_jsonl", &EnvEpisode::events_jsonl);
  m.def("_act_all", [](const std::vector<EnvEpisode*>& episodes, const std::vector<py::object>& actions) {
    if (episodes.size() != actions.size()) {
      throw InputError(fmt::format("{} action lists for {} environments", actions.size(), episodes.size()), "actions",
                       "one action list per environment");
    }
    std::vector<std::vector<policies::Action>> parsed;
    for (const auto& a : actions) parsed.push_back(actions_from_python(a, "freeplay.VecEnv"));
    py::gil_scoped_release release;
    for (std::size_t i = 0; i < episodes.size(); ++i) episodes[i]->hand(std::move(parsed[i]));
    std::exception_ptr error;
    for (auto* e : episodes) {
      try {
        e->wait();
      } catch (...) {
        if (!error) error = std::current_exception();
      }
    }
    if (error) std::rethrow_exception(error);
  }, py::arg("episodes"), py::arg("actions"), "Hands each episode its actions, then waits for all (in parallel).");
}

}  // namespace freeplay::python
