// The event log: appending an event (serialised and hashed once, as it is appended) and reading the hash.

#include <benchmark/benchmark.h>

#include "freeplay/core/event_log.hpp"

namespace {

using freeplay::Event;
using freeplay::EventLog;

// One event of a typical episode (a stroke point), appended to a log of 3 000 events (≈ a 20-minute episode).
void BM_EventLogEmit(benchmark::State& state) {
  EventLog log;
  int n = 0;
  for (auto _ : state) {
    if (n++ % 3000 == 0) {
      state.PauseTiming();
      log = EventLog{};
      state.ResumeTiming();
    }
    log.emit(Event{0.1 * n, "child.purple", "stroke_point", {{"x", 0.123456789 * n}, {"y", -0.2}, {"colour", "blue"}}});
  }
  benchmark::DoNotOptimize(log.hash());
}
BENCHMARK(BM_EventLogEmit);

// The same with a typed event of the episode (a child's touch, as SimWorld emits it).
void BM_EventLogEmitTyped(benchmark::State& state) {
  EventLog log;
  int n = 0;
  for (auto _ : state) {
    if (n++ % 3000 == 0) {
      state.PauseTiming();
      log = EventLog{};
      state.ResumeTiming();
    }
    log.emit(Event{0.1 * n, "child.purple", freeplay::events::TouchDown{1, 0.123456789 * n, -0.2, "stroke"}});
  }
  benchmark::DoNotOptimize(log.hash());
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
