#!/bin/bash
# The Slurm array job for real, on a one-node cluster on this machine (loopback only):
#   1. installs Debian's slurm-wlm and munge (when missing), writes a munge key and a slurm.conf in a temporary
#      folder, starts munged, slurmctld and slurmd, and waits for the node to be idle;
#   2. plumbing check: submits an array job of `echo` tasks and checks every task ran with its index and count;
#   3. submits scripts/slurm/freeplay-array.sbatch on a tiny suite (3 shards), waits, merges the shards with
#      `freeplay merge`, runs the same suite locally, and compares: episodes.jsonl (without each episode's wall_s),
#      summary.csv and summary.md must be identical;
#   4. stops the daemons it started and removes its folder (also on failure or timeout).
# Usage: FREEPLAY_SLURM_TEST=1 scripts/slurm/test-slurm.sh PATH/TO/freeplay      (as root; ctest: -L slurm)
# Exit status: 0 passed, 1 failed, 77 skipped (not asked for, not root, or `freeplay suite` not in this build).
set -uo pipefail

FREEPLAY=${1:-freeplay}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
DEADLINE=$((SECONDS + ${FREEPLAY_SLURM_TEST_TIMEOUT:-600}))

if [ "${FREEPLAY_SLURM_TEST:-0}" != "1" ]; then
  echo "SKIP: the Slurm test installs packages and starts slurmctld/slurmd; run it with FREEPLAY_SLURM_TEST=1 (as root)"
  exit 77
fi
if [ "$(id -u)" != "0" ]; then
  echo "SKIP: the Slurm test must run as root (it installs slurm-wlm and munge and starts their daemons)"
  exit 77
fi

log() { echo "[slurm-test $(date +%H:%M:%S)] $*"; }
die() { log "FAILED: $*"; exit 1; }
left() { echo $((DEADLINE - SECONDS)); }

# --- 1. packages ------------------------------------------------------------------------------------------------
if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  log "installing slurm-wlm and munge"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq > /dev/null || die "apt-get update failed"
  apt-get install -y -qq --no-install-recommends slurm-wlm munge > /dev/null || die "apt-get install failed"
fi
for program in munged slurmctld slurmd sbatch squeue sinfo scontrol; do
  command -v "$program" > /dev/null || die "$program is missing after installing slurm-wlm and munge"
done
log "$(slurmctld -V), munge $(munged --version 2>&1 | head -1)"

# --- 2. a one-node loopback cluster in a temporary folder --------------------------------------------------------
WORK=$(mktemp -d /tmp/freeplay-slurm.XXXXXX)
chmod 0755 "$WORK"
export SLURM_CONF="$WORK/slurm.conf"
cleanup() {
  log "stopping the daemons and cleaning up"
  scancel --quiet --full --signal=KILL --state=RUNNING,PENDING -u root 2> /dev/null || true
  for pidfile in "$WORK/slurmd.pid" "$WORK/slurmctld.pid" "$WORK/munge/munged.pid"; do
    if [ -s "$pidfile" ]; then
      pid=$(cat "$pidfile")
      kill "$pid" 2> /dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2> /dev/null || true
    fi
  done
  if [ "${FREEPLAY_SLURM_KEEP:-0}" = "1" ]; then log "kept $WORK"; else rm -rf "$WORK"; fi
}
trap cleanup EXIT
trap 'die "interrupted"' INT TERM

mkdir -p "$WORK/munge" "$WORK/state" "$WORK/spool" "$WORK/run"
chmod 0700 "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 0400 "$WORK/munge/munge.key"
munged --force --key-file="$WORK/munge/munge.key" --socket="$WORK/munge/munge.socket" \
  --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/munge/munged.log" --seed-file="$WORK/munge/munged.seed" \
  || die "munged did not start: $(cat "$WORK/munge/munged.log" 2> /dev/null)"
echo hello | munge --socket="$WORK/munge/munge.socket" | unmunge --socket="$WORK/munge/munge.socket" > /dev/null \
  || die "munge credentials do not round-trip"
log "munged is running"

CPUS=2
cat > "$SLURM_CONF" <<CONF
# One node on the loopback interface, for scripts/slurm/test-slurm.sh only.
ClusterName=freeplaytest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$WORK/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
InactiveLimit=0
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$CPUS State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -c -f "$SLURM_CONF" || die "slurmctld did not start: $(tail -5 "$WORK/slurmctld.log" 2> /dev/null)"
slurmd -N localhost -f "$SLURM_CONF" || die "slurmd did not start: $(tail -5 "$WORK/slurmd.log" 2> /dev/null)"
state=""
for _ in $(seq 60); do
  state=$(sinfo -h -n localhost -o %T 2> /dev/null | head -1)
  case "$state" in
    idle) break ;;
    down* | drain*) scontrol update nodename=localhost state=resume 2> /dev/null || true ;;
  esac
  sleep 1
done
[ "$state" = "idle" ] || die "the node did not become idle (state '$state'); slurmd log: $(tail -5 "$WORK/slurmd.log")"
log "slurmctld and slurmd are up; node localhost is idle with $CPUS CPUs"

