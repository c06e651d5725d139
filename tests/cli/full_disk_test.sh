#!/usr/bin/env bash
# A full disk never leaves a damaged or partial output, and never a half of a command's outputs:
# each command is run on a small tmpfs filled up to leave 2, 8, 14, ... KB free, and after every
# run either it failed (exit 1) and left no file at all, or it succeeded and every output is
# byte-identical to the same command's output on a disk with room.
#
#   full_disk_test.sh NENRIN SOURCE_DIR
#
# Needs root to mount the tmpfs; exit 77 (skip) otherwise.
set -u
nenrin=$1
src=$2
if [[ $(id -u) -ne 0 ]]; then
    echo "SKIP: mounting a small tmpfs needs root"
    exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/nenrin-full.XXXXXX")
disk=$work/disk
mkdir "$disk" "$work/ref"
if ! mount -t tmpfs -o size=600k tmpfs "$disk"; then
    rm -rf "$work"
    echo "SKIP: cannot mount a tmpfs here"
    exit 77
fi
trap 'umount "$disk"; rm -rf "$work"' EXIT
fail() {
    echo "FAIL: $*" >&2
    exit 1
}

skeleton=$src/scenes/skeletons/conifer.json
box=--box=-0.1,-0.1,0.5,0.1,0.1,0.9
# name | KB left free | outputs | command (OUT stands for the output folder). OpenVDB spins for
# ~20 s on a write that fails part-way, so VDB runs at three sizes only: none, part, all fit.
steps=$(seq 2 6 134 | tr '\n' ' ')
jobs=(
    "render|$steps|a.exr a.png|render $src/tests/data/scenes/small-glulam.json --res 64x40 --spp 1 -q -o OUT/a.exr --png OUT/a.png"
    "slice|$steps|s.exr s.png|bake slice --skeleton $skeleton --res 96x96 -q -o OUT/s.exr --png OUT/s.png"
    "vdb|2 60 200|v.vdb|bake volume --skeleton $skeleton $box --res 24 -q -o OUT/v.vdb"
    "df3|$steps|d.R.df3 d.G.df3 d.B.df3 d.knot.df3 d.inc|bake volume --skeleton $skeleton $box --res 24 -q -o OUT/d.df3"
)
runs=0
for job in "${jobs[@]}"; do
    IFS='|' read -r name sizes outputs command <<<"$job"
    # shellcheck disable=SC2086
    $nenrin ${command//OUT/$work/ref} >/dev/null || fail "$name: the reference run failed"
    for free in $sizes; do
        rm -rf "${disk:?}"/* "$disk"/.[!.]* 2>/dev/null
        avail=$(df --output=avail -k "$disk" | tail -1)
        ((avail > free)) && dd if=/dev/zero of="$disk/fill" bs=1k count=$((avail - free)) 2>/dev/null
        # shellcheck disable=SC2086
        $nenrin ${command//OUT/$disk} >/dev/null 2>"$work/err"
        rc=$?
        runs=$((runs + 1))
        left=$(ls -A "$disk" | grep -vx fill)
        if ((rc != 0)); then
            ((rc == 1)) || fail "$name with ${free} KB free: exit $rc ($(cat "$work/err"))"
            [[ -z $left ]] || fail "$name with ${free} KB free: failed but left: $left"
            [[ $(wc -l <"$work/err") -eq 1 ]] || fail "$name: expected one error line: $(cat "$work/err")"
        else
            for f in $outputs; do
                cmp -s "$disk/$f" "$work/ref/$f" || fail "$name with ${free} KB free: exit 0 but $f is damaged or missing"
            done
        fi
    done
done
echo "PASS: $runs runs on a full disk, every one all-or-nothing"
