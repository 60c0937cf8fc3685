#!/usr/bin/env bash
# `freeplay dataset` writes a 20-session synthetic PInSoRo dataset in the real layout; Python (yaml + csv) loads it the
# way the real dataset is loaded, and the label shares of the tables equal the run's; the same command resumes.
set -u
freeplay=$1
here=$(cd "$(dirname "$0")" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
printf 'name: cc\ncondition: child-child\nepisodes: 10\nseed: 5\nprotocol: {greeting_s: 2, tutorial_s: 2, freeplay_cap_s: 60, debriefing_s: 1}\n' > cc.yaml
printf 'name: cr\ncondition: child-robot\nepisodes: 9\nseed: 5\nrobot: {policy: social}\nprotocol: {greeting_s: 2, tutorial_s: 2, freeplay_cap_s: 60, debriefing_s: 1}\n' > cr.yaml
printf 'name: cam\ncondition: child-child\nepisodes: 1\nseed: 5\nprotocol: {greeting_s: 1, tutorial_s: 1, freeplay_cap_s: 3, debriefing_s: 1}\ncameras: [{name: camera_purple, rate_hz: 5, width: 64, height: 48, video: true}]\n' > cam.yaml
printf 'suite: mini\nscenarios: [{scenario: cc.yaml}, {scenario: cr.yaml}, {scenario: cam.yaml}]\n' > s.yaml
"$freeplay" dataset s.yaml --out ds --jobs 2 --quiet || { echo "FAIL: freeplay dataset"; exit 1; }
fail=0
/usr/bin/python3 "$here/check_dataset.py" ds 20 || fail=1
# The camera session's video has the real name (cam.yaml's one session is the only one with cameras).
[ "$(ls ds/data/*/videos/camera_purple_raw.* 2>/dev/null | wc -l)" -eq 1 ] || { echo "FAIL: no camera_purple_raw video"; ls -R ds/data; fail=1; }
# Resume: a second run finds everything done and leaves the sessions as they are.
before=$(cat ds/data/*/freeplay.bag.md5 | md5sum)
"$freeplay" dataset s.yaml --out ds --jobs 2 --quiet || { echo "FAIL: second run"; fail=1; }
[ "$(cat ds/data/*/freeplay.bag.md5 | md5sum)" = "$before" ] || { echo "FAIL: the second run changed the sessions"; fail=1; }
[ "$(ls -d ds/data/*/ | wc -l)" -eq 20 ] || { echo "FAIL: not 20 sessions after resuming"; fail=1; }
[ $fail -eq 0 ] && echo "dataset: all checks passed"
exit $fail
