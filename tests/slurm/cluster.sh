# cluster.sh — a single-node Slurm cluster for tests, in a temporary directory.
#
# Source it, then:  cluster_start DIR   (munged + slurmctld + slurmd for this
# host, their state, spool, logs and sockets under DIR; exports SLURM_CONF)
#                   cluster_stop        (stops every daemon cluster_start began)
# Nothing outside DIR is written; the daemons use free ports picked at start.
# Returns 77 from cluster_start when the Slurm or MUNGE programs are missing.

CLUSTER_PIDS=()

# Prints a TCP port nobody listens on (from a range above the usual ones).
cluster__free_port() {
  local p
  for p in $(shuf -i 20000-59999 -n 50); do
    if ! (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null; then echo "$p"; return 0; fi
  done
  return 1
}

# Waits up to $2 seconds for the command $1 to succeed.
cluster__wait() {
  local i
  for i in $(seq 1 $(( $2 * 10 ))); do
    eval "$1" >/dev/null 2>&1 && return 0
    sleep 0.1
  done
  return 1
}

cluster__conf() {
  local dir=$1 host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  mem=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
  cat > "$dir/slurm.conf" <<CONF
ClusterName=dmbenchtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=$(id -un)
SlurmdUser=root
SlurmctldPort=$(cluster__free_port)
SlurmdPort=$(cluster__free_port)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
}

cluster_start() {
  local dir=$1 p
  for p in munged slurmctld slurmd sbatch scontrol; do
    command -v "$p" >/dev/null || { echo "SKIP: $p not found (install slurm-wlm and munge: scripts/install-deps)"; return 77; }
  done
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chmod 700 "$dir" "$dir/munge"
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 600 "$dir/munge/munge.key"
  munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
         --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
         --seed-file="$dir/munge/munged.seed" || { echo "munged did not start"; return 1; }
  cluster__wait "test -s '$dir/munge/munged.pid'" 10
  CLUSTER_PIDS+=("$(cat "$dir/munge/munged.pid")")
  cluster__conf "$dir"
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -f "$SLURM_CONF" || { cat "$dir/log/slurmctld.log"; return 1; }
  cluster__wait "test -s '$dir/slurmctld.pid'" 10
  CLUSTER_PIDS+=("$(cat "$dir/slurmctld.pid")")
  slurmd -f "$SLURM_CONF" || { cat "$dir/log/slurmd.log"; return 1; }
  cluster__wait "test -s '$dir/slurmd.pid'" 10
  CLUSTER_PIDS+=("$(cat "$dir/slurmd.pid")")
  if ! cluster__wait "sinfo -h -o %T | grep -qx idle" 30; then
    echo "the node did not become idle:"; sinfo; tail -20 "$dir/log/slurmctld.log" "$dir/log/slurmd.log"
    return 1
  fi
}

cluster_stop() {
  local i pid
  for (( i=${#CLUSTER_PIDS[@]}-1; i>=0; i-- )); do
    pid=${CLUSTER_PIDS[$i]}
    kill "$pid" 2>/dev/null || continue
    cluster__wait "! kill -0 $pid" 10 || kill -9 "$pid" 2>/dev/null || true
  done
  CLUSTER_PIDS=()
}
