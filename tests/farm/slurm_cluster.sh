#!/usr/bin/env bash
# Throw-away single-node SLURM cluster for tests (ctest label `slurm`).
#
#   slurm_cluster.sh start DIR   start munged + slurmctld + slurmd, everything under DIR
#   slurm_cluster.sh stop DIR    stop exactly what `start DIR` started (by recorded PID)
#
# DIR should be a fresh, empty directory (e.g. from mktemp -d) with a short path: the munge
# socket lives at DIR/munge/munge.socket and a UNIX socket path must stay below 108 bytes.
# After `start`, `source DIR/env` sets SLURM_CONF so sbatch/squeue/scancel/sinfo/scontrol talk
# to this cluster. Finished jobs are recorded in DIR/jobcomp.log (one line per job with
# JobState=COMPLETED/FAILED/CANCELLED/... and ExitCode), since there is no accounting database.
#
# Exit codes: 0 ok; 77 skip (not root, or slurm/munge missing and cannot be installed);
# anything else is a failure (the relevant log tail is printed to stderr).
#
# Environment overrides (all optional):
#   SLURM_FARM_CTLD_PORT   first port to try for slurmctld (default 16817; slurmd uses the
#                          next free port after it); a free pair is searched upwards
#   SLURM_FARM_START_TIMEOUT  seconds to wait for the node to become idle (default 60)
#   SLURM_FARM_STOP_TIMEOUT   seconds to wait for each daemon to exit (default 20)
#   SLURM_FARM_NO_INSTALL=1   never run apt-get; skip (77) if packages are missing

set -u
set -o pipefail

SKIP=77
PACKAGES=(munge slurm-client slurmctld slurmd slurm-wlm)
# Marker put into the environment of every daemon we start, so that stop can verify a PID (and
# find the slurmstepd processes forked by our slurmd) without ever matching by program name.
MARKER_VAR=SLURM_FARM_CLUSTER_DIR

log() { echo "slurm_cluster: $*" >&2; }
die() { log "ERROR: $*"; exit 1; }
skip() { echo "SKIP: $*"; exit "$SKIP"; }

usage() {
    echo "usage: $0 start|stop DIR" >&2
    exit 2
}

# ---------------------------------------------------------------------------------------------
# Process helpers (PID based only)

# True if PID exists and is not a zombie. Zombies matter here: the daemons are reparented to
# PID 1 when `start` exits, and a container's PID 1 does not necessarily reap them.
pid_alive() {
    local pid=$1 state
    [[ $pid =~ ^[0-9]+$ ]] || return 1
    [[ -r /proc/$pid/stat ]] || return 1
    state=$(sed -e 's/^.*) //' "/proc/$pid/stat" 2>/dev/null | cut -d' ' -f1) || return 1
    [[ -n $state && $state != Z && $state != X ]]
}

# True if PID is one of ours: its environment carries MARKER_VAR=DIR or its command line
# mentions DIR. Protects against PID reuse after the daemon died long ago.
pid_is_ours() {
    local pid=$1 dir=$2
    pid_alive "$pid" || return 1
    if { tr '\0' '\n' <"/proc/$pid/environ"; } 2>/dev/null | grep -qxF "$MARKER_VAR=$dir"; then
        return 0
    fi
    { tr '\0' ' ' <"/proc/$pid/cmdline"; } 2>/dev/null | grep -qF -- "$dir/"
}

