#!/usr/bin/env bash
# Builds every test with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs them (tests
# labelled `slow` and the three longest whole-episode tests are skipped). About 15 minutes on 2 cores from a cold
# compiler cache; .ci/run runs it when FREEPLAY_CI_SANITIZE=1.
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
# -O0 with line tables only (-g1): reports keep file:line, and the build is far cheaper than -O2 -g. Warnings are
# already errors in step 1; here GCC's flow analysis under the sanitizers gives false -Wmaybe-uninitialized.
cmake -S . -B build-asan "${generator[@]}" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O0 -g1" \
      -DFREEPLAY_SANITIZE=ON -DFREEPLAY_WERROR=OFF -DFREEPLAY_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j "$(nproc)"
# Skipped here besides the `slow` label: the three longest whole-episode tests (run in step 1; other episode tests
# exercise the same code under the sanitizers).
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS=suppressions="$PWD/tests/lsan-suppressions.txt" \
  ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE slow \
  -E 'Episode\.TheSocialPolicyNeverGrabsAnItemAChildHolds|EpisodeCapture\.SaysWhenTheChildrenQuitBeforeTheMoment|Episode\.OneAndTwoWorkersGiveIdenticalRunFolders'
