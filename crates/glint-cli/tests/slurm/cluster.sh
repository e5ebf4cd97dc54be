#!/bin/bash
# A throwaway single-node Slurm cluster for tests/slurm.rs, run as root:
# munged with its own key and socket, slurmctld and slurmd on 127.0.0.1 with
# this machine's CPUs and memory, every file in a new temporary directory, no
# systemd.
#
#   cluster.sh SLURMCTLD_PORT SLURMD_PORT
#
# Prints `ready DIR` once the node takes jobs; clients reach the cluster with
# SLURM_CONF=DIR/slurm.conf. It stays up until its standard input closes (when
# the test ends, however it ends), then cancels what still runs, stops the
# daemons and removes DIR. When a daemon cannot start, its own messages go to
# standard error and the exit code is not 0.
set -euo pipefail

ctld_port=$1 slurmd_port=$2
dir=$(mktemp -d -t glint-slurm.XXXXXX)
export SLURM_CONF=$dir/slurm.conf
munged_pid="" slurmctld_pid="" slurmd_pid=""

stop() {
  if [ -n "$slurmctld_pid" ] && kill -0 "$slurmctld_pid" 2>/dev/null; then
    scancel --quiet --full --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 100); do
      [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  for pid in $slurmd_pid $slurmctld_pid $munged_pid; do
    kill "$pid" 2>/dev/null || true
  done
  wait 2>/dev/null || true
  rm -rf "$dir"
}
trap stop EXIT
trap 'exit 1' INT TERM

# Fails with the daemon's own messages when it has exited.
check_running() {
  local name=$1 pid=$2
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "$name did not start:" >&2
    tail -n 20 "$dir/$name.log" >&2
    exit 1
  fi
}

mkdir -m 0755 "$dir/munge"
mkdir "$dir/state" "$dir/spool"
head -c 1024 /dev/urandom >"$dir/munge/munge.key"
chmod 0400 "$dir/munge/munge.key"
munged --foreground --force --socket="$dir/munge/socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munge/munged.pid" --seed-file="$dir/munge/seed" \
  </dev/null >"$dir/munged.log" 2>&1 &
munged_pid=$!
for _ in $(seq 100); do
  [ -S "$dir/munge/socket" ] && break
  check_running munged "$munged_pid"
  sleep 0.1
done
if [ ! -S "$dir/munge/socket" ]; then
  echo "munged made no socket in 10 s:" >&2
  tail -n 20 "$dir/munged.log" >&2
  exit 1
fi

# `slurmd -C` prints this machine's node line (CPUs, sockets, cores, memory);
# the node keeps its own name. Jobs are requeued only when they ask to
# (`#SBATCH --requeue`), so the recipes' own line is what the test relies on.
node=$(slurmd -C | head -n 1 | sed -E 's/^NodeName=[^ ]+ //')
user=$(id -un)
cat >"$SLURM_CONF" <<EOF
ClusterName=glint-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
AuthInfo=socket=$dir/munge/socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MailProg=/bin/true
JobRequeue=0
NodeName=glint NodeAddr=127.0.0.1 NodeHostname=localhost $node State=UNKNOWN
PartitionName=glint Nodes=glint Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -D -i </dev/null >"$dir/slurmctld.log" 2>&1 &
slurmctld_pid=$!
slurmd -D -N glint </dev/null >"$dir/slurmd.log" 2>&1 &
slurmd_pid=$!
for _ in $(seq 300); do
  check_running slurmctld "$slurmctld_pid"
  check_running slurmd "$slurmd_pid"
  [ "$(sinfo -h -n glint -o %t 2>/dev/null)" = idle ] && break
  sleep 0.1
done
if [ "$(sinfo -h -n glint -o %t 2>/dev/null)" != idle ]; then
  echo "the node is not idle after 30 s:" >&2
  sinfo -N -l >&2 || true
  tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2
  exit 1
fi
echo "ready $dir"
cat >/dev/null