# wait_for_job ID: polls squeue until the job (every array task) left the queue, then checks each task's state.
wait_for_job() {
  local job=$1
  while squeue -h -j "$job" 2> /dev/null | grep -q .; do
    [ "$(left)" -gt 0 ] || die "job $job did not finish in time: $(squeue -j "$job")"
    sleep 1
  done
  # Without accounting, sacct has nothing; scontrol keeps finished jobs for MinJobAge (300 s).
  local states
  states=$(scontrol show job "$job" 2> /dev/null | grep -o 'JobState=[A-Z_]*' | sort | uniq -c)
  log "job $job finished: $(echo "$states" | tr '\n' ' ')"
  if echo "$states" | grep -v -q 'JobState=COMPLETED'; then
    tail -n 20 "$WORK"/run/*.log "$WORK"/run/*.out 2> /dev/null
    die "job $job has tasks that did not complete"
  fi
}

# --- 3. plumbing check: an array job of echo tasks ---------------------------------------------------------------
# shellcheck disable=SC2016  # expanded by the job's shell, not here
job=$(sbatch --parsable --array=0-3 --output="$WORK/run/hello-%a.out" --chdir="$WORK/run" \
  --wrap='echo "task $SLURM_ARRAY_TASK_ID of $SLURM_ARRAY_TASK_COUNT on $(hostname)"') || die "sbatch refused the job"
wait_for_job "$job"
for i in 0 1 2 3; do
  grep -q "^task $i of 4 on " "$WORK/run/hello-$i.out" || die "array task $i did not run: $(cat "$WORK/run/hello-$i.out")"
done
log "plumbing check passed: munge, slurmctld, slurmd and sbatch ran all 4 tasks of an array job"

# --- 4. the freeplay array job: shards, merge, and the same suite run locally -------------------------------------
if ! "$FREEPLAY" suite --help 2>&1 | grep -q -- "--shard"; then
  log "SKIP the freeplay part: '$FREEPLAY suite' is not in this build (the plumbing check above passed)"
  exit 77
fi
FREEPLAY=$(command -v "$FREEPLAY" || echo "$FREEPLAY")
FREEPLAY=$(cd "$(dirname "$FREEPLAY")" && pwd)/$(basename "$FREEPLAY")
cat > "$WORK/tiny.yaml" <<SUITE
# A few short episodes of each condition (the Slurm test).
suite: slurm-test
description: tiny suite for scripts/slurm/test-slurm.sh
scenarios:
  - scenario: $REPO/scenarios/child-child.yaml
    episodes: 3
  - scenario: $REPO/scenarios/child-robot-asocial.yaml
    episodes: 3
  - scenario: $REPO/scenarios/child-robot-social.yaml
    episodes: 2
SUITE
read -r -a overrides <<< "${FREEPLAY_SLURM_TEST_SET:---set protocol.freeplay_cap_s=60 --set protocol.greeting_s=0 --set protocol.tutorial_s=0 --set protocol.debriefing_s=0}"
"$FREEPLAY" validate "$WORK/tiny.yaml" "${overrides[@]}" > /dev/null || die "the tiny suite does not validate"

job=$(sbatch --parsable --array=0-2 --cpus-per-task=1 --output="$WORK/run/shard-%a.log" --chdir="$WORK/run" \
  --export=ALL,FREEPLAY="$FREEPLAY" "$HERE/freeplay-array.sbatch" "$WORK/tiny.yaml" "$WORK/run/slurm" \
  "${overrides[@]}") || die "sbatch refused freeplay-array.sbatch"
log "submitted freeplay-array.sbatch as job $job (3 shards)"
wait_for_job "$job"
for i in 0 1 2; do
  [ -s "$WORK/run/slurm/shard-$i/episodes.jsonl" ] || die "shard $i wrote no episodes: $(tail -20 "$WORK/run/shard-$i.log")"
done
"$FREEPLAY" merge "$WORK"/run/slurm/shard-* --out "$WORK/run/slurm/merged" || die "freeplay merge refused the shards"
log "running the same suite on this machine"
timeout "$(left)" "$FREEPLAY" suite "$WORK/tiny.yaml" --out "$WORK/run/local" --jobs "$CPUS" --quiet "${overrides[@]}" \
  || die "the local run failed"

strip_wall_clock() { sed -E 's/"wall_s":[^,}]*,?//' "$1"; }
diff <(strip_wall_clock "$WORK/run/local/episodes.jsonl") <(strip_wall_clock "$WORK/run/slurm/merged/episodes.jsonl") \
  > "$WORK/diff.txt" || die "episodes.jsonl differ (beyond wall_s): $(head -c 2000 "$WORK/diff.txt")"
for file in summary.csv summary.md; do
  cmp -s "$WORK/run/local/$file" "$WORK/run/slurm/merged/$file" \
    || die "$file differs: $(diff "$WORK/run/local/$file" "$WORK/run/slurm/merged/$file" | head -20)"
done
episodes=$(wc -l < "$WORK/run/local/episodes.jsonl")
log "PASSED: the merged output of 3 Slurm array tasks equals the local run ($episodes episodes; episodes.jsonl without wall_s, summary.csv, summary.md)"
