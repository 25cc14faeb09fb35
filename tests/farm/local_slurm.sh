# A single-node Slurm cluster on localhost in a temporary directory, for the farm tests.
# Sourced, not run: start_local_slurm DIR starts munged, slurmctld and slurmd with their
# own configuration, spool, state and key under DIR and exports SLURM_CONF;
# stop_local_slurm stops them. The caller traps EXIT to stop them on every path.
# Root is needed (slurmd runs jobs as their owner). Nothing here skips: any daemon that
# does not come up is an error.

local_slurm_dir=""

local_slurm_fail()
{
    echo "local_slurm: error: $*" >&2
    if [[ -n "$local_slurm_dir" ]]; then
        for log in "$local_slurm_dir"/log/*.log; do
            [[ -f "$log" ]] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }
        done
    fi
    return 1
}

start_local_slurm()
{
    local dir=$1
    local_slurm_dir=$dir
    mkdir -p "$dir"/{munge,spool/ctld,spool/d,log,state}
    local cpus memory_mb ports_base
    cpus=$(nproc)
    memory_mb=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 * 3 / 4 ))
    # Ports away from the defaults (6817/6818), so that a real cluster on this host is untouched.
    ports_base=$(( 17000 + RANDOM % 2000 ))

    command -v munged >/dev/null || { local_slurm_fail "munged not found (install munge)"; return 1; }
    command -v slurmctld >/dev/null || { local_slurm_fail "slurmctld not found (install slurmctld)"; return 1; }
    command -v slurmd >/dev/null || { local_slurm_fail "slurmd not found (install slurmd)"; return 1; }

    dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
    chmod 0400 "$dir/munge/munge.key"
    chmod 0700 "$dir/munge"
    munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
        --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
        --seed-file="$dir/munge/munged.seed" --force ||
        { local_slurm_fail "munged did not start"; return 1; }

    cat >"$dir/slurm.conf" <<CONF
ClusterName=statmctest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ports_base
SlurmdPort=$((ports_base + 1))
AuthType=auth/munge
# cred_expire: also how long a requeued job waits before it may start again (default 120 s).
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
CryptoType=crypto/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/d
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
MinJobAge=300
KillWait=5
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
    export SLURM_CONF="$dir/slurm.conf"
    slurmctld -f "$SLURM_CONF" || { local_slurm_fail "slurmctld did not start"; return 1; }
    slurmd -f "$SLURM_CONF" || { local_slurm_fail "slurmd did not start"; return 1; }
    # The node registers within seconds; wait for it to be idle (bounded).
    local i state
    for i in $(seq 1 60); do
        state=$(sinfo -h -n localhost -o %t 2>/dev/null || true)
        [[ "$state" == idle* ]] && return 0
        sleep 0.5
    done
    local_slurm_fail "the node did not become idle within 30 s (state '$state')"
}

stop_local_slurm()
{
    [[ -z "$local_slurm_dir" ]] && return 0
    local dir=$local_slurm_dir pidfile pid
    for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
        [[ -f "$pidfile" ]] || continue
        pid=$(cat "$pidfile")
        kill "$pid" 2>/dev/null || true
        for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null || true
    done
    local_slurm_dir=""
}
