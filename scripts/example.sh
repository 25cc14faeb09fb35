#!/usr/bin/env bash
# Builds statmc and denoises the bundled example: the statistics of a simulated 16-spp
# render of the Cornell Box (samples drawn around the Tungsten reference), so the result
# can be scored against the reference. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
shared=../shared/scenes/cornell-box
[ -f "$shared/TungstenRender.exr" ] || { echo "example: $shared/TungstenRender.exr not found (../shared must sit beside the checkout)" >&2; exit 1; }
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target statmc statmc-simulate
mkdir -p out
build/bench/statmc-simulate "$shared/TungstenRender.exr" --resolution 512x512 --spp 16 --seed 1 -o out/cornell-16spp.exr
time build/oiiotool_ext/statmc out/cornell-16spp.exr --denoise:radius=20:alpha=0.005 -o out/cornell-denoised.exr
oiiotool "$shared/TungstenRender.exr" --resize 512x512 -o out/cornell-reference.exr
for image in cornell-16spp cornell-denoised; do
  printf '%-18s' "$image:"
  oiiotool out/$image.exr --ch R,G,B out/cornell-reference.exr --diff 2>/dev/null | grep -E 'RMS error' || true
done
echo "Wrote out/cornell-16spp.exr (noisy statistics) and out/cornell-denoised.exr"
