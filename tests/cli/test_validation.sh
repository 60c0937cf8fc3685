#!/usr/bin/env bash
# Every validation error path of the CLI: exit status 2 and a message naming file:line:column, key and allowed values.
set -u
freeplay=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
printf 'name: x\ncondition: child-child\nplanner:\n  nmae: astar\n' > "$dir/unknown-key.yaml"
printf 'name: x\ncondition: child-child\nepisodes: many\n' > "$dir/wrong-type.yaml"
printf 'name: x\ncondition: child-child\nchildren:\n  purple: {age: 12}\n' > "$dir/range.yaml"
printf 'name: x\ncondition: robot-robot\n' > "$dir/enum.yaml"
printf 'name: [x\n' > "$dir/syntax.yaml"
printf 'suite: s\nscenarios:\n  - scenario: missing.yaml\n' > "$dir/suite.yaml"
printf 'name: ok\ncondition: child-child\n' > "$dir/ok.yaml"
expect 2 "unknown-key.yaml:4:3: 'planner.nmae': unknown key 'nmae' (allowed: name, time_budget_s, finger_speed_mps, reject_blocked_goals)" -- "$freeplay" validate "$dir/unknown-key.yaml"
expect 2 "wrong-type.yaml:3:11: 'episodes': expected an integer" -- "$freeplay" validate "$dir/wrong-type.yaml"
expect 2 "'children.purple.age': 12 is out of range (allowed: an integer in [4, 8])" -- "$freeplay" validate "$dir/range.yaml"
expect 2 "unknown value 'robot-robot' (allowed: one of child-child, child-robot)" -- "$freeplay" validate "$dir/enum.yaml"
expect 2 "syntax.yaml:" -- "$freeplay" validate "$dir/syntax.yaml"
expect 2 "does not exist" -- "$freeplay" validate "$dir/suite.yaml"
expect 0 "ok      $dir/ok.yaml" -- "$freeplay" validate "$dir/ok.yaml"
expect 2 "unknown value 'teleport'" -- "$freeplay" run "$dir/ok.yaml" --set planner.name=teleport --out "$dir/r1"
expect 2 "'--set': 'oops' is not an assignment" -- "$freeplay" run "$dir/ok.yaml" --set oops --out "$dir/r2"
expect 2 "not a suite" -- "$freeplay" suite "$dir/ok.yaml" --out "$dir/r3"
expect 2 "shard" -- "$freeplay" suite "$dir/suite.yaml" --shard 3/2
expect 2 "--jobs" -- "$freeplay" run "$dir/ok.yaml" --jobs 0
# Inputs that once escaped as bare library messages (exit 1): each is bad input, named by file and line, exit 2.
long=$(printf 'a%.0s' {1..300})
printf 'suite: s\nscenarios:\n  - scenario: %s/x.yaml\n' "$long" > "$dir/long-path-suite.yaml"
printf 'name: x\ncondition: child-robot\ncameras: [{name: env_camera}]\n' > "$dir/camera.yaml"
printf 'name: x\ncondition: child-child\n? [1, 2]\n: 3\n' > "$dir/map-key.yaml"
printf 'name: *nothing\ncondition: child-child\n' > "$dir/alias.yaml"
expect 2 "long-path-suite.yaml:3:15: 'scenarios[0].scenario': scenario file" -- "$freeplay" validate "$dir/long-path-suite.yaml"
expect 2 "cannot be read: File name too long" -- "$freeplay" validate "$dir/long-path-suite.yaml"
expect 2 "'99999999999999999999' is not an index of the list at 'cameras.99999999999999999999' (allowed: 0…0)" -- \
  "$freeplay" validate "$dir/camera.yaml" --set cameras.99999999999999999999.rate_hz=1
expect 2 "map-key.yaml:3:3: a key must be a name, found a list" -- "$freeplay" validate "$dir/map-key.yaml"
expect 2 "alias.yaml:1:7: YAML syntax error" -- "$freeplay" validate "$dir/alias.yaml"
[ -e "$dir/r1" ] && { echo "FAIL: a run folder was created for invalid input"; fail=1; }
[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
