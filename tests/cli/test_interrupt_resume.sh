#!/usr/bin/env bash
# Ctrl-C during a suite keeps every finished episode and writes the summary; the same command resumes, and the
# result equals an uninterrupted run (apart from measured wall and planning times).
set -u
freeplay=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
printf 'name: cc\ncondition: child-child\nepisodes: 6\nseed: 3\nprotocol: {freeplay_cap_s: 600}\n' > cc.yaml
printf 'name: cr\ncondition: child-robot\nepisodes: 6\nseed: 3\nprotocol: {freeplay_cap_s: 600}\n' > cr.yaml
printf 'suite: s\nscenarios: [{scenario: cc.yaml}, {scenario: cr.yaml}]\n' > s.yaml
"$freeplay" suite s.yaml --jobs 1 --quiet --out whole || { echo "0 passed, 1 failed"; exit 1; }

"$freeplay" suite s.yaml --jobs 1 --quiet > /dev/null 2>err.txt &
pid=$!
for _ in $(seq 1 600); do  # wait until two episodes are on disk, then press Ctrl-C
  run=$(ls -d runs/*-s 2>/dev/null | head -1)
  [ -n "$run" ] && [ -f "$run/episodes.jsonl" ] && [ "$(wc -l < "$run/episodes.jsonl")" -ge 2 ] && break
  sleep 0.05
done
kill -INT "$pid"
wait "$pid"; status=$?
fail=0
[ "$status" -eq 130 ] || { echo "FAIL: interrupted run exited with $status, want 130"; cat err.txt; fail=1; }
n=$(wc -l < "$run/episodes.jsonl")
[ "$n" -ge 2 ] && [ "$n" -lt 12 ] || { echo "FAIL: $n episodes kept after Ctrl-C"; fail=1; }
[ -f "$run/summary.md" ] || { echo "FAIL: no summary for the finished episodes"; fail=1; }
grep -q "run the same command again" err.txt || { echo "FAIL: no resume hint"; fail=1; }

"$freeplay" suite s.yaml --jobs 1 --quiet 2>err2.txt || { echo "FAIL: resume failed"; cat err2.txt; fail=1; }
grep -q "resuming" err2.txt || { echo "FAIL: the second run did not resume $run"; cat err2.txt; fail=1; }
[ "$(ls -d runs/*-s | wc -l)" -eq 1 ] || { echo "FAIL: the resume created a new folder"; fail=1; }
strip() { python3 -c 'import json,sys
for l in open(sys.argv[1]):
    r=json.loads(l); r.pop("wall_s",None); r.pop("timing",None); print(json.dumps(r,sort_keys=True))' "$1"; }
if ! diff <(strip whole/episodes.jsonl) <(strip "$run/episodes.jsonl") > /dev/null; then
  echo "FAIL: resumed run differs from the uninterrupted run"; fail=1
fi
diff -r whole/events "$run/events" > /dev/null || { echo "FAIL: event logs differ"; fail=1; }
cmp -s whole/summary.csv "$run/summary.csv" || { echo "FAIL: summaries differ"; fail=1; }
[ $fail -eq 0 ] && echo "1 passed, 0 failed" || echo "0 passed, 1 failed"
exit $fail
