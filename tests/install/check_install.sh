#!/usr/bin/env bash
# ctest install.tree: `cmake --install` into a temporary prefix, then use only what it holds,
# as a user would: statmc-render renders, statmc denoises (its plugins and the display's
# OCIO config found from the prefix), statmc-farm validates a job with the installed
# programs, and `import statmc` works from the prefix's site-packages, also from a venv made
# with --system-site-packages; a venv without numpy says what to do.
# Usage: check_install.sh BUILD_DIR PYTHON
set -euo pipefail
build=${1:?usage: check_install.sh BUILD_DIR PYTHON}
python=${2:?usage: check_install.sh BUILD_DIR PYTHON}
here=$(cd "$(dirname "$0")" && pwd)
scene=$(cd "$here/../../.." && pwd)/shared/scenes/cornell-box/scene.pbrt
[[ -f "$scene" ]] || { echo "check_install: $scene not found (../shared must sit beside the checkout)" >&2; exit 1; }
prefix=$(mktemp -d -t statmc-install.XXXXXX)
trap 'rm -rf "$prefix"' EXIT
fail() { echo "check_install: FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix/usr" >"$prefix/install.log" ||
  { cat "$prefix/install.log" >&2; fail "cmake --install failed"; }
bin=$prefix/usr/bin
for program in statmc statmc-render statmc-farm; do
  [[ -x "$bin/$program" ]] || fail "$program is not installed in $bin"
done
[[ -f "$prefix/usr/share/statmc/blender/statmc_cycles_passes.py" ]] ||
  fail "the Blender script is not installed in $prefix/usr/share/statmc/blender"
for op in denoise passes merge compare display verify oidn; do
  [[ -f "$prefix/usr/lib/statmc/plugins/$op.so" ]] || fail "$op.so is not installed in $prefix/usr/lib/statmc/plugins"
done
ops=$("$bin/statmc" --list-ops)
for op in denoise passes merge compare display verify oidn; do
  grep -q -- "--$op" <<<"$ops" || fail "the installed statmc does not list --$op: $ops"
done

"$bin/statmc-render" "$scene" --resolution 48x48 --spp 8 --seed 1 -q -o "$prefix/frame.exr"
"$bin/statmc" "$prefix/frame.exr" --denoise -o "$prefix/denoised.exr"
"$bin/statmc" "$prefix/denoised.exr" --display -o "$prefix/display.exr"
[[ -s "$prefix/denoised.exr" && -s "$prefix/display.exr" ]] || fail "no denoised or display output"
# The farm finds the installed programs beside itself and validates with them.
"$bin/statmc-farm" submit "$scene" --tasks 2 --spp 8 -o "$prefix/farm.exr" --denoise \
  --dry-run >"$prefix/farm.log" || { cat "$prefix/farm.log" >&2; fail "statmc-farm --dry-run"; }
grep -q "'$bin/statmc-render'" "$prefix/farm.log" || fail "the farm job does not run $bin/statmc-render"

site=$(find "$prefix/usr/lib" -maxdepth 3 -type d -path '*/python3*/*-packages' -print -quit)
[[ -n "$site" && -f "$site/statmc/__init__.py" ]] || fail "no statmc package under $prefix/usr/lib"
check_import='import sys, statmc
image = statmc.denoise(sys.argv[1])
assert image["beauty"].shape == (48, 48, 3), image["beauty"].shape
print(statmc.__version__)'
# A sanitized build's module needs its runtimes preloaded into the interpreter.
preload=${STATMC_PYTHON_PRELOAD:-}
PYTHONPATH=$site LD_PRELOAD=$preload "$python" -c "$check_import" "$prefix/frame.exr" >/dev/null ||
  fail "import statmc from $site"
"$python" -m venv --system-site-packages "$prefix/venv"
PYTHONPATH=$site LD_PRELOAD=$preload "$prefix/venv/bin/python" -c "$check_import" \
  "$prefix/frame.exr" >/dev/null || fail "import statmc from a venv with --system-site-packages"
"$python" -m venv --without-pip "$prefix/bare"
if out=$(PYTHONPATH=$site LD_PRELOAD=$preload "$prefix/bare/bin/python" -c 'import statmc' 2>&1); then
  fail "a venv without numpy imported statmc"
fi
grep -q "statmc needs numpy" <<<"$out" || fail "a venv without numpy: $out"
echo "install.tree: statmc, statmc-render, statmc-farm and import statmc work from $prefix/usr"
