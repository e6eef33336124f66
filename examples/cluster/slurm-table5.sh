#!/usr/bin/env bash
# table5 as a SLURM job array of N shards, then one merge job.
#
# Run it from the workspace root, on a filesystem every node shares:
#
#   bash examples/cluster/slurm-table5.sh [--shards N] [--cpus-per-task C] [--seed S]
#                                         [--dir DIR] [-- RUN-OPTIONS...]
#
#   --shards N          shards, one array task each (env SHARDS, default 8); the job array is
#                       --array=0-(N-1), derived from N
#   --cpus-per-task C   CPUs of each task and of the merge (env CPUS_PER_TASK, default 4); each
#                       task runs with --threads C
#   --seed S            the seed of every shard (default 2025)
#   --dir DIR           where shards/, logs/ and results/ go (default .)
#   -- RUN-OPTIONS      passed to every `run table5`, e.g. -- --set trials=400 (every shard must
#                       use the same values; `cargo xtask help table5` lists them)
#
# The runner: --xtask PATH (or XTASK=PATH) uses a prebuilt binary; without it the script builds
# target/release/xtask once here, so that the tasks do not all compile at the same time, and the
# tasks run that binary.
#
# Outside a job, the script first asks SLURM whether the cluster can run what it asks
# (`sbatch --test-only`, for the array and for the merge) and refuses with one line if not
# (exit 2) - a task asking for more CPUs than any node has would otherwise stay pending
# forever (reason PartitionConfig) and nothing would say so. It then submits itself as the job
# array (one task per shard: `xtask run table5 --shard K/N --out DIR/shards/K`) and the merge
# (`xtask merge DIR/shards/* --out DIR/results`), which starts only once every task has
# succeeded and is cancelled if one fails. Inside the array, SLURM runs it once per task with
# SLURM_ARRAY_TASK_ID = K.
#
# The merged DIR/results/table5/ are bit-identical to `cargo xtask run table5` on one machine
# with the same seed and RUN-OPTIONS (run.json aside: it records the date and thread count).
# scripts/check-slurm.sh runs this script on a one-node SLURM and checks exactly that.
#
# --array, --cpus-per-task and --output are given to sbatch by the script, from the values
# above; edit the time limit here (or override any option with SBATCH_* variables).
#SBATCH --job-name=table5-shard
#SBATCH --time=04:00:00

set -euo pipefail

me=slurm-table5
die() {
    echo "$me: $*" >&2
    exit 2
}

SHARDS="${SHARDS:-8}"
CPUS_PER_TASK="${CPUS_PER_TASK:-4}"
SEED=2025
DIR=.
XTASK="${XTASK:-}"
EXTRA=()

while (($#)); do
    case "$1" in
        --shards) SHARDS="${2:?--shards needs a value}"; shift 2 ;;
        --cpus-per-task) CPUS_PER_TASK="${2:?--cpus-per-task needs a value}"; shift 2 ;;
        --seed) SEED="${2:?--seed needs a value}"; shift 2 ;;
        --dir) DIR="${2:?--dir needs a value}"; shift 2 ;;
        --xtask) XTASK="${2:?--xtask needs a value}"; shift 2 ;;
        --) shift; EXTRA=("$@"); break ;;
        *) die "unknown argument \`$1\` (--shards N, --cpus-per-task C, --seed S, --dir DIR, -- RUN-OPTIONS)" ;;
    esac
done
[[ "$SHARDS" =~ ^[1-9][0-9]*$ ]] || die "shards must be a whole number of at least 1, not \`$SHARDS\`"
[[ "$CPUS_PER_TASK" =~ ^[1-9][0-9]*$ ]] || die "cpus per task must be a whole number of at least 1, not \`$CPUS_PER_TASK\`"
[[ "$SEED" =~ ^[0-9]+$ ]] || die "the seed must be a whole number, not \`$SEED\`"

