#!/usr/bin/env bash
# Checks examples/cluster/slurm-table5.sh on a real SLURM: a private one-node cluster on this
# machine, started here and stopped on exit.
#
#   scripts/check-slurm.sh
#
# 1. Installs Debian's slurm-wlm and munge if missing (as root, or with sudo).
# 2. Writes a one-node slurm.conf for this machine (its CPUs as `slurmd -C` finds them) in a new
#    temporary directory, with its own munge key and socket and its own ports, and starts munged,
#    slurmctld and slurmd on it (SLURM_CONF points the clients there; /etc/slurm is not used).
# 3. Runs the example asking for one CPU more per task than the node has, and checks that it
#    refuses at once: exit status 2, one line on stderr, nothing queued.
# 4. Runs the example for real on a reduced table5 (SHARDS shards of one CPU, --set
#    trials=TRIALS), waits for every task and the merge job, and checks that the merged
#    results/table5/ are the same bytes as a single `run table5` with the same seed and values
#    (run.json aside from its date, thread count and working folder).
# 5. Stops the daemons it started (also on failure or Ctrl-C) and removes the directory
#    (kept, and named, on failure).
#
# Environment: XTASK (a prebuilt runner; default: build target/release/xtask), SHARDS (default
# 3), TRIALS (default 4), SLURM_CHECK_TIMEOUT (seconds to wait for the jobs, default 300).
# With CI=true, a failure to install or start SLURM is a failure; else the check is skipped with
# the reason (exit 0).
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$PATH:/usr/sbin:/sbin"

me=check-slurm
SHARDS="${SHARDS:-3}"
TRIALS="${TRIALS:-4}"
SEED=2025
TIMEOUT="${SLURM_CHECK_TIMEOUT:-300}"
t0=$SECONDS

say() { echo "$me: $*" >&2; }
fail() {
    say "FAILED: $*"
    exit 1
}
# What cannot be set up here: a failure under CI, a skip with the reason elsewhere.
cannot() {
    if [[ "${CI:-}" == "true" ]]; then
        fail "$*"
    fi
    say "skipped: $*"
    exit 0
}

sudo=()
if [[ "$(id -u)" -ne 0 ]]; then
    if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
        sudo=(sudo -n)
    else
        cannot "slurmd must run as root: run as root or with passwordless sudo"
    fi
fi

install_slurm() {
    if command -v munged >/dev/null && command -v slurmctld >/dev/null &&
        command -v slurmd >/dev/null && command -v sbatch >/dev/null; then
        return 0
    fi
    command -v apt-get >/dev/null || cannot "slurm-wlm and munge are missing and there is no apt-get to install them"
    say "installing Debian's slurm-wlm and munge"
    "${sudo[@]}" apt-get update -qq || cannot "apt-get update failed"
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null ||
        cannot "apt-get install slurm-wlm munge failed"
    for c in munged slurmctld slurmd sbatch; do
        command -v "$c" >/dev/null || cannot "$c still missing after installing slurm-wlm and munge"
    done
}
install_slurm

# The runner: XTASK if given, else built once (a no-op when `cargo test --release` built it).
if [[ -z "${XTASK:-}" ]]; then
    cargo build --release --quiet -p xtask
    XTASK="$(cd "${CARGO_TARGET_DIR:-target}/release" && pwd)/xtask"
fi
[[ -x "$XTASK" ]] || fail "the runner $XTASK is not an executable file"
t_built=$SECONDS

work="$(mktemp -d "${TMPDIR:-/tmp}/check-slurm.XXXXXX")"
chmod 755 "$work"
# The daemons' directory: root's (with sudo), readable by the clients, which use its munge socket.
sys="$work/slurm"
"${sudo[@]}" mkdir -m 755 "$sys"
conf="$work/slurm.conf"
export SLURM_CONF="$conf"
ok=0

# Whether process $1 runs (a zombie waiting for its parent does not).
running() {
    local state
    state="$(cut -d ' ' -f 3 "/proc/$1/stat" 2>/dev/null)" && [[ "$state" != Z ]]
}

