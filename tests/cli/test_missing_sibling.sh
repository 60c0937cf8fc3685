#!/usr/bin/env bash
# The main job's build (scripts/build.sh --main) has `freeplay` and `freeplay-run` only: a command that needs
# `freeplay-full` says which executable is missing and the exact command that builds it.
set -u
freeplay=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cp "$freeplay" "$dir/freeplay"  # alone in its folder: neither freeplay-run nor freeplay-full beside it
out=$("$dir/freeplay" serve 2>&1); status=$?
fail=0
[ "$status" -eq 1 ] || { echo "FAIL: status $status (want 1)"; fail=1; }
for wanted in "'serve' needs $dir/freeplay-full" "scripts/build.sh --main builds the main job only" \
              "scripts/setup.sh && scripts/build.sh"; do
  grep -qF -- "$wanted" <<<"$out" || { echo "FAIL: output lacks: $wanted"; fail=1; }
done
[ "$fail" -eq 0 ] || echo "output was: $out"
exit "$fail"
