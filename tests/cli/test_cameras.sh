#!/usr/bin/env bash
# `freeplay run` with cameras (videos), and `freeplay render/screen --scenario --time`: outputs and error messages.
set -u
freeplay=$1
scenarios=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
short=(--set protocol.greeting_s=2 --set protocol.tutorial_s=2 --set protocol.freeplay_cap_s=20 --set protocol.debriefing_s=2)
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
check() {  # check DESCRIPTION -- test...
  local what=$1; shift 2
  if ! "$@"; then echo "FAIL: $what"; fail=1; fi
}

# A run with a video camera: one MP4 per episode, frames and the GL renderer in the record.
expect 0 "" -- "$freeplay" run "$scenarios/child-robot-asocial.yaml" --episodes 1 --quiet "${short[@]}" \
  --set 'cameras=[{name: env_camera, rate_hz: 5, width: 160, height: 90, video: true}]' --out "$dir/run"
videos=("$dir"/run/videos/*/env_camera.mp4)
check "one video" -- test -s "${videos[0]}"
check "no partial video" -- test -z "$(find "$dir/run" -name '*.partial.mp4')"
check "frames and gl_renderer in episodes.jsonl" -- grep -q '"gl_renderer":"[^"]' "$dir/run/episodes.jsonl"
check "frames in episodes.jsonl" -- grep -q '"frames":{"env_camera":' "$dir/run/episodes.jsonl"

# render/screen at a moment of the scenario's first episode.
expect 0 "wrote $dir/env.png" -- "$freeplay" render --scenario "$scenarios/child-robot-asocial.yaml" "${short[@]}" \
  --time 3 --camera env_camera --width 160 --height 90 --out "$dir/env.png"
check "render PNG" -- test -s "$dir/env.png"
expect 0 "free play 3.0 s" -- "$freeplay" render --scenario "$scenarios/child-robot-asocial.yaml" "${short[@]}" \
  --time 3 --camera camera_purple --camera CameraTop --width 96 --height 54 --out "$dir/{camera}.png"
check "one PNG per camera" -- test -s "$dir/camera_purple.png" -a -s "$dir/CameraTop.png"
expect 0 "wrote $dir/screen.png" -- "$freeplay" screen --scenario "$scenarios/child-robot-asocial.yaml" "${short[@]}" \
  --time 1 --stage debriefing --width 320 --out "$dir/screen.png"
check "screen PNG" -- test -s "$dir/screen.png"

# Errors: beyond the cap, unknown stage, --time without a scenario, a camera the scene lacks.
expect 2 "free play stops at its cap of 20 s" -- "$freeplay" screen --scenario "$scenarios/child-robot-asocial.yaml" \
  "${short[@]}" --time 25 --out "$dir/x.png"
expect 2 "greeting, tutorial, freeplay, debriefing" -- "$freeplay" screen \
  --scenario "$scenarios/child-robot-asocial.yaml" --time 1 --stage lunch --out "$dir/x.png"
expect 2 "--time and --set need a scenario" -- "$freeplay" render --camera env_camera --time 3 --out "$dir/x.png"
expect 2 "CameraTop" -- "$freeplay" render --scenario "$scenarios/child-child.yaml" "${short[@]}" --time 1 \
  --camera CameraTop --out "$dir/x.png"
[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
