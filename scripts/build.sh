#!/usr/bin/env bash
# Configures and builds freeplay-sim into build/ (Release). Extra arguments go to the CMake configure step.
# Usage: scripts/build.sh [--main] [CMAKE_ARGS...]
#   (default)  everything: the libraries, every executable, the tests, the benchmarks (README, Quick start, command 2)
#   --main     the main job only: `freeplay` and `freeplay-run`, what `freeplay run` and `freeplay suite` need, from
#              the packages of `scripts/setup.sh --main` (command 1); a later plain scripts/build.sh adds the rest
set -euo pipefail
cd "$(dirname "$0")/.."
parts=(-DFREEPLAY_MAIN_JOB_ONLY=OFF -DFREEPLAY_BUILD_TESTS=ON -DFREEPLAY_BUILD_BENCH=ON)
targets=()
if [ "${1:-}" = --main ]; then
  shift
  parts=(-DFREEPLAY_MAIN_JOB_ONLY=ON)
  targets=(--target freeplay freeplay_run)
elif [ "${1:-}" = -h ] || [ "${1:-}" = --help ]; then
  sed -n '2,6p' "$0"; exit 0
fi
jobs=$(nproc 2>/dev/null || echo 2)
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f build/Makefile ] && generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${parts[@]}" "$@" >/dev/null
cmake --build build -j "$jobs" "${targets[@]}"