# Live leftovers of the cluster in DIR: processes whose environment carries our marker (the
# daemons and the slurmstepd forked by our slurmd), job processes (SLURM_JOB_ID set and
# SLURM_CONF pointing at DIR), and all their descendants. Never this script or its ancestors.
cluster_pids() {
    local dir=$1 p pid stat rest e has_marker has_job has_conf
    local -a fields env
    local -A parent=() root=() skip=()
    # Bash builtins only (no fork per process): this scans every process on the machine.
    for p in /proc/[0-9]*; do
        pid=${p#/proc/}
        { read -r stat <"$p/stat"; } 2>/dev/null || continue
        rest=${stat##*) }
        read -r -a fields <<<"$rest"
        [[ -n ${fields[1]:-} ]] || continue
        parent[$pid]=${fields[1]}
        { mapfile -t -d '' env <"$p/environ"; } 2>/dev/null || continue
        has_marker=0 has_job=0 has_conf=0
        for e in "${env[@]}"; do
            case $e in
            "$MARKER_VAR=$dir") has_marker=1 ;;
            SLURM_JOB_ID=*) has_job=1 ;;
            "SLURM_CONF=$dir/slurm.conf") has_conf=1 ;;
            esac
        done
        if ((has_marker || (has_job && has_conf))); then
            root[$pid]=1
        fi
    done
    pid=$BASHPID
    while [[ -n $pid && $pid != 0 && -z ${skip[$pid]:-} ]]; do
        skip[$pid]=1
        pid=${parent[$pid]:-}
    done
    skip[$$]=1
    for pid in "${!parent[@]}"; do
        [[ -n ${skip[$pid]:-} ]] && continue
        # Walk up the parent chain; a process belongs to the cluster if any ancestor does.
        p=$pid
        while [[ -n $p && $p != 0 && $p != 1 ]]; do
            if [[ -n ${root[$p]:-} ]]; then
                pid_alive "$pid" && echo "$pid"
                break
            fi
            p=${parent[$p]:-}
        done
    done
}

# Wait up to $2 seconds for PID $1 to go away.
wait_gone() {
    local pid=$1 timeout=$2 i
    for ((i = 0; i < timeout * 10; i++)); do
        pid_alive "$pid" || return 0
        sleep 0.1
    done
    ! pid_alive "$pid"
}

# TERM, wait, then KILL one recorded PID if it is still ours.
stop_pid() {
    local name=$1 pid=$2 dir=$3 timeout=$4
    if ! pid_is_ours "$pid" "$dir"; then
        return 0
    fi
    kill -TERM "$pid" 2>/dev/null || true
    if wait_gone "$pid" "$timeout"; then
        log "stopped $name (pid $pid)"
        return 0
    fi
    log "$name (pid $pid) ignored SIGTERM for ${timeout}s, sending SIGKILL"
    kill -KILL "$pid" 2>/dev/null || true
    wait_gone "$pid" 5 || { log "WARNING: $name (pid $pid) still alive after SIGKILL"; return 1; }
}

# ---------------------------------------------------------------------------------------------
# Package check / install

have_binaries() {
    local b
    for b in munged slurmctld slurmd sinfo sbatch squeue scancel scontrol; do
        command -v "$b" >/dev/null 2>&1 || return 1
    done
}

ensure_packages() {
    # Debian puts the daemons into /usr/sbin, which a non-login PATH may lack.
    case ":$PATH:" in *:/usr/sbin:*) ;; *) PATH=$PATH:/usr/sbin ;; esac
    case ":$PATH:" in *:/sbin:*) ;; *) PATH=$PATH:/sbin ;; esac
    export PATH
    have_binaries && return 0
    [[ ${SLURM_FARM_NO_INSTALL:-0} == 1 ]] && skip "slurm/munge not installed and SLURM_FARM_NO_INSTALL=1"
    [[ $(id -u) -eq 0 ]] || skip "slurm/munge not installed and not root (cannot apt-get install)"
    command -v apt-get >/dev/null 2>&1 || skip "slurm/munge not installed and no apt-get on this system"
    log "installing ${PACKAGES[*]} with apt-get"
    export DEBIAN_FRONTEND=noninteractive
    local aptlog
    aptlog=$(mktemp) || skip "cannot create a temporary file for the apt-get log"
    if ! apt-get update -qq >"$aptlog" 2>&1 ||
        ! apt-get install -y -qq --no-install-recommends "${PACKAGES[@]}" >>"$aptlog" 2>&1; then
        tail -n 20 "$aptlog" >&2
        rm -f "$aptlog"
        skip "apt-get could not install ${PACKAGES[*]} (see above)"
    fi
    rm -f "$aptlog"
    have_binaries || skip "packages installed but slurm/munge binaries still missing"
}

# ---------------------------------------------------------------------------------------------
# Ports