if [[ -n "${SLURM_ARRAY_TASK_ID:-}" ]]; then
    # One task of the array: shard K of N. The submission passed --xtask and an absolute --dir.
    [[ -n "$XTASK" ]] || die "no runner: submit with \`bash $0\`, which gives the tasks their arguments, not with sbatch"
    if [[ "${SLURM_ARRAY_TASK_COUNT:-$SHARDS}" != "$SHARDS" ]]; then
        die "the array has ${SLURM_ARRAY_TASK_COUNT} tasks but there are ${SHARDS} shards"
    fi
    # The trials t of each batch with t % N == K. Writes DIR/shards/K/table5/partial-K-of-N.json.
    exec "$XTASK" run table5 \
        --shard "${SLURM_ARRAY_TASK_ID}/${SHARDS}" \
        --seed "$SEED" \
        --threads "${SLURM_CPUS_PER_TASK:-1}" \
        ${EXTRA[@]+"${EXTRA[@]}"} \
        --out "$DIR/shards/${SLURM_ARRAY_TASK_ID}"
fi

# Not inside the array: check, prepare and submit.
command -v sbatch >/dev/null || die "sbatch not found: run this on a SLURM login node"
mkdir -p "$DIR"
DIR="$(cd "$DIR" && pwd)"
if [[ -d "$DIR/shards" ]] && [[ -n "$(ls -A "$DIR/shards")" ]]; then
    die "$DIR/shards/ is not empty: move or delete it first (a merge refuses shards of another run)"
fi
if [[ -z "$XTASK" ]]; then
    root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
    cargo build --release --quiet --manifest-path "$root/Cargo.toml" -p xtask
    XTASK="${CARGO_TARGET_DIR:-$root/target}/release/xtask"
fi
[[ -x "$XTASK" ]] || die "the runner $XTASK is not an executable file"
XTASK="$(cd "$(dirname "$XTASK")" && pwd)/$(basename "$XTASK")"

cpus="${CPUS_PER_TASK} CPUs"
[[ "$CPUS_PER_TASK" != 1 ]] || cpus="1 CPU"

# What the tasks get: the same values, with the runner's path and DIR made absolute.
task_args=(--shards "$SHARDS" --cpus-per-task "$CPUS_PER_TASK" --seed "$SEED" --dir "$DIR"
    --xtask "$XTASK" -- ${EXTRA[@]+"${EXTRA[@]}"})
array_opts=(--array="0-$((SHARDS - 1))" --cpus-per-task="$CPUS_PER_TASK" --chdir="$DIR"
    --output="$DIR/logs/table5-shard-%a.out")
merge_opts=(--job-name=table5-merge --cpus-per-task="$CPUS_PER_TASK" --time=01:00:00
    --chdir="$DIR" --output="$DIR/logs/table5-merge.out")
merge_cmd="exec $(printf %q "$XTASK") merge shards/* --out results --threads $CPUS_PER_TASK"

# Can the cluster run them? `--test-only` submits nothing; SLURM refuses there what it would
# otherwise accept and leave pending forever (more CPUs per task than any node has).
refuse_unless_runnable() {
    local what="$1" out
    shift
    if ! out="$(sbatch --test-only "$@" 2>&1)"; then
        # SLURM's reason: the last line it printed, without its prefixes.
        out="$(printf '%s\n' "$out" | sed -n 's/^\(sbatch: \)\{0,1\}\(error: \)\{0,1\}\(allocation failure: \)\{0,1\}//; /./h; ${x;p;}')"
        local hint="see \`sinfo\` for the partitions' limits"
        if [[ "$out" == *"node configuration"* ]]; then
            hint="ask for fewer CPUs per task with --cpus-per-task or CPUS_PER_TASK (\`sinfo -o '%N %c'\` lists the nodes' CPUs)"
        fi
        die "SLURM cannot run ${what} (${out:-sbatch --test-only failed}): ${hint}"
    fi
}
refuse_unless_runnable "${SHARDS} shard tasks of ${cpus} each" \
    "${array_opts[@]}" "$0" "${task_args[@]}"
refuse_unless_runnable "the merge job with ${cpus}" \
    "${merge_opts[@]}" --wrap="$merge_cmd"

mkdir -p "$DIR/logs" "$DIR/shards"
array=$(sbatch --parsable "${array_opts[@]}" "$0" "${task_args[@]}")
array="${array%%;*}"
merge=$(sbatch --parsable "${merge_opts[@]}" \
    --dependency="afterok:${array}" --kill-on-invalid-dep=yes \
    --wrap="$merge_cmd")
merge="${merge%%;*}"
echo "submitted job array ${array} (${SHARDS} shards of ${cpus}) and merge job ${merge}"
echo "when both are done: $DIR/results/table5/ (tables also in $DIR/logs/table5-merge.out)"
