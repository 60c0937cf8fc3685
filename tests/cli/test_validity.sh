#!/usr/bin/env bash
# `freeplay validity`: bad input exits 2 with the option or file named; a tiny panel runs end to end, writes its
# report (JSON, Markdown, JUnit parsed by Debian's python3) and exits 0 or 1 by its gates; a yoked run of a source
# without event logs is refused before any episode.
set -u
freeplay=$1
scenarios=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
expect 2 "--sessions" -- "$freeplay" validity --sessions 1 --out "$dir/p0"
expect 2 "--jobs" -- "$freeplay" validity --jobs 0 --out "$dir/p0"
touch "$dir/file"
expect 2 "'--out': '$dir/file' exists and is not a folder" -- "$freeplay" validity --sessions 2 --out "$dir/file"
mkdir -p "$dir/empty-scenarios"
expect 2 "panel's scenario file" -- env FREEPLAY_SCENARIOS_DIR="$dir/empty-scenarios" "$freeplay" validity --sessions 2 --out "$dir/p1"
for f in chatterer mover idle yoked-social; do
  expect 0 "ok" -- "$freeplay" validate "$scenarios/validity/$f.yaml"
done

# A tiny panel (3 sessions per robot, capped at 5 min of free play to keep it short).
mkdir -p "$dir/scenarios/validity"
for f in child-robot-social child-robot-asocial validity/chatterer validity/mover validity/yoked-social validity/idle; do
  sed 's/freeplay_cap_s: 2400/freeplay_cap_s: 300/' "$scenarios/$f.yaml" > "$dir/scenarios/$f.yaml"
done
out=$(FREEPLAY_SCENARIOS_DIR="$dir/scenarios" "$freeplay" validity --sessions 3 --jobs 2 --out "$dir/panel" --quiet 2>&1)
status=$?
if [ "$status" -ne 0 ] && [ "$status" -ne 1 ]; then echo "FAIL: tiny panel exited $status"; echo "$out" | tail; fail=1; fi
for want in "validity panel: 3 sessions per robot, seed 4242" "yoked-social" "gates failed" "joint_play_share"; do
  grep -qF -- "$want" <<<"$out" || { echo "FAIL: the report lacks '$want'"; fail=1; }
done
/usr/bin/python3 - "$dir/panel" "$status" <<'PY' || fail=1
import json, sys, xml.etree.ElementTree as ET
panel, status = sys.argv[1], int(sys.argv[2])
report = json.load(open(f"{panel}/validity.json"))
assert [r["robot"] for r in report["robots"]] == ["asocial", "social", "chatterer", "mover", "yoked-social", "idle"], report["robots"]
assert all(len(r["shares"]) == 14 and r["n"] == 3 for r in report["robots"])
assert len(report["gates"]) == 14
root = ET.parse(f"{panel}/validity.xml").getroot()
failures = int(root.get("failures"))
assert failures == report["failures"] and (failures > 0) == (status == 1), (failures, status)
PY
# The yoked run replayed the social run: same seeds, so `freeplay compare` pairs them.
expect 0 "paired" -- "$freeplay" compare "$dir/panel/yoked-social" "$dir/panel/social" --metric duration_s
# A source kept without event logs cannot be yoked: refused before any episode, naming the fix.
expect 2 "--events all" -- "$freeplay" run "$dir/scenarios/validity/yoked-social.yaml" --episodes 2 \
  --set "robot.params.from=$dir/panel/asocial" --out "$dir/yoked-none"
exit $fail
