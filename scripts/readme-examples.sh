#!/usr/bin/env bash
# Runs every command of README.md's "Using it" block and "Studio workflows" section on
# generated files, so the examples stay true. The "Using it" block is read from the README
# itself; --oidn needs OIDN's library ($STATMC_OIDN_LIBRARY, or the one
# scripts/install-test-deps.sh installs), and fails loudly without it. The inputs are made with oiiotool: eight "renders" of one frame (a
# gradient plus Gaussian noise of a different seed each, with albedo and normal layers)
# and the noise-free gradient as the reference. Work happens in out/readme-examples/.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target statmc >/dev/null
export PATH="$PWD/build/oiiotool_ext:$PATH"
mkdir -p out/readme-examples
cd out/readme-examples

gradient="fill:top=0.1,0.1,0.1:bottom=0.9,0.8,0.7"
for k in 1 2 3 4 5 6 7 8; do
  oiiotool --pattern "$gradient" 64x48 3 --pattern noise:type=gaussian:mean=0:stddev=0.15:seed=$k 64x48 3 --add \
           --chnames R,G,B \
           --pattern fill:left=0.2,0.2,0.2:right=0.8,0.7,0.6 64x48 3 --chnames albedo.R,albedo.G,albedo.B --chappend \
           --pattern constant:color=0,0,1 64x48 3 --chnames normal.X,normal.Y,normal.Z --chappend \
           -d float -o render$k.exr
done
oiiotool --pattern "$gradient" 64x48 3 -d float -o reference.exr
statmc render5.exr render6.exr render7.exr render8.exr --passes -o frameB.exr
statmc render1.exr render2.exr --passes -o task1.exr
statmc render3.exr render4.exr --passes -o task2.exr
for f in 1 2 3 4; do  # a four-frame "sequence" of a static shot, two renders per frame
  statmc render$((2 * f - 1)).exr render$((2 * f)).exr --passes -o "shot.000$f.exr"
done

run() { echo "+ $*"; "$@"; }

# K passes from another renderer
run statmc render1.exr render2.exr render3.exr render4.exr --passes -o frame.exr
run statmc render1.exr render2.exr render3.exr render4.exr --passes --denoise -o frame-denoised.exr
# Denoise a beauty with its guides
run statmc frame.exr --denoise:guides=albedo,normal -o frame-denoised.exr
run statmc frame.exr --denoise:diagnostics=1 -o frame-diagnostics.exr
# AOVs renamed into the contract, denoised separately, recombined
run statmc frame.exr --ch R,G,B,variance.R,variance.G,variance.B,diffuse.R=R,diffuse.G=G,diffuse.B=B,diffuse.variance.R=variance.R,diffuse.variance.G=variance.G,diffuse.variance.B=variance.B,sampleCount.Y \
       frameB.exr --ch specular.R=R,specular.G=G,specular.B=B,specular.variance.R=variance.R,specular.variance.G=variance.G,specular.variance.B=variance.B \
       --chappend -o aovs.exr
run statmc aovs.exr --denoise:aov=diffuse --denoise:aov=specular -o aovs-denoised.exr
run statmc aovs.exr --denoise:aovs=diffuse,specular:joint=1 -o aovs-joint.exr
run statmc aovs-denoised.exr --ch R=diffuse.R,G=diffuse.G,B=diffuse.B \
       aovs-denoised.exr --ch R=specular.R,G=specular.G,B=specular.B --add -o beauty-denoised.exr
run statmc frame.exr --denoise -o:keep=means frame-comp.exr
# Merge farm tasks
run statmc task1.exr task2.exr --merge -o merged.exr
run statmc merged.exr frame.exr --diff
run statmc merged.exr --denoise -o merged-denoised.exr
# Frame sequences, denoised with their neighbours
run statmc shot.#.exr --frames 1-4 --denoise:temporal=2 -o shot-denoised.#.exr
run statmc shot.%04d.exr --denoise -o shot-per-frame.%04d.exr
# Compare against a reference and view the error
run statmc frame-denoised.exr reference.exr --compare -o error.exr
run statmc frame-denoised.exr reference.exr --compare --mulc 10 --display -o error-view.exr
run statmc --stats error.exr
# The README's "Using it" block, line by line as written, on files named as it names them.
statmc frame.exr aovs.exr --ch diffuse.R,diffuse.G,diffuse.B,diffuse.variance.R,diffuse.variance.G,diffuse.variance.B,specular.R,specular.G,specular.B,specular.variance.R,specular.variance.G,specular.variance.B \
       --chappend -o in.exr
for k in 1 2 3 4; do cp render$k.exr "$(printf '\x'$(printf %x $((96 + k))))".exr; done  # a.exr … d.exr
for f in $(seq 5 48); do cp "shot.000$(( (f - 1) % 4 + 1 )).exr" "$(printf 'shot.%04d.exr' "$f")"; done
if [ -z "${STATMC_OIDN_LIBRARY:-}" ]; then
  STATMC_OIDN_LIBRARY=$(ls /opt/statmc-oidn/lib/python3*/site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2 2>/dev/null || true)
  export STATMC_OIDN_LIBRARY
fi
block=$(awk '/^## Using it/ {on = 1} on && /^```sh/ {inside = 1; next} inside && /^```/ {exit} inside' ../../README.md)
[ -n "$block" ] || { echo "readme-examples: no \"Using it\" block in README.md" >&2; exit 1; }
while IFS= read -r line; do
  command=${line%%  #*}  # the comment, not a frame pattern's #
  [ -n "${command// }" ] || continue
  echo "+ $command"
  eval "$command" >/dev/null
done <<<"$block"
echo "readme-examples: every command ran"
