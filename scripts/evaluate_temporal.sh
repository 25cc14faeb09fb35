#!/usr/bin/env bash
# The temporal evaluation of docs/evaluation-temporal.md (not part of CI; about 15 minutes
# on this project's 2-core machine at the defaults, most of it the pan's per-frame
# references, which are cached in OUT and reused). Two sequences made from the shared
# Cornell box (scripts/temporal_scenes.py): a static camera with independent seeds per frame,
# and a slow orbit of the camera with the motion layer. Each is denoised per frame and
# with temporal=1 and 2 by the statmc tool over the frame pattern, and scored by
# scripts/temporal_metrics.py, which also draws the charts.
#
#   bash scripts/evaluate_temporal.sh
#   OUT=build/temporal-quick FRAMES=8 PAN_REF_SPP=256 bash scripts/evaluate_temporal.sh
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${BUILD:-build}
out=${OUT:-$build/evaluation-temporal}
res=${RES:-160}
frames=${FRAMES:-24}
spps=${SPPS:-4 16 64}
pan_spp=${PAN_SPP:-16}
ref_spp=${REF_SPP:-4096}
pan_ref_spp=${PAN_REF_SPP:-1024}
scene=${SCENE:-$root/../shared/scenes/cornell-box/scene.pbrt}

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target statmc-render statmc
render="$build/renderer/statmc-render"
tool="$build/oiiotool_ext/statmc"
mkdir -p "$out"
/usr/bin/python3 scripts/temporal_scenes.py "$scene" "$out"

# Renders FRAMES frames of SCENE at SPP into DIR/f.####.exr unless they are there.
render_sequence() {  # scene spp dir seed
  if [ ! -f "$3/f.$(printf %04d "$frames").exr" ]; then
    mkdir -p "$3"
    "$render" "$1" --frames "1-$frames" --fps 24 --spp "$2" --seed "$4" \
      --resolution "${res}x${res}" --threads 2 -q -o "$3/f.#.exr"
  fi
}

# OIDN (docs/method.md §15) where its library is found (STATMC_OIDN_LIBRARY, or pyoidn beside
# Python); without it the OIDN rows are left out, and the report says only what ran.
oidn=""
oidn_found() {  # a frame to try it on
  if [ -z "$oidn" ]; then
    if "$tool" "$1" --oidn -o "$out/oidn-probe.exr" >/dev/null 2>&1; then
      oidn=1
      rm -f "$out/oidn-probe.exr"
    else
      oidn=0
      echo "evaluate_temporal.sh: the OIDN library was not found: no OIDN rows" >&2
    fi
  fi
  [ "$oidn" = 1 ]
}

# Times one command over the sequence into DIR/timing.csv as LABEL, per frame.
timed() {  # dir label commands...
  local dir=$1 label=$2 start end
  shift 2
  start=$(date +%s.%N)
  "$tool" "$dir/f.#.exr" --frames "1-$frames" "$@"
  end=$(date +%s.%N)
  echo "$label,$(echo "($end - $start) / $frames" | bc -l)" >> "$dir/timing.csv"
}

# Denoises DIR/f.#.exr per frame (K = 0) and with temporal=K, and with OIDN and verified
# OIDN per frame; the wall time per frame (reading and writing included) goes to
# DIR/timing.csv.
denoise_sequence() {  # dir [extra denoise parameters]
  local dir=$1 extra=${2:-}
  echo "k,seconds_per_frame" > "$dir/timing.csv"
  for k in 0 1 2; do
    timed "$dir" "$k" "--denoise:temporal=$k$extra" -o "$dir/d$k.#.exr"
  done
  if oidn_found "$dir/f.0001.exr"; then
    timed "$dir" oidn --oidn -o "$dir/oidn.#.exr"
    timed "$dir" verified --dup --oidn --verify -o "$dir/verified.#.exr"
  fi
}

[ -f "$out/static-ref.exr" ] || "$render" "$out/static.pbrt" --spp "$ref_spp" --seed 1000 \
  --resolution "${res}x${res}" --threads 2 -q -o "$out/static-ref.exr"
for spp in $spps; do
  render_sequence "$out/static.pbrt" "$spp" "$out/static-$spp" 1
  denoise_sequence "$out/static-$spp"
done

render_sequence "$out/pan.pbrt" "$pan_ref_spp" "$out/pan-ref" 1000
render_sequence "$out/pan.pbrt" "$pan_spp" "$out/pan-$pan_spp" 1
denoise_sequence "$out/pan-$pan_spp"
# The same pan without its motion layer: temporal denoising then assumes a static camera.
mkdir -p "$out/pan-$pan_spp-nomotion"
/usr/bin/python3 scripts/temporal_scenes.py --strip-motion "$out/pan-$pan_spp" \
  "$out/pan-$pan_spp-nomotion" "$frames"
denoise_sequence "$out/pan-$pan_spp-nomotion"

/usr/bin/python3 scripts/temporal_metrics.py --out "$out" --frames "$frames" --spps "$spps" \
  --pan-spp "$pan_spp" --res "$res" --ref-spp "$ref_spp" --pan-ref-spp "$pan_ref_spp" \
  --report docs/evaluation-temporal.md --images docs/images
