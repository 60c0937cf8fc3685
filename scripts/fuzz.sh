#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang++ (ASan + UBSan) into build-fuzz/ and runs each for SECONDS
# (default 60), seeded from the shipped files; prints executions and crashes per target (docs/fuzzing.md).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: scenario suite overrides annotations bag)
# Exit status: 0 when no target found a crash, 1 otherwise (the inputs are kept in build-fuzz/crashes/<target>/).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scenario suite overrides annotations bag)
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f build-fuzz/Makefile ] && generator=(-G Ninja)
# -O1 -g1: fast enough to fuzz, with file:line in the reports; tests and benchmarks are not needed here.
cmake -S . -B build-fuzz "${generator[@]}" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_FLAGS="-O1 -g1" -DFREEPLAY_FUZZ=ON -DFREEPLAY_WERROR=OFF \
      -DFREEPLAY_BUILD_TESTS=OFF -DFREEPLAY_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j "$(nproc)" --target "${targets[@]/#/fuzz_}"

# Seed corpora: the shipped scenarios, suites and baselines; a few overrides; annotations written by the simulation;
# three tiny recorded bags (made by build/freeplay when it is built).
seeds=build-fuzz/seeds
mkdir -p "$seeds"/{scenario,suite,overrides,annotations,bag}
cp scenarios/*.yaml "$seeds/scenario/"
for f in baselines/*.yaml; do cp "$f" "$seeds/scenario/baseline-$(basename "$f")"; done
cp scenarios/*.yaml "$seeds/suite/"
i=0
for o in planner.name=rrtconnect perception.latency_s=0.3 'cameras=[{name: env_camera, rate_hz: 5}]' \
         children.purple.age=5 robot.params.speed=2 'record={bag: true, compression: lz4}' protocol.tutorial_s=0 \
         'controller.targets[0].wait=1' kind=controller 'children=[1, 2]' seed=18446744073709551615; do
  printf '%s\n' "$o" > "$seeds/overrides/$((i++)).txt"
done
printf 'purple:\n  - noplay: [100, 101.5]\n  - solitary: [100, 104]\nyellow:\n  - passive: [100, 104]\n  - "?": [1, 2]\n' \
  > "$seeds/annotations/0.yaml"
# Three bags: uncompressed chunks (as the real bags), lz4 and bz2 chunks (record.compression), so that the fuzzer
# starts from valid compressed chunks too.
for compression in none lz4 bz2; do
  seed="$seeds/bag/$compression.bag"
  [[ " ${targets[*]} " == *" bag "* ]] && [ -x build/freeplay ] && [ ! -f "$seed" ] || continue
  run=$(mktemp -d)
  build/freeplay run scenarios/child-child.yaml --quiet --record --out "$run/r" --episodes 1 --set protocol.greeting_s=0 \
    --set protocol.tutorial_s=0 --set protocol.freeplay_cap_s=1 --set protocol.debriefing_s=0 \
    --set record.compression=$compression >/dev/null
  cp "$(find "$run/r" -name freeplay.bag | head -1)" "$seed"
  rm -rf "$run"
done

status=0
printf '%-12s %12s %8s %8s\n' target executions seconds crashes
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t crashes=build-fuzz/crashes/$t log=build-fuzz/fuzz_$t.log
  mkdir -p "$corpus" "$crashes"
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1:max_allocation_size_mb=1024:malloc_context_size=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    build-fuzz/fuzz/fuzz_"$t" "$corpus" "$seeds/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -dict=fuzz/yaml.dict -print_final_stats=1 -artifact_prefix="$crashes/" >"$log" 2>&1 || true
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  found=$(find "$crashes" -type f | wc -l)
  printf '%-12s %12s %8s %8s\n' "$t" "${execs:-?}" "$seconds" "$found"
  if [ "$found" -gt 0 ] || [ -z "$execs" ]; then status=1; tail -30 "$log"; fi
done
exit $status
