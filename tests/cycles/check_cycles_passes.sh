#!/usr/bin/env bash
# ctest cycles.passes: blender/statmc_cycles_passes.py on a tiny .blend saved as a user might
# leave it (Eevee, Blender's denoiser on, no Denoising Data, the animated seed on, PNG
# output). With --use-cycles it must render K=3 passes of 2 frames as multilayer EXRs with the
# Denoising Albedo/Normal layers and distinct pixels (a seed per frame and pass), leave the
# .blend untouched, refuse bad arguments with exit 1, and print statmc commands that run.
# Exit 77 (skipped, shown by ctest) without blender.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$here/../..
out=$1
statmc=${STATMC:-$root/build/oiiotool_ext/statmc}
if ! command -v blender >/dev/null; then
  echo "cycles.passes: blender is not installed (apt-get install blender): skipped" >&2
  exit 77
fi
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
blend=$out/user.blend passes=$out/passes

# The example scene at 32x24, saved with settings that statmc_cycles_passes.py must override.
blender -b --factory-startup -P "$root/scripts/cycles_scene.py" --python-expr "
import bpy
s = bpy.context.scene
s.cycles.use_denoising = True
s.cycles.use_animated_seed = True
s.view_layers[0].cycles.denoising_store_passes = False
s.render.image_settings.file_format = 'PNG'
s.render.engine = 'BLENDER_EEVEE'
bpy.ops.wm.save_as_mainfile(filepath='$blend')" -- --out "$out/unused" --passes 0 \
  --resolution 32x24 >"$out/make-blend.log" 2>&1 ||
  { tail "$out/make-blend.log"; fail "could not save $blend"; }
before=$(md5sum <"$blend")

run() { blender -b --factory-startup "$blend" -P "$root/blender/statmc_cycles_passes.py" -- "$@"; }
expect_error() {  # arguments..., then the message expected
  local message=${*: -1} status=0
  run "${@:1:$#-1}" >"$out/error.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] && grep -q "statmc_cycles_passes: error: .*$message" "$out/error.log" ||
    { tail -3 "$out/error.log"; fail "'${*:1:$#-1}' gave exit $status, not 1 with '$message'"; }
}
expect_error 1 "$passes" "K must be 2 to 999"
expect_error 3 "$passes" "not Cycles"
expect_error 3 "$blend/dir" "cannot write into OUT_DIR"

# Blender now and then fails on its way out after the script has finished: what counts is
# that the script got to its last lines.
status=0
run 3 "$passes" --frames 1-2 --samples 4 --use-cycles >"$out/blender.log" 2>&1 || status=$?
grep -q "^Next, denoise with statmc:" "$out/blender.log" ||
  { tail -20 "$out/blender.log"; fail "statmc_cycles_passes.py failed (exit $status)"; }
[ "$status" -eq 0 ] || echo "cycles.passes: note: blender exited with $status after the script" >&2
[ "$(md5sum <"$blend")" = "$before" ] || fail "the .blend was changed"
for f in 0001 0002; do
  for k in 000 001 002; do
    file=$passes/pass$k-$f.exr
    [ -f "$file" ] || fail "$file is missing"
    "$statmc" --info -v "$file" >"$out/info.txt"
    for channel in Combined.R "Denoising Albedo.R" "Denoising Normal.X"; do
      grep -q "ViewLayer.$channel" "$out/info.txt" || fail "$file has no channel ViewLayer.$channel"
    done
  done
done
# Distinct seeds: no two passes, of one frame or of two, hold the same pixels.
rgb=R=ViewLayer.Combined.R,G=ViewLayer.Combined.G,B=ViewLayer.Combined.B
for pair in "pass000-0001 pass001-0001" "pass001-0001 pass002-0001" "pass000-0001 pass000-0002"; do
  set -- $pair
  "$statmc" "$passes/$1.exr" --ch "$rgb" "$passes/$2.exr" --ch "$rgb" --diff >"$out/diff.txt" 2>&1 ||
    true  # exit 1 when they differ, as wanted: the report says which
  grep -q FAILURE "$out/diff.txt" || { cat "$out/diff.txt"; fail "$1 and $2 hold the same pixels"; }
done
# The statmc commands the script printed, as printed (statmc from this build).
grep -q "^  statmc .*/pass002-#.exr --frames 1-2 --passes --denoise" "$out/blender.log" ||
  fail "no statmc command printed"
grep "^  statmc " "$out/blender.log" | while read -r _ rest; do
  eval "\"$statmc\" $rest" || fail "statmc $rest"
done
"$statmc" --info -v "$passes/denoised-0001.exr" | grep -q "albedo.R" ||
  fail "the Denoising Albedo pass did not reach the statistics as the albedo guide"
echo "cycles.passes: 2 frames x 3 passes, distinct, with guides; statmc --passes --denoise ran"
