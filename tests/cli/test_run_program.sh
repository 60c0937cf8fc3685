#!/usr/bin/env bash
# `freeplay run/suite` start in `freeplay-run`, which loads the simulation's libraries only, and a run that records
# or films is handed to `freeplay-full` (same command line, same process); other commands go to `freeplay-full`.
set -u
freeplay=$1
build=$(dirname "$freeplay")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
heavy='libopencv_imgcodecs|libopencv_videoio|libroscpp|librosbag_storage|libmp3lame|libespeak'
# The libraries a command loads, from the dynamic loader's own log (LD_DEBUG=files: one "file=…" line each).
loaded() { LD_DEBUG=files LD_DEBUG_OUTPUT="$dir/ld" "$@" > "$dir/out.txt" 2>&1; local status=$?
  cat "$dir"/ld.* 2>/dev/null | grep -o 'file=[^ ]*' | sort -u; rm -f "$dir"/ld.*; return $status; }
short=(--episodes 1 --quiet --set protocol.greeting_s=2 --set protocol.tutorial_s=2 --set protocol.freeplay_cap_s=20
       --set protocol.debriefing_s=2)
printf 'name: plain\ncondition: child-robot\nseed: 5\n' > "$dir/plain.yaml"

if ldd "$build/freeplay-run" | grep -Eq "$heavy"; then
  echo "FAIL: freeplay-run links a recording, codec or ROS library:"; ldd "$build/freeplay-run" | grep -E "$heavy"; fail=1
fi
libs=$(loaded "$freeplay" run "$dir/plain.yaml" "${short[@]}" --out "$dir/plain") ||
  { echo "FAIL: plain run"; cat "$dir/out.txt"; fail=1; }
if grep -Eq "$heavy" <<<"$libs"; then echo "FAIL: a plain run loaded $(grep -E "$heavy" <<<"$libs" | head -3)"; fail=1; fi
[ "$(wc -l < "$dir/plain/episodes.jsonl")" -eq 1 ] || { echo "FAIL: the plain run wrote no episode"; fail=1; }

if "$build/freeplay-full" list policies > /dev/null 2>&1 && ldd "$build/freeplay-full" | grep -q librosbag_storage; then
  libs=$(loaded "$freeplay" run "$dir/plain.yaml" "${short[@]}" --record --out "$dir/recorded") ||
    { echo "FAIL: recorded run"; cat "$dir/out.txt"; fail=1; }
  grep -q librosbag_storage <<<"$libs" || { echo "FAIL: --record was not handed to freeplay-full"; fail=1; }
  ls "$dir"/recorded/sessions/*/*.bag > /dev/null 2>&1 || { echo "FAIL: the recorded run wrote no bag"; fail=1; }
  # The same episode, recorded or not, plays out the same.
  cmp -s "$dir/plain/events/plain-0000.jsonl" "$dir/recorded/events/plain-0000.jsonl" ||
    { echo "FAIL: recording changed the episode's event log"; fail=1; }
fi
libs=$(loaded "$freeplay" run "$dir/plain.yaml" "${short[@]}" --out "$dir/video" \
  --set 'cameras=[{name: env_camera, rate_hz: 2, width: 64, height: 36, video: true}]') ||
  { echo "FAIL: filmed run"; cat "$dir/out.txt"; fail=1; }
grep -q libopencv_videoio <<<"$libs" || { echo "FAIL: a run with a video was not handed to freeplay-full"; fail=1; }
ls "$dir"/video/videos/*/env_camera.mp4 > /dev/null 2>&1 || { echo "FAIL: the filmed run wrote no video"; fail=1; }
"$freeplay" list policies > /dev/null || { echo "FAIL: list policies (freeplay-full)"; fail=1; }
"$build/freeplay-run" --help | grep -q "suite" || { echo "FAIL: freeplay-run --help lists no suite command"; fail=1; }

if [ "$fail" -eq 0 ]; then echo "all passed"; else exit 1; fi
