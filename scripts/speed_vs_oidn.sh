#!/usr/bin/env bash
# statmc against Intel Open Image Denoise (CPU device) on the same frames, in one run (not
# part of CI; a few minutes). Renders the Cornell box at 1280×720 and 1920×1080 (16 spp) with
# statmc-render, times statmc's whole denoise operator in memory (bench_denoise's
# BM_DenoiseOperator on that frame, all cores, median of 5) and OIDN's CPU filter through
# pyoidn (PyPI, in a virtual environment under the build directory; median of 5, colour
# only and colour + albedo + normal), and prints the table docs/performance.md (and README.md's summary) quotes.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD:-build}
out=${OUT:-$build/speed-vs-oidn}
scene=${SCENE:-$PWD/../shared/scenes/cornell-box/scene.pbrt}
cmake --build "$build" --target statmc-render bench_denoise
venv=$build/oidn-venv
[ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import pyoidn" 2>/dev/null || {
  /usr/bin/python3 -m venv --system-site-packages "$venv" && "$venv/bin/pip" install -q pyoidn; }
mkdir -p "$out"
for res in 1280x720 1920x1080; do
  frame=$out/cornell-$res.exr
  [ -f "$frame" ] || "$build/renderer/statmc-render" "$scene" --spp 16 --resolution "$res" -q \
    -o "$frame"
  STATMC_BENCH_FRAME=$frame "$build/bench/bench_denoise" --benchmark_filter='BM_DenoiseOperator/0/' \
    --benchmark_format=json > "$out/statmc-$res.json"
  "$venv/bin/python" scripts/speed_vs_oidn.py time "$frame" > "$out/oidn-$res.json"
done
/usr/bin/python3 scripts/speed_vs_oidn.py table "$out"
