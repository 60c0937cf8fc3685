#!/bin/bash
# Submits a suite as a Slurm array of N shards plus a merge job that runs when every shard succeeded.
#
#   scripts/slurm/submit.sh SUITE.yaml RUN_DIR N [freeplay suite options…]
#
# The merged run lands in RUN_DIR/merged; per-task logs in RUN_DIR/logs. Extra sbatch options can be given in
# $SBATCH_OPTIONS (e.g. "--partition=short --time=02:00:00"); FREEPLAY names the program (default: on PATH).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
suite=${1:?usage: submit.sh SUITE.yaml RUN_DIR N [freeplay suite options…]}
run_dir=${2:?usage: submit.sh SUITE.yaml RUN_DIR N [freeplay suite options…]}
shards=${3:?usage: submit.sh SUITE.yaml RUN_DIR N [freeplay suite options…]}
shift 3
freeplay=${FREEPLAY:-freeplay}
mkdir -p "$run_dir/logs"
# shellcheck disable=SC2086  # SBATCH_OPTIONS is a list of options
array_job=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="0-$((shards - 1))" --output="$run_dir/logs/shard-%a.log" \
  --export=ALL,FREEPLAY="$freeplay",FREEPLAY_SHARDS="$shards" "$here/freeplay-array.sbatch" "$suite" "$run_dir" "$@")
array_job=${array_job%%;*}
# shellcheck disable=SC2086
merge_job=$(sbatch --parsable ${SBATCH_OPTIONS:-} --dependency="afterok:$array_job" --job-name=freeplay-merge \
  --output="$run_dir/logs/merge.log" --wrap="'$freeplay' merge '$run_dir'/shard-* --out '$run_dir/merged'")
echo "submitted shards as job $array_job (array 0-$((shards - 1))) and the merge as job ${merge_job%%;*}"
echo "merged run: $run_dir/merged (when both finished: squeue -u \$USER)"
