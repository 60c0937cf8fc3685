#!/usr/bin/env bash
# End-to-end test of `freeplay compare|baseline|check|merge` on synthetic run folders: outputs, exit statuses
# (0 pass, 1 failed gate, 2 bad input) and JUnit XML read back by python3's XML parser.
set -u
FREEPLAY=${1:?usage: cli_test.sh PATH/TO/freeplay}
if ! command -v python3 > /dev/null; then
  echo "SKIP: python3 is needed to write the synthetic runs and parse the JUnit XML"
  exit 77
fi
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# expect STATUS COMMAND…: runs the command (output in out.txt) and checks its exit status.
expect() {
  local want=$1; shift
  "$@" > out.txt 2>&1
  local got=$?
  if [ "$got" != "$want" ]; then fail "'$*' exited $got, expected $want"; cat out.txt; fi
}
contains() { grep -q -- "$1" out.txt || { fail "output lacks '$1'"; cat out.txt; }; }

# Synthetic runs: A (asocial + social, same seeds), B (social robot degraded), shards of A with run.json.
python3 - <<'PY'
import json, os, random
def record(variant, policy, i, moves):
    child = random.Random(1000 + i)          # the same child for the same seed
    noise = random.Random(hash((variant, i)) & 0xffff)
    e = child.gauss(0, 1)
    return {"variant": variant, "scenario": variant, "condition": "child-robot", "policy": policy,
            "episode": i, "episode_id": f"{variant}-{i:04d}", "seed": 1000 + i, "config_hash": 7,
            "program_version": "test", "duration_s": 1100 + 300 * e + 50 * noise.gauss(0, 1), "ended_by": "quit",
            "simulated_s": 1500.0, "wall_s": 0.25,
            "metrics": {"robot_item_moves_per_min": moves + 0.4 * e + 0.2 * noise.gauss(0, 1),
                        "label_share": {"purple": {"cooperative": 0.3 + 0.05 * e + 0.02 * noise.gauss(0, 1)}}}}
def write(folder, records, manifest=None):
    os.makedirs(folder, exist_ok=True)
    with open(f"{folder}/episodes.jsonl", "w") as f:
        for r in records:
            f.write(json.dumps(r, sort_keys=True, separators=(",", ":")) + "\n")
    if manifest is not None:
        with open(f"{folder}/run.json", "w") as f:
            json.dump(manifest, f)
a = [record("child-robot-asocial", "asocial", i, 2.0) for i in range(20)] + \
    [record("child-robot-social", "social", i, 2.6) for i in range(20)]
b = [record("child-robot-asocial", "asocial", i, 2.0) for i in range(20)] + \
    [record("child-robot-social", "social", i, 1.2) for i in range(20)]
write("A", a)
write("B", b)
write("only-social", [r for r in a if r["variant"] == "child-robot-social"])
manifest = {"suite_file": "s.yaml", "suite": "synthetic", "overrides": [],
            "variants": [{"id": "child-robot-asocial", "episodes": 20}, {"id": "child-robot-social", "episodes": 20}]}
for k in range(3):
    write(f"shard-{k}", [r for r in a if (r["episode"] + k) % 3 == 0], dict(manifest, shard=[k + 1, 3]))
os.makedirs("shard-1/events", exist_ok=True)
open("shard-1/events/child-robot-social-0002.jsonl", "w").write("{}\n")
PY

