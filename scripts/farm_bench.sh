#!/usr/bin/env bash
# The farm's costs, measured (docs/farm.md, "Measured"): samples/s of a 640x360 render with
# and without a checkpoint every 10 s; a 4-task statmc-farm render on a single-node Slurm on
# localhost against one local render; and the time a SIGKILLed task loses. Root, and the
# Slurm packages of scripts/install-test-deps.sh. Usage: scripts/farm_bench.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(cd "${1:-build}" && pwd)
render=$build/renderer/statmc-render
farm=$build/farm/statmc-farm
scene=$(cd .. && pwd)/shared/scenes/cornell-box/scene.pbrt
work=$(mktemp -d -t statmc-farm-bench.XXXXXX)
source tests/farm/local_slurm.sh
trap 'stop_local_slurm; rm -rf "$work"' EXIT

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
# Waits for the job in $1 to be merged; fails when it failed or took over 20 minutes.
wait_merged()
{
    local status start=$SECONDS
    while true; do
        status=0
        "$farm" status --job-dir "$1" >"$work/status.txt" 2>&1 || status=$?
        [[ $status -eq 0 ]] && return 0
        [[ $status -eq 3 && $((SECONDS - start)) -lt 1200 ]] || { cat "$work/status.txt" >&2; exit 1; }
        sleep 0.2
    done
}

echo "== checkpoint overhead: 640x360, 256 spp, 2 threads (Msamples/s of 3 runs each, interleaved)"
for run in 1 2 3; do
    for mode in none every-10s; do
        extra=(); [[ $mode == every-10s ]] && extra=(--checkpoint 10)
        "$render" "$scene" --resolution 640x360 --spp 256 --threads 2 "${extra[@]}" -o "$work/c.exr" 2>"$work/c.log"
        echo "$mode: $(sed -n 's/.* \([0-9.]*\) Msamples\/s/\1/p' "$work/c.log") Msamples/s"
    done
done

start_local_slurm "$work/slurm"
echo "== 4-task farm render vs one local render: 640x360, 256 spp, 2 cores"
t0=$(now)
"$render" "$scene" --resolution 640x360 --spp 256 -q -o "$work/local.exr"
echo "local render: $(since "$t0") s"
t0=$(now)
"$farm" submit "$scene" --tasks 4 --spp 256 -o "$work/farm.exr" --cpus-per-task 1 \
    --render-args=--resolution --render-args=640x360 >/dev/null
wait_merged "$work/statmc-farm"
echo "farm, submit to merged (tasks on 1 CPU each, 2 at a time): $(since "$t0") s"

echo "== time lost to a killed task: 320x180, 2 tasks of 512 spp, checkpoint every 5 s, SIGKILL 7 s after the first"
mkdir -p "$work/k"
args=(--tasks 2 --spp 1024 --checkpoint 5 --cpus-per-task 1 --render-args=--resolution --render-args=320x180)
t0=$(now)
"$farm" submit "$scene" "${args[@]}" -o "$work/k/again.exr" --job-dir "$work/k/again" >/dev/null
wait_merged "$work/k/again"
echo "not killed, submit to merged: $(since "$t0") s"
t0=$(now)
"$farm" submit "$scene" "${args[@]}" -o "$work/k/frame.exr" >/dev/null
until [[ -f "$work/k/frame.task1.exr.checkpoint" ]]; do sleep 0.1; done
sleep 7
pkill -KILL -f -- "-o $work/k/frame.task1.exr --task 1/2"
echo "killed at $(since "$t0") s"
wait_merged "$work/k/statmc-farm"
echo "killed once, submit to merged: $(since "$t0") s"
grep -h "resuming\|attempt\|requeue" "$work/k/statmc-farm/logs/render-1.log"
