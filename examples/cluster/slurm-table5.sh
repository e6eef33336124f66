#!/usr/bin/env bash
# table5 as a SLURM job array of N shards, then one merge job.
#
# Run it from the workspace root, on a filesystem every node shares:
#
#   bash examples/cluster/slurm-table5.sh
#
# Outside a job, the script builds the runner once, submits itself as the job array
# (one task per shard: `cargo xtask run table5 --shard K/N --out shards/K`) and submits the
# merge (`cargo xtask merge shards/*`) to start only once every task has succeeded. Inside the
# array, SLURM runs it once per task with SLURM_ARRAY_TASK_ID = K.
#
# The merged results/table5/ are bit-identical to `cargo xtask run table5` on one machine with
# the same seed and --set values. To change N, change both SHARDS and the --array line.
#
#SBATCH --job-name=table5-shard
#SBATCH --array=0-7
#SBATCH --cpus-per-task=4
#SBATCH --time=04:00:00
#SBATCH --output=logs/table5-shard-%a.out

set -euo pipefail

SHARDS=8                       # N: must be the number of tasks of --array (0 to N-1)
SEED=2025                      # every shard must use the same seed...
EXTRA=()                       # ...and the same parameters, e.g. EXTRA=(--set KEY=VALUE); see `cargo xtask help table5`

if [[ -z "${SLURM_ARRAY_TASK_ID:-}" ]]; then
    # Not inside the array: prepare and submit.
    if [[ -d shards ]] && [[ -n "$(ls -A shards)" ]]; then
        echo "shards/ is not empty: move or delete it first (a merge refuses shards of another run)" >&2
        exit 2
    fi
    mkdir -p logs shards
    # Build once here, so the tasks do not all compile at the same time.
    cargo build --release --quiet -p xtask
    array=$(sbatch --parsable "$0")
    merge=$(sbatch --parsable \
        --dependency="afterok:${array}" \
        --job-name=table5-merge \
        --cpus-per-task=2 \
        --time=01:00:00 \
        --output=logs/table5-merge.out \
        --wrap="cargo xtask merge shards/* --out results")
    echo "submitted job array ${array} (${SHARDS} shards) and merge job ${merge}"
    echo "when both are done: results/table5/ (tables also in logs/table5-merge.out)"
    exit 0
fi

if [[ "${SLURM_ARRAY_TASK_COUNT:-${SHARDS}}" != "${SHARDS}" ]]; then
    echo "the array has ${SLURM_ARRAY_TASK_COUNT} tasks but SHARDS=${SHARDS}: make --array 0-$((SHARDS - 1))" >&2
    exit 2
fi

# One shard: the trials t of each batch with t % N == K. Writes shards/K/table5/partial-K-of-N.json.
cargo xtask run table5 \
    --shard "${SLURM_ARRAY_TASK_ID}/${SHARDS}" \
    --seed "${SEED}" \
    --threads "${SLURM_CPUS_PER_TASK:-1}" \
    ${EXTRA[@]+"${EXTRA[@]}"} \
    --out "shards/${SLURM_ARRAY_TASK_ID}"
