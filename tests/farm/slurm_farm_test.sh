#!/usr/bin/env bash
# ctest label `slurm`: a real single-node SLURM cluster (munge, slurmctld, slurmd on 127.0.0.1,
# started and stopped by slurm_cluster.sh) runs `nenrin farm slurm` jobs, and their results must
# be byte-identical to one-machine runs:
#   1. a render split into 4 tiles plus its merge job (EXR and PNG), then the same after one
#      part is deleted and retry.sh resubmits only that part;
#   2. a 3-frame batch (a seed sweep), each frame against `nenrin render --set`.
#
#   slurm_farm_test.sh NENRIN SCENE
#
# Exit 0 pass, 77 skip (no root, packages not installable), 1 failure.
set -u
set -o pipefail

nenrin=$1
scene=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)
harness=$here/slurm_cluster.sh
fail() {
    echo "FAIL: $*" >&2
    exit 1
}

dir=$(mktemp -d "${TMPDIR:-/tmp}/nenrin-slurm.XXXXXX") || fail "mktemp"
chmod 755 "$dir"
trap '"$harness" stop "$dir/cluster" >/dev/null 2>&1; rm -rf "$dir"' EXIT
mkdir "$dir/cluster" "$dir/work"
"$harness" start "$dir/cluster"
rc=$?
((rc == 77)) && exit 77
((rc == 0)) || fail "the cluster did not start ($rc)"
# shellcheck source=/dev/null
source "$dir/cluster/env"
cd "$dir/work" || fail "cd"

# Waits (at most $1 s) until the jobs in the given .jobid files have left the queue.
wait_for() {
    local deadline=$(($(date +%s) + $1)) ids
    shift
    ids=$(cat "$@" | paste -sd,)
    while (($(date +%s) < deadline)); do
        [[ -z $(squeue -h -j "$ids" -t PD,R,CG,CF,S 2>/dev/null) ]] && return 0
        sleep 0.5
    done
    squeue >&2
    return 1
}
show_logs() {
    for f in "$1"/logs/*; do
        echo "--- $f" >&2
        tail -n 20 "$f" >&2
    done
}

common=(--res 96x72 --spp 4)

# 1. A 4-tile render.
"$nenrin" render "$scene" "${common[@]}" -o one.exr --png one.png -q >/dev/null || fail "render"
"$nenrin" farm slurm --tiles 4 --job-dir job render "$scene" "${common[@]}" -o farm.exr \
    --png farm.png || fail "nenrin farm slurm (render)"
wait_for 300 job/tasks.jobid job/merge.jobid || fail "the render job did not finish in 300 s"
[[ -f farm.exr ]] || {
    show_logs job
    fail "the merge job wrote no farm.exr"
}
cmp one.exr farm.exr || fail "the merged render differs from the one-machine render"
cmp one.png farm.png || fail "the merged PNG differs from the one-machine PNG"
[[ $(ls job/logs | grep -c '^task-') -eq 4 ]] || fail "expected 4 task logs"
echo "4-tile render: merged EXR and PNG byte-identical to one machine"

# A lost part: retry.sh resubmits only part 2, then the merge.
rm job/parts/part-2.exr farm.exr farm.png
job/retry.sh | tee retry.out || fail "retry.sh"
grep -q "resubmitted tasks 2 " retry.out || fail "retry.sh did not resubmit only part 2"
wait_for 300 job/tasks.jobid job/merge.jobid || fail "the retried job did not finish in 300 s"
cmp one.exr farm.exr || fail "the merge after a retry differs from the one-machine render"
echo "retry of a lost part: byte-identical again"

# 2. A 3-frame batch: a seed sweep.
cat >batch.json <<JSON
{"scene": "$scene", "output": "frames/{name}.exr",
 "set": {"/render/resolution": [96, 72], "/render/spp": 4},
 "sweep": {"/render/seed": [1, 2, 3]}}
JSON
"$nenrin" farm slurm --job-dir batch.job batch batch.json || fail "nenrin farm slurm (batch)"
wait_for 300 batch.job/tasks.jobid || fail "the batch did not finish in 300 s"
for seed in 1 2 3; do
    frame=frames/frame-0001-000$seed.exr
    [[ -f $frame ]] || {
        show_logs batch.job
        fail "the batch wrote no $frame"
    }
    "$nenrin" render "$scene" --set "/render/resolution=[96,72]" \
        --set /render/spp=4 --set /render/seed=$seed -o ref-$seed.exr -q >/dev/null ||
        fail "render seed $seed"
    cmp "$frame" ref-$seed.exr || fail "batch frame $seed differs from nenrin render --set"
done
cmp -s frames/frame-0001-0001.exr frames/frame-0001-0002.exr && fail "seeds 1 and 2 gave one image"
echo "3-frame batch: every frame byte-identical to its nenrin render --set"
echo PASS
