#!/usr/bin/env bash
# The evaluation of docs/evaluation.md, refreshed with one command (about 10 minutes on
# this project's 2-core machine; not part of CI). Renders a reference and noisy frames per scene with
# statmc-render, scores every method with statmc-evaluate, and redraws the charts and the
# report with scripts/plot_evaluation.py.
#
#   bash scripts/evaluate.sh            # REF_SPP=4096 SPPS="4 16 64 256" SEEDS="1 2"
#   OUT=build/eval-quick REF_SPP=1024 SPPS="4 16" bash scripts/evaluate.sh   # a quick look
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${BUILD:-build}
out=${OUT:-$build/evaluation}
ref_spp=${REF_SPP:-4096}
spps=${SPPS:-4 16 64 256}
seeds=${SEEDS:-1 2}
scenes_dir=${SCENES:-$root/../shared/scenes}
images=${IMAGES:-docs/images}
report=${REPORT:-docs/evaluation.md}

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target statmc-render statmc statmc-evaluate
render=$build/renderer/statmc-render
evaluate=$build/bench/evaluation/statmc-evaluate
mkdir -p "$out"
csv=$out/results.csv
timing=$out/timing.csv
rm -f "$csv" "$timing"

# scene, resolution: Cornell is square (its Tungsten reference is 1024²); the others 16:9.
for entry in cornell-box:256x256 veach-mis:320x180 veach-ajar:320x180; do
  scene=${entry%%:*} res=${entry#*:}
  dir=$out/$scene
  mkdir -p "$dir"
  ref=$dir/reference-$ref_spp.exr
  if [ ! -f "$ref" ]; then
    echo "== $scene: reference, $ref_spp spp at $res"
    "$render" "$scenes_dir/$scene/scene.pbrt" -o "$ref" --spp "$ref_spp" --resolution "$res" --seed 1000 -q
  fi
  if [ -f "$scenes_dir/$scene/TungstenRender.exr" ]; then
    # Cross-check of our reference against Tungsten's, resampled to our resolution.
    oiiotool "$scenes_dir/$scene/TungstenRender.exr" --resize "$res" -d float -o "$dir/tungsten.exr"
    "$build/oiiotool_ext/statmc" "$ref" "$dir/tungsten.exr" --compare > "$dir/tungsten-check.txt" || true
  fi
  noisy=()
  for spp in $spps; do
    for seed in $seeds; do
      f=$dir/noisy-$spp-$seed.exr
      "$render" "$scenes_dir/$scene/scene.pbrt" -o "$f" --spp "$spp" --resolution "$res" --seed "$seed" -q
      noisy+=("$f")
    done
  done
  echo "== $scene: scoring"
  "$evaluate" --reference "$ref" --scene "$scene" --csv "$csv" "${noisy[@]}"
done

# Denoise time against resolution and radius (Cornell, 16 spp).
for res in 320x180 640x360 1280x720; do
  f=$out/timing-$res.exr
  "$render" "$scenes_dir/cornell-box/scene.pbrt" -o "$f" --spp 16 --resolution "$res" --seed 7 -q
  "$evaluate" --reference "$f" --scene cornell-box --csv "$timing" --radius-sweep 2,5,10,20 "$f"
done

/usr/bin/python3 scripts/plot_evaluation.py "$csv" "$timing" --ref-spp "$ref_spp" \
  --tungsten "$out"/*/tungsten-check.txt --images "$images" --report "$report"
echo "$report and $images/eval-*.png updated from $csv"
