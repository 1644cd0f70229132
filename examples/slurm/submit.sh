#!/bin/bash
# Submits a sharded comparison: an array job of N shards, and the merge job chained after it.
#
#   examples/slurm/submit.sh EXPERIMENT.json OUT_DIR N [sbatch options for both jobs ...]
#
# e.g. examples/slurm/submit.sh configs/experiments/paper_random_vibration_sweep.json \
#        /scratch/$USER/sweep 64 --partition=compute --account=nav
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 EXPERIMENT.json OUT_DIR N [sbatch options ...]" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
experiment=$(realpath "$1")
out=$(realpath -m "$2")
shards=$3
shift 3
array=$(sbatch --parsable "$@" --array="0-$((shards - 1))" "$here/compare_array.sbatch" \
  "$experiment" "$out" "$shards")
array=${array%%;*}  # --parsable prints JOBID[;CLUSTER]
merge=$(sbatch --parsable "$@" --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  "$here/compare_merge.sbatch" "$out")
merge=${merge%%;*}
echo "array job $array ($shards shards), merge job $merge after it; results in $out"
