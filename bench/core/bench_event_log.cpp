// The event log: appending an event (serialised and hashed once, as it is appended) and reading the hash.

#include <benchmark/benchmark.h>

#include "freeplay/core/event_log.hpp"

namespace {

using freeplay::Event;
using freeplay::EventLog;

// Appends the event `make(n)` makes for the n-th iteration to a log restarted every 3 000 events (≈ a 20-minute
// episode), the restart untimed.
template <typename MakeEvent>
void emit_into_episode_logs(benchmark::State& state, MakeEvent make) {
  EventLog log;
  int n = 0;
  for (auto _ : state) {
    if (n++ % 3000 == 0) {
      state.PauseTiming();
      log = EventLog{};
      state.ResumeTiming();
    }
    log.emit(make(n));
  }
  benchmark::DoNotOptimize(log.hash());
}

// One event of a typical episode (a stroke point), written as a string-typed event.
void BM_EventLogEmit(benchmark::State& state) {
  emit_into_episode_logs(state, [](int n) {
    return Event{0.1 * n, "child.purple", "stroke_point", {{"x", 0.123456789 * n}, {"y", -0.2}, {"colour", "blue"}}};
  });
}
BENCHMARK(BM_EventLogEmit);

// The same with a typed event of the episode (a child's touch, as SimWorld emits it).
void BM_EventLogEmitTyped(benchmark::State& state) {
  emit_into_episode_logs(state, [](int n) {
    return Event{0.1 * n, "child.purple", freeplay::events::TouchDown{1, 0.123456789 * n, -0.2, "stroke"}};
  });
}
BENCHMARK(BM_EventLogEmitTyped);

// The hash of a finished 3 000-event log (what the episode record reads once).
void BM_EventLogHash(benchmark::State& state) {
  EventLog log;
  for (int n = 0; n < 3000; ++n) log.emit(Event{0.1 * n, "sandtray", "item_moved", {{"item", "zebra"}, {"x", 0.01 * n}}});
  for (auto _ : state) benchmark::DoNotOptimize(log.hash());
}
BENCHMARK(BM_EventLogHash);

}  // namespace