# compare: two variants of one run (paired by seed), two runs, JSON, bad input.
expect 0 "$FREEPLAY" compare A --variant child-robot-asocial --variant child-robot-social
contains "paired by seed"
contains "metrics.robot_item_moves_per_min"
contains "p Holm W"
expect 0 "$FREEPLAY" compare A B --metric 'metrics.robot_*'
contains "A: A \[child-robot-asocial\]"
contains "A: A \[child-robot-social\]"
expect 0 "$FREEPLAY" compare A B --variant child-robot-social --json
python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["comparisons"]; m={x["metric"]: x for x in c[0]["metrics"]}; \
assert len(c) == 1 and c[0]["paired"]; assert m["metrics.robot_item_moves_per_min"]["significant"]; \
assert m["metrics.robot_item_moves_per_min"]["paired"]["wilcoxon"]["p"] < 0.001' out.txt || fail "compare --json content"
expect 2 "$FREEPLAY" compare A --variant child-robot-social
contains "two --variant"
expect 2 "$FREEPLAY" compare A B --variant nope
contains "no variant 'nope'"
expect 2 "$FREEPLAY" compare A B --metric 'nothing.*'
contains "matches no metric"

# baseline + check: passes on the unchanged run, fails on the degraded policy (exit 1), JUnit XML parses.
expect 0 "$FREEPLAY" baseline A --out base.yaml
contains "wrote 6 gates"
expect 0 "$FREEPLAY" check A --baseline base.yaml --junit ok.xml
contains "6 of 6 gates passed"
expect 1 "$FREEPLAY" check B --baseline base.yaml --junit fail.xml
contains "FAIL  child-robot-social   metrics.robot_item_moves_per_min"
contains "1 of 6 gates FAILED"
python3 - <<'PY' || fail "JUnit XML"
import xml.etree.ElementTree as E
for name, failures in (("ok.xml", 0), ("fail.xml", 1)):
    root = E.parse(name).getroot()
    assert root.tag == "testsuites" and int(root.get("tests")) == 6 and int(root.get("failures")) == failures
    assert [s.get("name") for s in root.findall("testsuite")] == ["child-robot-asocial", "child-robot-social"]
    assert len(root.findall("testsuite/testcase/failure")) == failures
PY
expect 0 "$FREEPLAY" baseline A --out nwt.yaml --not-worse-than higher_is_better --metric 'metrics.robot_*' --variant child-robot-social
expect 1 "$FREEPLAY" check B --baseline nwt.yaml
contains "the whole CI is lower"
# bad input: malformed baseline (file:line:column), a variant the run lacks, conflicting band options.
printf 'variants:\n  child-robot-social:\n    duration_s: {expected: 1, rel: 0.1, abs: 3}\n' > bad.yaml
expect 2 "$FREEPLAY" check A --baseline bad.yaml
contains "bad.yaml:3:17"
contains "exactly one band"
expect 2 "$FREEPLAY" check only-social --baseline base.yaml
contains "no episodes of variant 'child-robot-asocial'"
expect 2 "$FREEPLAY" baseline A --out x.yaml --rel 0.1 --abs 2

# merge: shards join into A (same records, sorted like a single-machine run); duplicates and gaps are refused.
expect 0 "$FREEPLAY" merge shard-2 shard-0 shard-1 --out merged
contains "merged 40 episodes (1 per-episode files) from 3 run folders"
python3 -c 'import json; l=lambda p:[json.loads(x) for x in open(p)]; assert l("A/episodes.jsonl") == l("merged/episodes.jsonl")' \
  || fail "merged episodes differ from the whole run"
[ -f merged/events/child-robot-social-0002.jsonl ] || fail "per-episode file not copied"
if [ ! -f merged/summary.csv ] || [ ! -f merged/summary.md ]; then fail "summaries not written"; fi
expect 2 "$FREEPLAY" merge shard-0 shard-1 --out merged2
contains "are missing"
[ ! -e merged2 ] || fail "a refused merge wrote its output"
cp -r shard-1 shard-1-again
expect 2 "$FREEPLAY" merge shard-0 shard-1 shard-2 shard-1-again --out merged3
contains "given twice"
expect 2 "$FREEPLAY" merge shard-0 shard-1 shard-2 --out merged
contains "not empty"

if [ "$failures" -ne 0 ]; then echo "$failures check(s) failed"; exit 1; fi
echo "all CLI checks passed"
