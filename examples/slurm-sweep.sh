#!/usr/bin/env bash
# A bifurcation sweep as a Slurm array job, for batch clusters without Dask:
# each array task runs one shard (`rocking sweep --shard K/N`), and a job
# that starts when all of them have succeeded joins the shards
# (`rocking merge`) into exactly the files one `rocking sweep` writes.
#
#   bash examples/slurm-sweep.sh            # on the login node: submits both jobs
#
# Settings (environment variables, all optional):
#   SWEEP    the scene and sweep, as `rocking sweep` takes them
#            (default: the paper's Fig. 4 at 10x its resolution)
#   SHARDS   number of array tasks (default 16)
#   OUT      output folder, on a file system the nodes share (default sweep-out)
#   ROCKING  the rocking binary (default: `rocking` on PATH)
#
# Slurm numbers array tasks from 0, as `--shard K/N` counts K, so task K
# computes the values with index ≡ K (mod N). The shards' values are
# interleaved, so every task gets a fair share of slow and fast values.
#SBATCH --job-name=rocking-sweep
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=rocking-sweep-%A_%a.log
set -euo pipefail

ROCKING="${ROCKING:-rocking}"
SHARDS="${SHARDS:-16}"
OUT="${OUT:-sweep-out}"
read -r -a SWEEP <<< "${SWEEP:---preset fig4 --param excitation.a_v --from 0 --to 3 --step 0.002}"

if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then
  # One array task: shard K of N, on the task's cores.
  K="$SLURM_ARRAY_TASK_ID"
  N="${SLURM_ARRAY_TASK_COUNT:-$SHARDS}"
  exec "$ROCKING" sweep "${SWEEP[@]}" --shard "$K/$N" --threads "${SLURM_CPUS_PER_TASK:-1}" \
    --out "$OUT/shard-$K" --quiet
elif [ "${1:-}" = merge ]; then
  # After every shard: one sweep's files (classes.csv, points.csv,
  # sweep.json, bifurcation.png/svg) in $OUT/merged.
  exec "$ROCKING" merge --out "$OUT/merged" "$OUT"/shard-*
else
  # On the login node: the array, then the merge once all tasks succeeded.
  script="$(realpath "$0")"
  job="$(sbatch --parsable --array="0-$((SHARDS - 1))" --export=ALL "$script")"
  sbatch --parsable --dependency="afterok:$job" --export=ALL --job-name=rocking-merge \
    --output="rocking-merge-%j.log" --wrap "bash '$script' merge"
  echo "submitted array job $job ($SHARDS shards) and its merge; results in $OUT/merged"
fi