port_in_use() {
    local port=$1
    if command -v ss >/dev/null 2>&1; then
        ss -Hltn "sport = :$port" 2>/dev/null | grep -q . && return 0
        return 1
    fi
    # Fallback: something answers on the port.
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null
}

# Print two free ports, starting the search at $1.
pick_ports() {
    local port=$1 found=() tries=0
    while ((${#found[@]} < 2 && tries < 200)); do
        port_in_use "$port" || found+=("$port")
        port=$((port + 1))
        tries=$((tries + 1))
    done
    ((${#found[@]} == 2)) || return 1
    echo "${found[0]} ${found[1]}"
}

# ---------------------------------------------------------------------------------------------

show_tail() {
    local f
    for f in "$@"; do
        [[ -s $f ]] || continue
        echo "----- tail of $f -----" >&2
        tail -n 25 "$f" >&2
    done
}

cmd_stop() {
    local dir=$1 timeout=${SLURM_FARM_STOP_TIMEOUT:-20} rc=0 pid name
    [[ -d $dir ]] || { log "stop: $dir does not exist, nothing to do"; return 0; }

    # Cancel remaining jobs first so slurmstepd/job processes are torn down by slurm itself.
    if [[ -f $dir/slurmctld.pid.started && -f $dir/slurm.conf ]] &&
        pid_is_ours "$(cat "$dir/slurmctld.pid.started")" "$dir"; then
        local jobs=()
        mapfile -t jobs < <(SLURM_CONF=$dir/slurm.conf timeout 10 squeue -h -o %A 2>/dev/null | sort -u)
        if ((${#jobs[@]} > 0)); then
            log "cancelling leftover jobs: ${jobs[*]}"
            SLURM_CONF=$dir/slurm.conf timeout 10 scancel "${jobs[@]}" 2>/dev/null || true
            local i
            for ((i = 0; i < 50; i++)); do
                [[ -z $(SLURM_CONF=$dir/slurm.conf timeout 5 squeue -h -o %A 2>/dev/null) ]] && break
                sleep 0.2
            done
        fi
    fi

    for name in slurmd slurmctld munged; do
        [[ -f $dir/$name.pid.started ]] || continue
        pid=$(cat "$dir/$name.pid.started" 2>/dev/null)
        stop_pid "$name" "$pid" "$dir" "$timeout" || rc=1
    done

    # Anything else of this cluster (slurmstepd and job processes of jobs that were still
    # running, e.g. because slurmctld had died and scancel was impossible). A few rounds, in
    # case something forked while being killed.
    local left=()
    for _ in 1 2 3; do
        mapfile -t left < <(cluster_pids "$dir")
        ((${#left[@]} > 0)) || break
        log "killing leftover processes of this cluster: ${left[*]}"
        for pid in "${left[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
        for pid in "${left[@]}"; do wait_gone "$pid" 5 || true; done
    done
    mapfile -t left < <(cluster_pids "$dir")
    if ((${#left[@]} > 0)); then
        log "WARNING: processes of this cluster survived: ${left[*]}"
        rc=1
    fi
    rm -f "$dir"/*.pid.started
    return $rc
}

cmd_start() {
    local dir=$1 v
    # Do not let an outer SLURM job/cluster environment (SLURM_JOB_ID, SLURM_CONF, ...) leak
    # into the daemons or the client commands used here.
    for v in $(compgen -e | grep '^SLURM_'); do
        [[ $v == SLURM_FARM_* ]] || unset "$v"
    done
    [[ $(id -u) -eq 0 ]] || skip "the throw-away SLURM cluster needs root (slurmd must run as root)"
    ensure_packages
    mkdir -p "$dir" || die "cannot create $dir"
    dir=$(cd "$dir" && pwd -P) || die "cannot resolve $dir"
    [[ ! -e $dir/slurm.conf ]] || die "$dir already holds a cluster (slurm.conf exists); use a fresh directory"

    local host nproc mem_mb start_ts
    start_ts=$(date +%s.%N)
    # slurmctld and slurmd compare these names with gethostname() cut at the first dot.
    host=$(hostname -s 2>/dev/null) || host=$(uname -n)
    host=${host%%.*}
    [[ -n $host ]] || die "cannot determine the short hostname"
    nproc=$(nproc)
    mem_mb=$(awk '/^MemTotal:/ {print int($2/1024)}' /proc/meminfo 2>/dev/null)
    local real_mem=1000
    [[ -n $mem_mb ]] && ((mem_mb < 1200)) && real_mem=$((mem_mb / 2))

    local munge_dir=$dir/munge
    local sock=$munge_dir/munge.socket
    ((${#sock} < 100)) || die "DIR path too long for a UNIX socket: $sock (${#sock} bytes)"

    # Serialise concurrent starts on this machine from port choice until both daemons listen,
    # so two clusters never pick the same ports. Daemons get fd 9 closed (9>&-).
    exec 9>"${TMPDIR:-/tmp}/slurm_farm_cluster.lock" || die "cannot open lock file"
    flock -w 120 9 || die "timed out waiting for another slurm_cluster.sh start"

    local ports ctld_port slurmd_port
    ports=$(pick_ports "${SLURM_FARM_CTLD_PORT:-16817}") || die "no free TCP ports found"
    read -r ctld_port slurmd_port <<<"$ports"

    # If anything below fails (or start is interrupted, e.g. by a ctest timeout), tear down
    # what was started.
    local qdir
    printf -v qdir %q "$dir"
    trap 'rc=$?; if ((rc != 0)); then log "start failed, stopping what was started"; cmd_stop '"$qdir"' >/dev/null 2>&1; fi' EXIT
    trap 'exit 143' TERM
    trap 'exit 130' INT
    trap 'exit 129' HUP

    # --- munge ---------------------------------------------------------------------------------
    # munged refuses insecure paths: the socket dir must be a+x but not group/other writable.
    mkdir -p "$munge_dir" || die "cannot create $munge_dir"
    chmod 0755 "$munge_dir" || die "cannot chmod $munge_dir"
    dd if=/dev/urandom of="$munge_dir/munge.key" bs=1024 count=1 status=none ||
        die "cannot write munge key"
    chmod 0400 "$munge_dir/munge.key"
    chown "$(id -u):$(id -g)" "$munge_dir/munge.key"

    # --force: munged insists that every ancestor of the socket is a+x and refuses a 0700
    # mktemp dir; only root talks to this munged, so downgrade that check to a warning.
    env "$MARKER_VAR=$dir" munged --foreground --force \
        --socket="$sock" \
        --key-file="$munge_dir/munge.key" \
        --pid-file="$munge_dir/munged.pid" \
        --log-file="$munge_dir/munged.log" \
        --seed-file="$munge_dir/munged.seed" \
        </dev/null >"$munge_dir/munged.out" 2>&1 9>&- &
    echo $! >"$dir/munged.pid.started"
    local i
    for ((i = 0; i < 100; i++)); do
        [[ -S $sock ]] && break
        pid_alive "$(cat "$dir/munged.pid.started")" || break
        sleep 0.1
    done
    if [[ ! -S $sock ]] || ! munge -n -S "$sock" </dev/null | unmunge -S "$sock" >/dev/null 2>&1; then
        show_tail "$munge_dir/munged.out" "$munge_dir/munged.log"
        die "munged did not come up on $sock"
    fi

    # --- slurm config --------------------------------------------------------------------------
    mkdir -p "$dir/state" "$dir/spool" "$dir/log" || die "cannot create state dirs"
    cat >"$dir/slurm.conf" <<EOF
# Generated by $(basename "$0") for a throw-away test cluster.
ClusterName=farmtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$dir/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/filetxt
JobCompLoc=$dir/jobcomp.log
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
# Default batch_sched_delay=3 makes every scheduling pass after a job ends wait ~3 s.
SchedulerParameters=batch_sched_delay=0
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=300
NodeName=$host NodeAddr=127.0.0.1 CPUs=$nproc RealMemory=$real_mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
    # Keep the system /etc/slurm/plugstack.conf (and its includes) out of the test cluster.
    : >"$dir/plugstack.conf"
    # cgroup.conf is only read from the slurm.conf directory. Slurm 22.05 (Debian 12) loads no
    # cgroup code with proctrack/linuxproc + task/none + jobacct_gather/none and does not need
    # the file (its CgroupPlugin has no "disabled" value). From 23.02 on slurmd initialises
    # cgroups regardless, which fails in most containers, and CgroupPlugin=disabled exists.
    local version major minor
    version=$(slurmd -V 2>/dev/null | awk '{print $2}')
    IFS=. read -r major minor _ <<<"${version:-0.0}"
    if ((10#${major:-0} > 23 || (10#${major:-0} == 23 && 10#${minor:-0} >= 2))); then
        printf 'CgroupPlugin=disabled\n' >"$dir/cgroup.conf"
    fi
    printf 'export SLURM_CONF=%s\n' "$dir/slurm.conf" >"$dir/env"

    # --- daemons -------------------------------------------------------------------------------
    export SLURM_CONF=$dir/slurm.conf
    env "$MARKER_VAR=$dir" slurmctld -D -i -f "$dir/slurm.conf" \
        </dev/null >"$dir/log/slurmctld.out" 2>&1 9>&- &
    echo $! >"$dir/slurmctld.pid.started"

    # Wait for slurmctld to answer before starting slurmd (avoids a registration retry delay).
    local ok=0
    for ((i = 0; i < 300; i++)); do
        if ! pid_alive "$(cat "$dir/slurmctld.pid.started")"; then break; fi
        if timeout 5 scontrol ping 2>/dev/null | grep -q 'is UP'; then ok=1; break; fi
        sleep 0.2
    done
    if ((ok == 0)); then
        show_tail "$dir/log/slurmctld.out" "$dir/log/slurmctld.log"
        die "slurmctld did not come up"
    fi

    env "$MARKER_VAR=$dir" slurmd -D -N "$host" -f "$dir/slurm.conf" \
        </dev/null >"$dir/log/slurmd.out" 2>&1 9>&- &
    echo $! >"$dir/slurmd.pid.started"

    local deadline state=""
    deadline=$(($(date +%s) + ${SLURM_FARM_START_TIMEOUT:-60}))
    while (($(date +%s) < deadline)); do
        if ! pid_alive "$(cat "$dir/slurmd.pid.started")"; then
            show_tail "$dir/log/slurmd.out" "$dir/log/slurmd.log"
            die "slurmd exited during start-up"
        fi
        if ! pid_alive "$(cat "$dir/slurmctld.pid.started")"; then
            show_tail "$dir/log/slurmctld.out" "$dir/log/slurmctld.log"
            die "slurmctld exited during start-up"
        fi
        state=$(timeout 5 sinfo -h -N -n "$host" -o %T 2>/dev/null | head -n1)
        [[ $state == idle ]] && break
        sleep 0.2
    done
    if [[ $state != idle ]]; then
        timeout 5 scontrol show node "$host" >&2 2>/dev/null
        show_tail "$dir/log/slurmctld.log" "$dir/log/slurmd.out" "$dir/log/slurmd.log"
        die "node $host not idle after ${SLURM_FARM_START_TIMEOUT:-60}s (state: '${state:-none}')"
    fi
    trap - EXIT TERM INT HUP
    exec 9>&-
    local elapsed
    elapsed=$(awk -v a="$start_ts" -v b="$(date +%s.%N)" 'BEGIN {printf "%.1f", b - a}')
    echo "slurm cluster up in ${elapsed}s: node $host ($nproc CPUs) idle, ports $ctld_port/$slurmd_port; source $dir/env"
}

main() {
    (($# == 2)) || usage
    # A caller piping our output into e.g. `head` must not make us die half-way through a stop.
    trap '' PIPE
    local cmd=$1 dir=$2
    [[ -n $dir ]] || usage
    case $dir in /*) ;; *) dir=$PWD/$dir ;; esac
    case $cmd in
    start) cmd_start "$dir" ;;
    stop)
        [[ -d $dir ]] && dir=$(cd "$dir" && pwd -P)
        cmd_stop "$dir"
        ;;
    *) usage ;;
    esac
}

main "$@"
