#!/usr/bin/env bash
# The farm's costs, measured (docs/farm.md, "Measured"): samples/s of a 640x360 render with
# and without a checkpoint every 10 s; a 4-task statmc-farm render on a single-node Slurm on
# localhost against one local render; and the time a SIGKILLed task loses. Root, and the
# Slurm packages of scripts/install-deps.sh. Usage: scripts/farm_bench.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(cd "${1:-build}" && pwd)
render=$build/renderer/statmc-render
farm=$build/farm/statmc-farm
scene=$(cd .. && pwd)/shared/scenes/cornell-box/scene.pbrt
work=$(mktemp -d /tmp/statmc-farm-bench.XXXXXX)
source tests/farm/local_slurm.sh
trap 'stop_local_slurm; rm -rf "$work"' EXIT

rate() { sed -n 's/.* \([0-9.]*\) Msamples\/s/\1/p' "$1"; }
echo "== checkpoint overhead: 640x360, 256 spp, 2 threads (median of 3)"
for mode in none every-10s; do
    for run in 1 2 3; do
        extra=(); [[ $mode == every-10s ]] && extra=(--checkpoint 10)
        "$render" "$scene" --resolution 640x360 --spp 256 --threads 2 "${extra[@]}" -o "$work/c.exr" 2>"$work/c.log"
        rate "$work/c.log"
    done | sort -n | sed -n 2p | sed "s/^/$mode: Msamples\/s (median) /"
done

start_local_slurm "$work/slurm"
echo "== 4-task farm render vs one local render: 640x360, 256 spp"
t0=$(date +%s.%N)
"$render" "$scene" --resolution 640x360 --spp 256 -q -o "$work/local.exr"
echo "local render: $(echo "$(date +%s.%N) - $t0" | bc) s"
t0=$(date +%s.%N)
"$farm" submit "$scene" --tasks 4 --spp 256 -o "$work/farm.exr" --render-args=--resolution --render-args=640x360 >/dev/null
until "$farm" status --job-dir "$work/statmc-farm" >/dev/null 2>&1; do sleep 0.2; done
echo "farm (submit to merged): $(echo "$(date +%s.%N) - $t0" | bc) s"

echo "== time lost to a killed task: checkpoint every 5 s, SIGKILL 7 s after the first one"
mkdir -p "$work/k"
t0=$(date +%s.%N)
"$farm" submit "$scene" --tasks 2 --spp 1024 --checkpoint 5 -o "$work/k/frame.exr" \
    --render-args=--resolution --render-args=320x180 --render-args=--threads --render-args=1 >/dev/null
until [[ -f "$work/k/frame.task1.exr.checkpoint" ]]; do sleep 0.1; done
sleep 7
pkill -KILL -f -- "-o $work/k/frame.task1.exr --task 1/2"
until "$farm" status --job-dir "$work/k/statmc-farm" >/dev/null 2>&1; do sleep 0.2; done
echo "killed farm (submit to merged): $(echo "$(date +%s.%N) - $t0" | bc) s"
grep -h "resuming\|attempt" "$work/k/statmc-farm/logs/render-1.log"
t0=$(date +%s.%N)
"$farm" submit "$scene" --tasks 2 --spp 1024 --checkpoint 5 -o "$work/k/again.exr" --job-dir "$work/k/again" \
    --render-args=--resolution --render-args=320x180 --render-args=--threads --render-args=1 >/dev/null
until "$farm" status --job-dir "$work/k/again" >/dev/null 2>&1; do sleep 0.2; done
echo "same job unkilled (submit to merged): $(echo "$(date +%s.%N) - $t0" | bc) s"
