#!/usr/bin/env bash
# statmc-farm on a real Slurm: a single-node cluster on localhost (local_slurm.sh) runs
#  1. a 4-task render of the Cornell Box, merged by its merge job: bitwise equal to
#     statmc-render --tasks 4 run here;
#  2. the same with one render task SIGKILLed mid-render: the task is requeued, resumes
#     from its checkpoint (its log says so) and the merge is still bitwise equal;
#  3. a 3-frame sequence with denoising.
# Usage: test_slurm_farm.sh BUILD_DIR. Needs root and the slurm-wlm/munge packages; fails
# (never skips) when the cluster cannot start. Debian's python3 (numpy, OpenImageIO) compares images.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?usage: test_slurm_farm.sh BUILD_DIR}" && pwd)
render=$build/renderer/statmc-render
farm=$build/farm/statmc-farm
scene=$(cd "$here/../../.." && pwd)/shared/scenes/cornell-box/scene.pbrt
[[ -f "$scene" ]] || { echo "test_slurm_farm: $scene not found (../shared must sit beside the checkout)" >&2; exit 1; }
[[ $(id -u) -eq 0 ]] || { echo "test_slurm_farm: must run as root (slurmd starts jobs as their owner)" >&2; exit 1; }

work=$(mktemp -d -t statmc-slurm-test.XXXXXX)
source "$here/local_slurm.sh"
finish()
{
    local status=$?
    if [[ $status -ne 0 ]]; then
        echo "test_slurm_farm: FAILED; job logs:" >&2
        for log in "$work"/*/statmc-farm/logs/*.log; do
            [[ -f "$log" ]] && { echo "--- $log" >&2; tail -n 15 "$log" >&2; }
        done
    fi
    stop_local_slurm
    rm -rf "$work"
    exit $status
}
trap finish EXIT
start_local_slurm "$work/slurm"

fail() { echo "test_slurm_farm: $*" >&2; exit 1; }

# Waits until every frame of the job in $1 is merged (statmc-farm status exits 0), at most $2 s.
wait_merged()
{
    local dir=$1 limit=$2 start=$SECONDS status
    while true; do
        status=0
        "$farm" status --job-dir "$dir" >"$work/status.txt" 2>&1 || status=$?
        [[ $status -eq 0 ]] && break
        [[ $status -eq 3 ]] || { cat "$work/status.txt" >&2; fail "the job failed (status $status)"; }
        (( SECONDS - start < limit )) || { cat "$work/status.txt" >&2; squeue >&2; fail "not merged within $limit s"; }
        sleep 1
    done
    cat "$work/status.txt"
}

# Every pixel and channel name of two EXRs equal, bit for bit.
same_bits()
{
    /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, numpy as np, OpenImageIO as oiio
a, b = (oiio.ImageBuf(p) for p in sys.argv[1:3])
if a.spec().channelnames != b.spec().channelnames:
    sys.exit(f"channels differ: {a.spec().channelnames} vs {b.spec().channelnames}")
pa, pb = (np.ascontiguousarray(x.get_pixels(oiio.FLOAT)) for x in (a, b))
if pa.shape != pb.shape or not np.array_equal(pa.view(np.uint32), pb.view(np.uint32)):
    sys.exit(f"pixels differ in {np.count_nonzero(pa.view(np.uint32) != pb.view(np.uint32))} values")
PY
}

common=(--render-args=--resolution --render-args=64x64)

echo "== 1. four tasks, merged on the cluster, equal to --tasks 4 here"
mkdir -p "$work/one"
t0=$SECONDS
"$farm" submit "$scene" --tasks 4 --spp 64 -o "$work/one/frame.exr" --checkpoint 5 "${common[@]}"
wait_merged "$work/one/statmc-farm" 120
echo "farm wall time: $((SECONDS - t0)) s"
t0=$SECONDS
"$render" "$scene" --resolution 64x64 --spp 64 --tasks 4 -q -o "$work/one/local.exr"
echo "local --tasks 4 wall time: $((SECONDS - t0)) s"
same_bits "$work/one/frame.exr" "$work/one/local.exr" || fail "the farm's merge differs from --tasks 4"

echo "== 2. one render task SIGKILLed mid-render: requeued, resumed, still equal"
mkdir -p "$work/two"
"$farm" submit "$scene" --tasks 4 --spp 2048 -o "$work/two/frame.exr" --checkpoint 0.5 "${common[@]}"
checkpoint=$work/two/frame.task1.exr.checkpoint
start=$SECONDS
until [[ -f "$checkpoint" ]]; do
    (( SECONDS - start < 60 )) || fail "task 1 wrote no checkpoint within 60 s"
    sleep 0.1
done
sleep 0.3
pkill -KILL -f -- "-o $work/two/frame.task1.exr --task 1/4" || fail "no render of task 1 to kill"
echo "killed task 1 at $(date -Is)"
wait_merged "$work/two/statmc-farm" 240
log=$work/two/statmc-farm/logs/render-1.log
grep -q "requeueing it to resume" "$log" || fail "task 1 was not requeued: $(cat "$log")"
grep -q "resuming from checkpoint" "$log" || fail "task 1 did not resume from its checkpoint: $(cat "$log")"
grep "resuming from checkpoint" "$log"
"$render" "$scene" --resolution 64x64 --spp 2048 --tasks 4 -q -o "$work/two/local.exr"
same_bits "$work/two/frame.exr" "$work/two/local.exr" || fail "the resumed farm render differs from --tasks 4"

echo "== 3. a three-frame sequence, denoised"
mkdir -p "$work/three"
for f in 1 2 3; do
    printf 'Include "%s"\n' "$scene" >"$work/three/shot.$(printf %04d $f).pbrt"
done
"$farm" submit "$work/three/shot.%04d.pbrt" --frames 1-3 --tasks 2 --spp 16 --denoise method=classic \
    -o "$work/three/shot.%04d.exr" "${common[@]}"
wait_merged "$work/three/statmc-farm" 120
for f in 0001 0002 0003; do
    [[ -f "$work/three/shot.$f.exr" && -f "$work/three/shot.$f.denoised.exr" ]] || fail "frame $f missing"
    spp=$(/usr/bin/python3 -c "import sys, OpenImageIO as o; print(o.ImageBuf(sys.argv[1]).spec().getattribute('statmc:spp'))" "$work/three/shot.$f.exr")
    [[ "$spp" == 16 ]] || fail "frame $f has statmc:spp $spp, not 16"
done
echo "test_slurm_farm: all passed"
