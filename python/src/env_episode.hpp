#pragma once
// One episode of `freeplay.Env` stepped decision by decision: the real episode loop runs on a worker thread; its
// policy posts each decision's observation (with the observable events and coded labels since the previous one) and
// waits for the actions handed over. env.cpp binds it for Env; vec_env.cpp steps several at once for VecEnv.

#include <nlohmann/json.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "freeplay/core/rng.hpp"
#include "freeplay/policies/play_policy.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/runner/episode_observer.hpp"
#include "freeplay/scenario/scenario.hpp"

namespace freeplay::python {

/// One decision handed to Python: the observation and what happened since the previous decision.
struct Decision {
  policies::Observation observation;                 ///< what the policy sees
  std::vector<nlohmann::json> events;                ///< event-log entries since the previous decision
  std::vector<policies::ActionResult> results;       ///< moves and utterances that ended since then
  std::map<std::string, std::vector<std::string>> coded;  ///< per child seat: the coder's current labels
  /// Per child seat: the child model's hidden state; filled only for an Env that asked for privileged information.
  std::map<std::string, runner::ChildHiddenState> privileged;
  /// Counts the changes of `observation.zones` (they change rarely; VecEnv reuses their Python objects until then).
  std::uint64_t zones_version = 0;
};

/// Wakes a thread that waits for whichever of several episodes is ready first (VecEnv.recv): each episode that
/// signals to it posts when it has a decision for the stepping thread or has ended.
struct ReadySignal {
  std::mutex mutex;
  std::condition_variable cv;
  std::uint64_t posts = 0;  ///< decisions and ends posted so far (guarded by `mutex`)

  /// Counts one more post and wakes the waiting thread.
  void post() {
    {
      std::lock_guard lock(mutex);
      ++posts;
    }
    cv.notify_all();
  }
};

/// Polls `done` briefly (yielding the core between tries) when the episode workers fit the machine's cores, as the
/// two sides of an episode do before they sleep; true when `done` became true (env.cpp holds the rule).
bool poll_before_sleeping(const std::function<bool()>& done);

/// One episode of an Env: a worker thread running runner::run_episode and the decision channel.
class EnvEpisode {
 public:
  /// Loads the scenario (as `freeplay run` would) for stepping; it must be a child-robot scenario.
  /// `privileged` also keeps the children's hidden state at each decision (Env(privileged=True)).
  EnvEpisode(const std::string& file, const std::vector<std::string>& overrides, bool perceives_children,
             bool privileged);
  ~EnvEpisode();
  EnvEpisode(const EnvEpisode&) = delete;
  EnvEpisode& operator=(const EnvEpisode&) = delete;

  /// Starts the episode with root seed `seed` and waits for its first decision (or its end).
  void start(std::uint64_t seed);
  /// Hands the actions of the current decision to the episode (returns at once).
  void hand(std::vector<policies::Action> actions);
  /// Waits until the episode asks for the next decision or ends; rethrows what stopped it.
  void wait();

  /// True when the episode waits for actions or has ended: wait() then returns at once.
  bool ready() const { return state_.load() != State::Running; }
  /// Posts to `signal` from now on at each decision and at the end (VecEnv's asynchronous stepping); call while
  /// no episode runs.
  void signal_to(std::shared_ptr<ReadySignal> signal) { signal_ = std::move(signal); }
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
  std::vector<policies::Action> decide(const policies::Observation& observation);
  /// Called by the channel policy when a move or an utterance ended.
  void result(const policies::ActionResult& r);
  /// Called by the observer at every tick.
  void observe(const runner::EpisodeSnapshot& snapshot);
  /// Called by the channel policy when the episode resets it: keeps the policy's context and random stream.
  void reset_policy(const policies::PolicyContext& context, Rng rng);
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

  void work(std::uint64_t seed);
  void stop_worker();

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
  std::shared_ptr<ReadySignal> signal_;  // posted to at each decision and at the end, if set
};

}  // namespace freeplay::python
