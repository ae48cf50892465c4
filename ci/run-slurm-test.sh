#!/usr/bin/env bash
# The Slurm test: brings up a single-node Slurm cluster (Debian's slurm-wlm and munge, daemons
# started directly as root, no systemd), submits validation/slurm/smoke.yaml through
# validation/slurm/submit.sh as a 4-task array plus the dependent merge-and-report job, waits
# (bounded), and checks that the merged folder equals a single-machine `phdslam run` of the same
# experiment in every non-timing column (ci/compare_results.py). Every daemon it started is
# stopped on exit, also on failure.
#
#   ci/run-slurm-test.sh [PHDSLAM_BINARY]     (default: build/release/apps/phdslam)
#
# Needs root (the daemons run as root with a generated munge key in a temporary folder).
# Environment: SLURM_TEST_TIMEOUT (seconds to wait for the jobs, default 600),
# SLURM_TEST_KEEP=1 keeps the temporary folder.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
started=$(date +%s)
program=$(realpath -m "${1:-build/release/apps/phdslam}")
[[ -f "$program" && -x "$program" ]] || {
  echo "run-slurm-test: no program $program (build first)" >&2
  exit 2
}
[[ "$(id -u)" -eq 0 ]] || { echo "run-slurm-test: needs root" >&2; exit 2; }
ci/install-deps.sh --slurm

tmp=$(mktemp -d /tmp/phdslam-slurm.XXXXXX)
chmod 755 "$tmp"
pids=()
stop_daemons() {
  local status=$?
  if [[ -n "${SLURM_CONF:-}" ]]; then  # this cluster's jobs first, so no job step outlives it
    scancel --full --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 50); do [[ -z "$(squeue -h 2>/dev/null)" ]] && break; sleep 0.1; done
  fi
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [[ $status -ne 0 ]]; then
    for log in "$tmp"/*.log "$tmp"/out/slurm/logs/*; do
      [[ -f "$log" ]] && { echo "--- $log"; tail -n 20 "$log"; }
    done >&2
  fi
  [[ "${SLURM_TEST_KEEP:-0}" == 1 ]] || rm -rf "$tmp"
  echo "run-slurm-test: daemons stopped; wall time $(( $(date +%s) - started )) s" >&2
  exit $status
}
trap stop_daemons EXIT
trap 'exit 130' INT TERM

# munge: a generated key, its own socket.
mkdir -p "$tmp/munge" && chmod 700 "$tmp/munge"
mungekey --create --keyfile="$tmp/munge/munge.key" --force
munged --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/socket" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munged.log" \
  --seed-file="$tmp/munge/seed"
for _ in $(seq 50); do [[ -s "$tmp/munge/munged.pid" ]] && break; sleep 0.1; done
pids+=("$(cat "$tmp/munge/munged.pid")")

# Slurm: one node, this host, ports chosen at random to avoid other clusters.
host=$(hostname -s)
cpus=$(nproc)
port=$(( 20000 + RANDOM % 20000 ))
mkdir -p "$tmp/state" "$tmp/spool"
cat > "$tmp/slurm.conf" <<CONF
ClusterName=phdslamtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$(( port + 1 ))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=600
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF"
for _ in $(seq 100); do [[ -s "$tmp/slurmctld.pid" ]] && break; sleep 0.1; done
pids+=("$(cat "$tmp/slurmctld.pid")")
slurmd -f "$SLURM_CONF"
for _ in $(seq 100); do [[ -s "$tmp/slurmd.pid" ]] && break; sleep 0.1; done
pids+=("$(cat "$tmp/slurmd.pid")")
for _ in $(seq 100); do
  sinfo -h -o '%t' 2>/dev/null | grep -qE '^(idle|mix|alloc)' && break
  sleep 0.2
done
sinfo

# Submit through the script, then the single-machine reference while the jobs run.
experiment=validation/slurm/smoke.yaml
submitted=$(PHDSLAM="$program" validation/slurm/submit.sh "$experiment" "$tmp/out" 4)
echo "$submitted"
array_id=$(awk '$1 == "array" {print $2}' <<< "$submitted")
merge_id=$(awk '$1 == "merge" {print $2}' <<< "$submitted")
"$program" run --experiment "$experiment" --quiet --jobs 1 --out "$tmp/single" > /dev/null

deadline=$(( $(date +%s) + ${SLURM_TEST_TIMEOUT:-600} ))
state=""
while (( $(date +%s) < deadline )); do
  state=$(scontrol show job "$merge_id" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  case "$state" in
    COMPLETED) break ;;
    FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE)
      echo "run-slurm-test: merge job $merge_id ended $state" >&2; exit 1 ;;
  esac
  sleep 1
done
[[ "$state" == COMPLETED ]] || { echo "run-slurm-test: timed out (merge job state '$state')" >&2; exit 1; }
for task in 1 2 3 4; do
  task_state=$(scontrol show job "${array_id}_$task" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  [[ "$task_state" == COMPLETED ]] || { echo "run-slurm-test: task $task $task_state" >&2; exit 1; }
  [[ -f "$tmp/out/shards/shard-$task/sweep.json" ]] || { echo "no shard $task" >&2; exit 1; }
done
[[ -s "$tmp/out/merged/report/index.html" ]] || { echo "run-slurm-test: no report" >&2; exit 1; }
python3 ci/compare_results.py "$tmp/single" "$tmp/out/merged"
echo "run-slurm-test: OK (4-task array $array_id, merge job $merge_id)"
