#!/usr/bin/env bash
# Blender Cycles end to end (docs/renderers.md): Blender renders K passes of a small scene
# (scripts/cycles_scene.py: multilayer EXRs with the denoising passes) and a reference;
# statmc turns the passes into statistics and denoises them with Denoising Albedo/Normal
# as guides; both are scored against the reference, and a before/after picture is made.
# The scene's two light groups are denoised jointly and checked to still add up.
# Usage: scripts/cycles-example.sh [OUT_DIR]   (default out/cycles; K=8 SPP=4 RES=320x240
#        REFERENCE=1024 PICTURE=path.png override). Needs Debian's blender: exit 77 (ctest's
#        skip) when it is not installed. Not part of CI: Blender is large.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/cycles}
K=${K:-8} SPP=${SPP:-4} RES=${RES:-320x240} REFERENCE=${REFERENCE:-1024}
statmc=${STATMC:-build/oiiotool_ext/statmc}
if ! command -v blender >/dev/null; then
  echo "cycles-example: blender is not installed (apt-get install blender): skipped" >&2
  exit 77
fi
[ -x "$statmc" ] || cmake --build build --target statmc
mkdir -p "$out"
rm -f "$out"/pass*.exr
rm -f "$out/reference.exr"
blender_status=0
blender -b --factory-startup --python scripts/cycles_scene.py -- --out "$out" --passes "$K" \
  --samples "$SPP" --resolution "$RES" --reference "$REFERENCE" >"$out/blender.log" 2>&1 ||
  blender_status=$?
# Blender now and then fails on its way out after writing everything; what counts is that
# every file is there.
passes_written=$(find "$out" -maxdepth 1 -name 'pass*.exr' | wc -l)
if [ "$passes_written" -ne "$K" ] || [ ! -f "$out/reference.exr" ]; then
  tail -20 "$out/blender.log" >&2
  echo "cycles-example: blender wrote $passes_written of $K passes (exit $blender_status)" >&2
  exit 1
fi
[ "$blender_status" -eq 0 ] ||
  echo "cycles-example: note: blender exited with $blender_status after writing every file" >&2

# The three commands of the README.
"$statmc" "$out"/pass*.exr --passes -o "$out/statistics.exr"
"$statmc" "$out/statistics.exr" --denoise -o "$out/denoised.exr"
"$statmc" "$out/reference.exr" --ch R=ViewLayer.Combined.R,G=ViewLayer.Combined.G,B=ViewLayer.Combined.B \
  -o "$out/reference-rgb.exr"

# Blender's light groups (Combined_key, Combined_fill) come in as the AOVs key and fill,
# carried by --passes as means; averaged with the beauty's members they still add up.
"$statmc" "$out/statistics.exr" --denoise:aovs=key,fill:joint=1 -o "$out/light-groups.exr"
echo "== key + fill against the denoised beauty"
lg="$out/light-groups.exr"
"$statmc" "$lg" --ch R=key.R,G=key.G,B=key.B "$lg" --ch R=fill.R,G=fill.G,B=fill.B --add \
  "$lg" --ch R,G,B --diff | tee "$out/light-groups-diff.txt" || true  # judged below

for image in statistics denoised; do
  echo "== $image ($((K * SPP)) spp) vs the ${REFERENCE}-spp reference"
  "$statmc" "$out/$image.exr" --ch R,G,B "$out/reference-rgb.exr" --compare | tee "$out/$image-scores.txt"
done
if [ -n "${PICTURE:-}" ]; then
  oiiotool "$out/statistics.exr" --ch R,G,B "$out/denoised.exr" --ch R,G,B \
    "$out/reference-rgb.exr" --mosaic 3x1 --colorconvert linear sRGB -d uint8 -o "$PICTURE"
  echo "Wrote $PICTURE (mean of the passes | statmc | reference)"
fi
