#!/usr/bin/env bash
# Builds statmc, renders the Cornell Box at 16 spp with statmc-render (statistics EXR with
# albedo/normal guides) and denoises it with statmc. Scores both against the Tungsten
# reference below the light (rows 72+: the reference's light border is filtered, ours
# box-sampled). Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=../shared/scenes/cornell-box
[ -f "$scene/scene.pbrt" ] || { echo "example: $scene/scene.pbrt not found (../shared must sit beside the checkout)" >&2; exit 1; }
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target statmc statmc-render
mkdir -p out
build/renderer/statmc-render "$scene/scene.pbrt" --resolution 512x512 --spp 16 --seed 1 --quiet -o out/cornell-16spp.exr
time build/oiiotool_ext/statmc out/cornell-16spp.exr --denoise:radius=20:alpha=0.005 -o out/cornell-denoised.exr
oiiotool "$scene/TungstenRender.exr" --resize 512x512 -o out/cornell-reference.exr
for image in cornell-16spp cornell-denoised; do
  echo "$image vs reference (below the light):"
  oiiotool out/$image.exr --ch R,G,B --cut 512x440+0+72 out/cornell-reference.exr --cut 512x440+0+72 --diff 2>/dev/null \
    | grep -E 'Mean error|RMS error' || true
done
echo "Wrote out/cornell-16spp.exr (statistics) and out/cornell-denoised.exr"
