#!/usr/bin/env bash
# Self-test of slurm_cluster.sh: start a throw-away cluster, run a plain job, an array job and a
# dependent job, check a failing array task cancels its afterok dependant, stop the cluster and
# check nothing is left running. Repeats the cycle CYCLES times (default 2).
#
#   slurm_cluster_selftest.sh [CYCLES]
#
# Exit 0 ok, 77 skipped (propagated from slurm_cluster.sh), 1 failure.

set -u
set -o pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
harness=$here/slurm_cluster.sh
cycles=${1:-2}

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN {printf "%.2f", b - a}'; }
fail() {
    echo "FAIL: $*" >&2
    exit 1
}

# wait_jobs TIMEOUT JOBID... : wait until none of the jobs is pending/running/completing.
wait_jobs() {
    local timeout=$1 deadline
    shift
    deadline=$(($(date +%s) + timeout))
    local ids
    ids=$(
        IFS=,
        echo "$*"
    )
    while (($(date +%s) < deadline)); do
        [[ -z $(squeue -h -j "$ids" -t PD,R,CG,CF,S 2>/dev/null) ]] && return 0
        sleep 0.2
    done
    squeue >&2
    return 1
}

# State of a finished job from the jobcomp log (last record of that JobId).
job_state() {
    awk -v id="JobId=$1" '$1 == id {s = $0} END {print s}' "$dir/jobcomp.log" |
        sed -n 's/.* JobState=\([A-Z_]*\) .*/\1/p'
}

one_cycle() {
    local cycle=$1
    dir=$(mktemp -d "${TMPDIR:-/tmp}/slurmfarm.XXXXXX") || fail "mktemp"
    trap '"$harness" stop "$dir" >/dev/null 2>&1; rm -rf "$dir"' EXIT

    local t0 rc
    t0=$(now)
    "$harness" start "$dir"
    rc=$?
    ((rc == 77)) && exit 77
    ((rc == 0)) || fail "cycle $cycle: start failed ($rc)"
    echo "cycle $cycle: start took $(since "$t0")s"
    # shellcheck source=/dev/null
    source "$dir/env"

    # --- happy path: plain job, array job, dependent job -------------------------------------
    t0=$(now)
    local j1 ja jd
    j1=$(sbatch --parsable -o "$dir/j1.log" --wrap "echo hi > $dir/out.txt") || fail "sbatch j1"
    ja=$(sbatch --parsable --array=1-3 -o "$dir/arr_%a.log" \
        --wrap "echo task \$SLURM_ARRAY_TASK_ID > $dir/arr.\$SLURM_ARRAY_TASK_ID.txt") ||
        fail "sbatch array"
    jd=$(sbatch --parsable --dependency="afterok:$ja" --kill-on-invalid-dep=yes -o "$dir/dep.log" \
        --wrap "cat $dir/arr.*.txt > $dir/dep.txt; id -un; pwd; echo \"PATH=\$PATH\"") ||
        fail "sbatch dependant"
    wait_jobs 120 "$j1" "$ja" "$jd" || fail "jobs did not finish within 120 s"
    echo "cycle $cycle: 3 jobs (1 + array of 3 + dependant) done in $(since "$t0")s"
    [[ $(cat "$dir/out.txt" 2>/dev/null) == hi ]] || fail "out.txt wrong"
    local i
    for i in 1 2 3; do
        [[ $(cat "$dir/arr.$i.txt" 2>/dev/null) == "task $i" ]] || fail "arr.$i.txt wrong"
    done
    [[ $(wc -l <"$dir/dep.txt") -eq 3 ]] || fail "dependent job output wrong"
    [[ $(job_state "$jd") == COMPLETED ]] || fail "dependant state $(job_state "$jd")"
    echo "cycle $cycle: dependant ran as '$(sed -n 1p "$dir/dep.log")' in '$(sed -n 2p "$dir/dep.log")'"

    # --- failing array task: afterok dependant must be cancelled ------------------------------
    t0=$(now)
    local jf jfd
    jf=$(sbatch --parsable --array=1-3 -o /dev/null \
        --wrap "[ \$SLURM_ARRAY_TASK_ID = 2 ] && exit 1; sleep 1") || fail "sbatch failing array"
    jfd=$(sbatch --parsable --dependency="afterok:$jf" --kill-on-invalid-dep=yes -o /dev/null \
        --wrap "touch $dir/must_not_exist") || fail "sbatch failing dependant"
    wait_jobs 60 "$jf" || fail "failing array did not finish"
    local t_arr
    t_arr=$(now)
    wait_jobs 60 "$jfd" || fail "dependant of failed array not cancelled within 60 s"
    local st
    st=$(job_state "$jfd")
    [[ $st == CANCELLED ]] || fail "dependant of failed array ended as '$st'"
    [[ ! -e $dir/must_not_exist ]] || fail "dependant of failed array ran"
    echo "cycle $cycle: dependant of failed array CANCELLED $(since "$t_arr")s after the array ended" \
        "($(since "$t0")s after submission)"

    # --- stop and check nothing is left -------------------------------------------------------
    local pids
    pids=$(cat "$dir"/*.pid.started)
    t0=$(now)
    "$harness" stop "$dir" || fail "stop failed"
    echo "cycle $cycle: stop took $(since "$t0")s"
    "$harness" stop "$dir" || fail "second stop failed"
    local p state
    for p in $pids; do
        if [[ -r /proc/$p/stat ]]; then
            state=$(sed -e 's/^.*) //' "/proc/$p/stat" | cut -d' ' -f1)
            [[ $state == Z || $state == X ]] || fail "pid $p still running after stop"
        fi
    done
    for p in /proc/[0-9]*; do
        if { tr '\0' ' ' <"$p/cmdline"; } 2>/dev/null | grep -qF -- "$dir/"; then
            state=$(sed -e 's/^.*) //' "$p/stat" 2>/dev/null | cut -d' ' -f1)
            [[ $state == Z || $state == X || -z $state ]] ||
                fail "process ${p#/proc/} still uses $dir: $(tr '\0' ' ' <"$p/cmdline")"
        fi
    done
    rm -rf "$dir"
    trap - EXIT
    unset SLURM_CONF
}

for ((c = 1; c <= cycles; c++)); do
    one_cycle "$c"
done
echo "PASS: $cycles start/stop cycles"
