#!/bin/bash
# Submits render-shards.sbatch as a job array, and a job that stitches the
# shards into $OUT.png once every task has ended. Options go to the array's
# sbatch: `--array=3,5` renders only shards 3 and 5 again, then stitches.
set -euo pipefail
export SHARDS=${SHARDS:-8}
export OUT=${OUT:-$HOME/renders/showcase}
mkdir -p logs
array=$(sbatch --parsable --array="0-$((SHARDS - 1))" "$@" "$(dirname "$0")/render-shards.sbatch")
echo "Submitted shards as job array $array"
# afterany, not afterok: after a failed shard the stitch still runs, names the
# missing shards and writes nothing.
sbatch --job-name=glint-stitch --output=logs/stitch.log --dependency="afterany:$array" \
    --wrap 'glint stitch "$OUT"/shard_*.png -o "$OUT.png"'
