#!/usr/bin/env bash
# Runs every Google Benchmark program in build/bench/, writes one JSON per program into OUT (default
# build/bench-results/<UTC time>/), and, when bench/reference/<program>.json exists, compares with Debian's
# compare.py (libbenchmark-tools) and prints which figures moved.
# Usage: bench/run_all.sh [--out DIR] [--repetitions N] [--filter REGEX] [--update-reference]
set -euo pipefail
cd "$(dirname "$0")/.."
out="build/bench-results/$(date -u +%Y%m%d-%H%M%S)"
repetitions=5
filter="."
update=0
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --repetitions) repetitions=$2; shift 2 ;;
    --filter) filter=$2; shift 2 ;;
    --update-reference) update=1; shift ;;
    -h|--help) sed -n '2,5p' "$0"; exit 0 ;;
    *) echo "run_all.sh: unknown option '$1' (allowed: --out, --repetitions, --filter, --update-reference)" >&2; exit 2 ;;
  esac
done
[ -d build/bench ] || { echo "run_all.sh: build/bench/ is missing; build first (scripts/build.sh)" >&2; exit 2; }
mkdir -p "$out"
compare=/usr/share/benchmark/compare.py
python=/usr/bin/python3  # Debian's, with python3-scipy for compare.py (a python3 earlier on PATH may lack it)
[ -x "$python" ] || python=python3
for program in build/bench/bench_*; do
  [ -x "$program" ] || continue
  name=$(basename "$program")
  echo "== $name"
  "$program" --benchmark_filter="$filter" --benchmark_repetitions="$repetitions" \
    --benchmark_report_aggregates_only=true --benchmark_out="$out/$name.json" --benchmark_out_format=json \
    > "$out/$name.txt"
  grep -E "_median" "$out/$name.txt" || true
  reference=bench/reference/$name.json
  if [ "$update" -eq 1 ]; then
    mkdir -p bench/reference && cp "$out/$name.json" "$reference"
  elif [ -f "$reference" ] && [ -f "$compare" ]; then
    "$python" "$compare" benchmarks "$reference" "$out/$name.json" > "$out/$name.compare.txt" 2>&1 ||
      echo "run_all.sh: compare.py failed for $name (see $out/$name.compare.txt; it needs python3-scipy)" >&2
    grep -E "_median" "$out/$name.compare.txt" || true
  fi
done
echo "results: $out"