# Cancel our jobs, then stop the daemons we started (their pid files are in $sys).
cleanup() {
    local status=$?
    trap - EXIT INT TERM
    if [[ -e "$sys/slurmctld.pid" ]]; then
        scancel --quiet --user="$(id -un)" 2>/dev/null || true
    fi
    local d pid
    for d in slurmd slurmctld munged; do
        pid="$("${sudo[@]}" cat "$sys/$d.pid" 2>/dev/null || true)"
        [[ -n "$pid" ]] || continue
        "${sudo[@]}" kill "$pid" 2>/dev/null || continue
        for _ in $(seq 50); do
            running "$pid" || break
            sleep 0.1
        done
        "${sudo[@]}" kill -KILL "$pid" 2>/dev/null || true
    done
    if [[ "$ok" == 1 ]]; then
        "${sudo[@]}" rm -rf "$work"
    else
        say "kept $work (slurm/slurmctld.log, slurm/slurmd.log, run/logs/)"
    fi
    exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# Show the end of a log when something goes wrong.
tail_log() {
    [[ -e "$1" ]] || "${sudo[@]}" test -e "$1" || return 0
    echo "--- $1 (end):" >&2
    "${sudo[@]}" tail -n 20 "$1" >&2 || true
}

# waits up to $1 seconds for the command that follows to succeed
wait_for() {
    local seconds="$1"
    shift
    for _ in $(seq $((seconds * 5))); do
        if "$@" >/dev/null 2>&1; then
            return 0
        fi
        sleep 0.2
    done
    return 1
}

port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
ctld_port=16817
while ! port_free "$ctld_port" || ! port_free $((ctld_port + 1)); do
    ctld_port=$((ctld_port + 2))
done

# munge: our own key and socket, so that a munged already running here is left alone.
"${sudo[@]}" dd if=/dev/urandom of="$sys/munge.key" bs=1024 count=1 status=none
"${sudo[@]}" chmod 400 "$sys/munge.key"
"${sudo[@]}" munged --force --socket="$sys/munge.socket" --key-file="$sys/munge.key" \
    --pid-file="$sys/munged.pid" --log-file="$sys/munged.log" --seed-file="$sys/munged.seed" ||
    { tail_log "$sys/munged.log"; cannot "munged did not start"; }
wait_for 10 "${sudo[@]}" test -S "$sys/munge.socket" ||
    { tail_log "$sys/munged.log"; cannot "munged did not open its socket"; }

# The node as slurmd finds it: CPUs, sockets, cores and threads (memory left out, as no job
# asks for any), named by the short host name that slurmctld and slurmd go by.
host="$(uname -n)"
host="${host%%.*}"
node="$(slurmd -C | head -n 1 | sed "s/^NodeName=[^ ]*/NodeName=$host/; s/ RealMemory=[0-9]*//")"
[[ "$node" == NodeName=* ]] || cannot "slurmd -C did not describe this machine: $node"
cpus="$(sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' <<<"$node")"

cat >"$conf" <<EOF
# A one-node cluster for scripts/check-slurm.sh, on $host ($cpus CPUs).
ClusterName=check
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$((ctld_port + 1))
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sys/munge.socket
StateSaveLocation=$sys/state
SlurmdSpoolDir=$sys/spool
SlurmctldPidFile=$sys/slurmctld.pid
SlurmdPidFile=$sys/slurmd.pid
SlurmctldLogFile=$sys/slurmctld.log
SlurmdLogFile=$sys/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
$node NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=check Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
"${sudo[@]}" mkdir -p "$sys/state" "$sys/spool"

"${sudo[@]}" env SLURM_CONF="$conf" slurmctld -f "$conf" ||
    { tail_log "$sys/slurmctld.log"; cannot "slurmctld did not start"; }
wait_for 30 scontrol ping ||
    { tail_log "$sys/slurmctld.log"; cannot "slurmctld does not answer (scontrol ping)"; }
"${sudo[@]}" env SLURM_CONF="$conf" slurmd -f "$conf" -N "$host" ||
    { tail_log "$sys/slurmd.log"; cannot "slurmd did not start"; }
node_idle() { [[ "$(sinfo -h -n "$host" -o %T)" == idle ]]; }
wait_for 30 node_idle ||
    { tail_log "$sys/slurmd.log"; cannot "node $host is not idle: $(sinfo -h -o '%T %E' 2>&1)"; }
t_up=$SECONDS
say "SLURM up on $host ($cpus CPUs) in $((t_up - t_built)) s"

example=(bash examples/cluster/slurm-table5.sh --seed "$SEED" --xtask "$XTASK")
run_opts=(-- --set "trials=$TRIALS")

# An unsatisfiable request is refused at once, with one line, and nothing is queued.
start=$SECONDS
set +e
"${example[@]}" --shards 2 --cpus-per-task $((cpus + 1)) --dir "$work/refused" "${run_opts[@]}" \
    >"$work/refused.out" 2>"$work/refused.err"
status=$?
set -e
refusal="$(cat "$work/refused.err")"
[[ "$status" == 2 ]] || fail "asking for $((cpus + 1)) CPUs per task on a $cpus-CPU node: exit status $status, not 2 (stderr: $refusal)"
[[ "$(wc -l <"$work/refused.err")" == 1 && "$refusal" == slurm-table5:* ]] ||
    fail "the refusal is not one line from slurm-table5: $refusal"
((SECONDS - start <= 15)) || fail "the refusal took $((SECONDS - start)) s"
[[ -z "$(squeue -h -o %i)" ]] || fail "a refused request left jobs queued: $(squeue -h -o '%i %T %r')"
say "refused at once: $refusal"

# The whole path: the array, the merge after it, and the same tables as a single run.
out="$("${example[@]}" --shards "$SHARDS" --cpus-per-task 1 --dir "$work/run" "${run_opts[@]}")" ||
    fail "the example did not submit: $out"
echo "$out" >&2
array="$(sed -n 's/^submitted job array \([0-9]*\) .* merge job \([0-9]*\)$/\1/p' <<<"$out")"
merge="$(sed -n 's/^submitted job array \([0-9]*\) .* merge job \([0-9]*\)$/\2/p' <<<"$out")"
[[ -n "$array" && -n "$merge" ]] || fail "no job ids in the example's output: $out"

queue_empty() { [[ -z "$(squeue -h -o %i)" ]]; }
wait_for "$TIMEOUT" queue_empty ||
    fail "jobs still queued after $TIMEOUT s: $(squeue -h -o '%i %T %r')"
states="$(scontrol -o show job "$array" | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | xargs)"
[[ "$states" == "$SHARDS JobState=COMPLETED" ]] ||
    { tail_log "$work/run/logs/table5-shard-0.out"; fail "the array's tasks ended as: $states"; }
mstate="$(scontrol -o show job "$merge" | grep -o 'JobState=[A-Z_]*')"
[[ "$mstate" == JobState=COMPLETED ]] ||
    { tail_log "$work/run/logs/table5-merge.out"; fail "the merge job ended as $mstate"; }
t_jobs=$SECONDS

"$XTASK" run table5 --seed "$SEED" --set "trials=$TRIALS" --out "$work/single" -q >/dev/null
merged="$work/run/results/table5"
single="$work/single/table5"
[[ -s "$merged/table.md" ]] || fail "no $merged/table.md"
diff -r --exclude=run.json "$single" "$merged" >&2 ||
    fail "the merged results differ from a single run"
# The date, the threads and the folder the command ran in (where relative input paths were read
# from) are how the run was made, not which run it is.
provenance() { grep -v -e '"date":' -e '"threads":' -e '"folder":' "$1/run.json"; }
diff <(provenance "$single") <(provenance "$merged") >&2 ||
    fail "the merged run.json names another run than the single run's"

ok=1
say "ok: $SHARDS shards and the merge, identical to a single run ($(find "$merged" -type f | wc -l) files);" \
    "SLURM start $((t_up - t_built)) s, jobs $((t_jobs - t_up)) s, total $((SECONDS - t0)) s"
