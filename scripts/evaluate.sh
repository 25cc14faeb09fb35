#!/usr/bin/env bash
# The evaluation of docs/evaluation.md, refreshed with one command (not part of CI; on this
# project's 2-core machine about 3 hours at the defaults, most of it the references, which
# are cached in OUT and reused; the committed report used REF_SPP=2048 RUNS=1, the
# references rendered first with SPPS=" " RENDER_ONLY=1, about 2 hours). Renders a
# reference and noisy frames per scene with statmc-render, runs OIDN on them when pyoidn
# can be installed (an evaluation-only dependency, in a virtual environment under the
# build directory), scores every method (verified OIDN too) with statmc-evaluate, and
# redraws the charts and the report with scripts/plot_evaluation.py. The noisy frames'
# render times and the denoise times feed the equal-time charts: let nothing else run then.
#
#   bash scripts/evaluate.sh            # REF_SPP=4096 SPPS="4 16 64 256" SEEDS="1 2"
#   OUT=build/eval-quick REF_SPP=1024 SPPS="4 16" bash scripts/evaluate.sh   # a quick look
#   OIDN=0 bash scripts/evaluate.sh     # without the OIDN columns
#   RENDER_ONLY=1 bash scripts/evaluate.sh   # render and cache the frames, score later
#                                            # (so that timing runs on a quiet machine)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${BUILD:-build}
out=${OUT:-$build/evaluation}
ref_spp=${REF_SPP:-4096}
spps=${SPPS:-4 16 64 256}
seeds=${SEEDS:-1 2}
runs=${RUNS:-3}  # timed runs per method and input (the median is kept)
scenes_dir=${SCENES:-$root/../shared/scenes}
images=${IMAGES:-docs/images}
report=${REPORT:-docs/evaluation.md}

own_scenes=$root/bench/evaluation/scenes
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target statmc-render statmc statmc-evaluate
render=$build/renderer/statmc-render
evaluate=$build/bench/evaluation/statmc-evaluate
mkdir -p "$out"
csv=$out/results.csv
timing=$out/timing.csv
rm -f "$csv" "$timing"

# OIDN through pyoidn (PyPI) in a virtual environment that sees Debian's OpenImageIO and
# numpy. If it cannot be installed, the report says so and the OIDN columns are absent.
externals=()
if [ "${OIDN:-1}" = 1 ]; then
  venv=$build/oidn-venv
  if [ -x "$venv/bin/python" ] || { /usr/bin/python3 -m venv --system-site-packages "$venv" &&
       "$venv/bin/pip" install -q pyoidn; }; then
    externals=(--external oidn,oidn-guides)
  else
    echo "evaluate.sh: pyoidn could not be installed; OIDN is left out" >&2
  fi
fi

# scene:resolution:scene file. Every frame has at least as many pixels as 640×360 (Cornell:
# 512², square as its Tungsten reference is); caustic-corner is this project's own scene.
for entry in cornell-box:512x512:$scenes_dir/cornell-box/scene.pbrt \
             veach-mis:640x360:$scenes_dir/veach-mis/scene.pbrt \
             veach-ajar:640x360:$scenes_dir/veach-ajar/scene.pbrt \
             caustic-corner:640x360:$own_scenes/caustic-corner/scene.pbrt; do
  IFS=: read -r scene res file <<<"$entry"
  dir=$out/$scene
  mkdir -p "$dir"
  ref=$dir/reference-$ref_spp-$res.exr
  if [ ! -f "$ref" ]; then
    echo "== $scene: reference, $ref_spp spp at $res"
    # Into place only when complete: an interrupted render exits 130 with a partial file.
    "$render" "$file" -o "$ref.part.exr" --spp "$ref_spp" --resolution "$res" --seed 1000 -q
    mv "$ref.part.exr" "$ref"
  fi
  if [ -f "$scenes_dir/$scene/TungstenRender.exr" ]; then
    # Cross-check of our reference against Tungsten's, resampled to our resolution.
    oiiotool "$scenes_dir/$scene/TungstenRender.exr" --resize "$res" -d float -o "$dir/tungsten.exr"
    "$build/oiiotool_ext/statmc" "$ref" "$dir/tungsten.exr" --compare > "$dir/tungsten-check.txt" || true
  fi
  noisy=()
  for spp in $spps; do
    for seed in $seeds; do
      f=$dir/noisy-$res-$spp-$seed.exr
      if [ ! -f "$f" ]; then
        "$render" "$file" -o "$f.part.exr" --spp "$spp" --resolution "$res" --seed "$seed" -q
        mv "$f.part.exr" "$f"
      fi
      noisy+=("$f")
    done
  done
  [ "${RENDER_ONLY:-0}" = 1 ] && continue
  if [ ${#externals[@]} -gt 0 ]; then
    echo "== $scene: OIDN"
    "$venv/bin/python" bench/evaluation/oidn_denoise.py "${noisy[@]}"
  fi
  echo "== $scene: scoring"
  "$evaluate" --reference "$ref" --scene "$scene" --csv "$csv" --runs "$runs" "${externals[@]}" \
    "${noisy[@]}"
done

# Denoise time against resolution and radius (Cornell, 16 spp).
for res in 320x180 640x360 1280x720; do
  f=$out/timing-$res.exr
  [ -f "$f" ] || "$render" "$scenes_dir/cornell-box/scene.pbrt" -o "$f" --spp 16 --resolution "$res" --seed 7 -q
  [ "${RENDER_ONLY:-0}" = 1 ] && continue
  "$evaluate" --reference "$f" --scene cornell-box --csv "$timing" --runs "$runs" \
    --radius-sweep 2,5,10,20 "$f"
done

if [ "${RENDER_ONLY:-0}" = 1 ]; then
  echo "frames cached in $out; run again without RENDER_ONLY to score them"
  exit 0
fi
/usr/bin/python3 scripts/plot_evaluation.py "$csv" "$timing" --ref-spp "$ref_spp" --runs "$runs" \
  --tungsten "$out"/*/tungsten-check.txt --images "$images" --report "$report"
echo "$report and $images/eval-*.png updated from $csv"
