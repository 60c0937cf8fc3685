#!/usr/bin/env bash
# Measures the start-up of the `freeplay` program: median wall time of N runs (default 20) of `--version` and of
# `validate` on a shipped scenario, and what the dynamic loader does first (libraries mapped, relocations).
# Usage: scripts/startup_time.sh [N] [FREEPLAY]   (docs/fuzzing.md, "Start-up")
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-20}
freeplay=${2:-build/freeplay}
median_ms() {  # median_ms COMMAND...: the median wall time of $runs runs, in ms
  local times=()
  for ((i = 0; i < runs; i++)); do
    local start end
    start=$(date +%s%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s%N)
    times+=($(((end - start) / 1000)))
  done
  printf '%s\n' "${times[@]}" | sort -n | awk '{a[NR] = $1} END {printf "%.1f", a[int((NR + 1) / 2)] / 1000}'
}
echo "freeplay --version                     : $(median_ms "$freeplay" --version) ms (median of $runs)"
echo "freeplay validate child-robot-social   : $(median_ms "$freeplay" validate scenarios/child-robot-social.yaml) ms"
echo "shared libraries loaded                : $(ldd "$freeplay" | wc -l)"
LD_DEBUG=statistics "$freeplay" --version 2>&1 >/dev/null | sed -n 's/^ *[0-9]*: *//p' | grep -E 'total startup|relocation:|final number of relocations:' || true
