#!/usr/bin/env bash
# A single-node Slurm cluster from Debian's packages (slurm-wlm, munge), for `serosa batch
# --slurm` and its test: munged, slurmctld and slurmd on this machine, their state and logs in
# one folder, nothing in /etc changed (the key munge's package made is used as it is).
#
#   tools/slurm_cluster.sh start DIR     starts it; prints `export SLURM_CONF=DIR/slurm.conf`
#   tools/slurm_cluster.sh stop DIR      stops what `start` started
#
# Needs root (slurmd runs jobs as their user; munged reads its key). The node takes this
# machine's short host name and all its CPUs; one partition, "serosa", the default.
set -euo pipefail
cmd=${1:-}
dir=${2:-}
[[ -n "$cmd" && -n "$dir" ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)

stop() {
  for d in slurmd slurmctld munged; do
    if [[ -f "$dir/$d.pid" ]]; then
      kill "$(cat "$dir/$d.pid")" 2>/dev/null || true
      rm -f "$dir/$d.pid"
    fi
  done
}

if [[ "$cmd" == stop ]]; then stop; exit 0; fi
[[ "$cmd" == start ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "$0: needs root (slurmd, munged), and sudo is missing" >&2; exit 1; }
  exec sudo -n "$0" "$@"
fi
for b in munged slurmctld slurmd sbatch squeue scontrol; do
  command -v "$b" >/dev/null || { echo "$0: $b is missing: install slurm-wlm and munge" >&2; exit 1; }
done
stop
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
host=$(hostname -s)
cpus=$(nproc)
# Free ports above 20000, so that a second cluster (another test) does not collide.
port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
ctld_port=$(port)
slurmd_port=$(port)

# munge: its own socket in DIR, the package's key.
key=/etc/munge/munge.key
if [[ ! -s $key ]]; then
  mkdir -p /etc/munge
  dd if=/dev/urandom of=$key bs=1 count=1024 status=none
  chmod 400 $key
fi
chown root "$dir/munge"
munged --force --socket="$dir/munge/munge.socket" --pid-file="$dir/munged.pid" \
  --key-file="$key" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed"

cat >"$dir/slurm.conf" <<CONF
ClusterName=serosa
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
SwitchType=switch/none
MaxArraySize=10001
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=serosa Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=NO
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -f "$SLURM_CONF" -i
slurmd -f "$SLURM_CONF"
# Ready when the node is idle.
for _ in $(seq 1 60); do
  if sinfo -h -o %t 2>/dev/null | grep -q '^idle'; then
    echo "export SLURM_CONF=$SLURM_CONF"
    exit 0
  fi
  sleep 0.5
done
echo "$0: the node never came up; see $dir/slurmctld.log and $dir/slurmd.log" >&2
sinfo >&2 || true
exit 1
