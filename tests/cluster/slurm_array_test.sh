#!/bin/bash
# SlurmCluster.ShardedArrayJobMergesToTheUnshardedRun: starts a single-node Slurm cluster in a
# temporary folder (munged with a generated key, slurmctld and slurmd started directly, no
# system service touched), runs tiny_experiment.json as a 2-task array job with
# examples/slurm/compare_array.sbatch (sbatch --wait), merges it with
# examples/slurm/compare_merge.sbatch chained by --dependency=afterok, and checks that the
# merged results equal the unsharded run's (results.json but wall_seconds, table.md, plots).
# The daemons are always shut down (scontrol shutdown; munged killed by its pid).
#
# Usage: slurm_array_test.sh STOCHNAV_BINARY SOURCE_DIR. Exit 77 (CTest: skipped) without root
# or without the Debian 12 packages slurm-wlm and munge. KEEP_SLURM_TEST_DIR=1 keeps the folder.
set -uo pipefail

stochnav=$1
source_dir=$2
experiment="$source_dir/tests/cluster/tiny_experiment.json"
examples="$source_dir/examples/slurm"

if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: the Slurm cluster test starts slurmctld/slurmd as SlurmUser=root; run it as root"
  exit 77
fi
for tool in munged mungekey munge slurmctld slurmd sbatch scontrol sinfo; do
  if ! PATH="$PATH:/usr/sbin:/sbin" command -v "$tool" > /dev/null; then
    echo "SKIP: $tool not found; install the Debian packages slurm-wlm and munge (.ci/packages.txt)"
    exit 77
  fi
done
export PATH="$PATH:/usr/sbin:/sbin"

work=$(mktemp -d /tmp/stochnav_slurm.XXXXXX)
chmod 700 "$work"
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/logs"
chmod 700 "$work/munge"
munged_pid="" slurmctld_pid="" slurmd_pid=""
export SLURM_CONF="$work/slurm.conf"

log() { echo "[slurm test $(date +%T)] $*"; }

show_logs() {
  for file in "$work"/logs/*; do
    [ -f "$file" ] || continue
    echo "----- $file (last 30 lines)"
    tail -n 30 "$file"
  done
}

fail() {
  echo "FAIL: $*"
  show_logs
  exit 1
}

# Waits up to $1 seconds for process $2 to end.
wait_for_exit() {
  local seconds=$1 pid=$2
  for _ in $(seq $((seconds * 10))); do
    kill -0 "$pid" 2> /dev/null || return 0
    sleep 0.1
  done
  return 1
}

cleanup() {
  local status=$?
  if [ -n "$slurmctld_pid" ] || [ -n "$slurmd_pid" ]; then
    timeout 10 scontrol shutdown > /dev/null 2>&1
  fi
  for pid in $slurmd_pid $slurmctld_pid $munged_pid; do
    kill -TERM "$pid" 2> /dev/null
    wait_for_exit 10 "$pid" || kill -KILL "$pid" 2> /dev/null
    wait "$pid" 2> /dev/null
  done
  if [ "${KEEP_SLURM_TEST_DIR:-0}" = 1 ]; then
    echo "kept $work"
  else
    rm -rf "$work"
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

# Two free TCP ports for slurmctld and slurmd (nothing answers on them).
port_is_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }
base=$((20000 + RANDOM % 20000))
while ! port_is_free "$base" || ! port_is_free $((base + 1)); do base=$((base + 2)); done

log "munged with a generated key"
mungekey --create --keyfile="$work/munge/munge.key" || fail "mungekey could not create a key"
socket="$work/munge/munge.socket"
munged --foreground --force --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --seed-file="$work/munge/munged.seed" \
  > "$work/logs/munged.log" 2>&1 &
munged_pid=$!
for _ in $(seq 100); do [ -S "$socket" ] && break; sleep 0.1; done
munge --socket="$socket" --no-input | unmunge --socket="$socket" > /dev/null ||
  fail "munged does not answer on $socket"

host=$(hostname -s)
cat > "$SLURM_CONF" << CONF
ClusterName=stochnavtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$base
SlurmdPort=$((base + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/logs/slurmctld.log
SlurmdLogFile=$work/logs/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

log "slurmctld and slurmd on ports $base and $((base + 1))"
slurmctld -D -i -f "$SLURM_CONF" > "$work/logs/slurmctld.out" 2>&1 &
slurmctld_pid=$!
slurmd -D -f "$SLURM_CONF" > "$work/logs/slurmd.out" 2>&1 &
slurmd_pid=$!
state=""
for _ in $(seq 60); do
  state=$(timeout 5 sinfo --noheader --nodes="$host" --format=%t 2> /dev/null)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] || fail "the node did not come up idle within 30 s (state '$state')"

log "unsharded reference run"
"$stochnav" compare "$experiment" --out "$work/out" > "$work/logs/reference.out" 2>&1 ||
  fail "the unsharded run failed"
mv "$work/out" "$work/reference"

log "array job of 2 shards (sbatch --wait)"
cd "$work" || fail "cannot enter $work"
array=$(STOCHNAV="$stochnav" timeout 120 sbatch --wait --parsable --array=0-1 --cpus-per-task=1 \
  --output="$work/logs/shard-%A_%a.out" "$examples/compare_array.sbatch" "$experiment" \
  "$work/out" 2)
array_status=$?
array=${array%%;*}
[ "$array_status" -eq 0 ] || fail "the array job ($array) failed or timed out (status $array_status)"
[ -d "$work/out/shards/shard-0-of-2" ] && [ -d "$work/out/shards/shard-1-of-2" ] ||
  fail "the array tasks did not write shard-0-of-2 and shard-1-of-2"

log "merge job after array job $array (--dependency=afterok)"
STOCHNAV="$stochnav" timeout 60 sbatch --wait --parsable --dependency="afterok:$array" \
  --kill-on-invalid-dep=yes --output="$work/logs/merge-%j.out" \
  "$examples/compare_merge.sbatch" "$work/out" > /dev/null ||
  fail "the merge job failed or timed out"

log "merged results against the unsharded run"
# nlohmann::json writes each double in its shortest exact form: equal text, equal bits.
grep -c '"per_seed"' "$work/out/results.json" > /dev/null || fail "no per-seed values in results.json"
diff <(grep -v '"wall_seconds"' "$work/reference/results.json") \
  <(grep -v '"wall_seconds"' "$work/out/results.json") > "$work/logs/results.diff" ||
  fail "results.json differs from the unsharded run's (logs/results.diff)"
cmp "$work/reference/table.md" "$work/out/table.md" || fail "table.md differs"
for plot in "$work"/reference/*.png; do
  [ -e "$plot" ] || continue
  cmp "$plot" "$work/out/$(basename "$plot")" || fail "$(basename "$plot") differs"
done
log "PASS: the array job's merged results equal the unsharded run"
