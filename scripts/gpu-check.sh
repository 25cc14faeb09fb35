#!/usr/bin/env bash
# The GPU checks of docs/gpu.md, as one prepared run on a machine with an NVIDIA GPU (this
# project's lent H200 machine has nvcc, CMake and ninja but none of core's libraries, and
# reaches no package registry). Two steps:
#
#   bash scripts/gpu-check.sh --fetch-deps   # here: Debian's TBB, Boost, GoogleTest and
#                                            # Google Benchmark packages into .device-debs/
#   bash scripts/gpu-check.sh                # there, with .device-debs carried along
#
# The second unpacks the packages into a temporary folder, configures core alone
# (STATMC_CORE_ONLY, CUDA on) with every core, builds test_core, test_cuda and bench_cuda,
# runs the CUDA tests, core's CPU tests and the GPU benchmark, and writes the logs and
# results.txt to $OUT (or build-gpu/out). It stops itself well inside 10 minutes
# (TIME_LIMIT, seconds).
set -uo pipefail
cd "$(dirname "$0")/.."
debs=.device-debs

if [ "${1:-}" = --fetch-deps ]; then
  mkdir -p "$debs"
  grep -qx "/$debs/" .git/info/exclude 2>/dev/null || echo "/$debs/" >> .git/info/exclude
  (cd "$debs" && apt-get download libtbb-dev libtbb12 libtbbmalloc2 libtbbbind-2-5 \
     libboost1.74-dev libgtest-dev libgmock-dev libbenchmark-dev libbenchmark1debian)
  du -sh "$debs"
  exit
fi

out=${OUT:-build-gpu/out}
mkdir -p "$out"
limit=${TIME_LIMIT:-480}
start=$(date +%s)
left() { echo $((limit - ($(date +%s) - start))); }
step() {  # step NAME COMMAND...: runs with the time left, logs to $out/NAME.log
  local name=$1; shift
  local budget; budget=$(left)
  if [ "$budget" -le 5 ]; then echo "$name: no time left" | tee -a "$out/results.txt"; return 1; fi
  timeout "$budget" "$@" > "$out/$name.log" 2>&1
  local rc=$?
  echo "$name: exit $rc ($(( $(date +%s) - start )) s in)" | tee -a "$out/results.txt"
  return $rc
}
: > "$out/results.txt"
{ nvidia-smi; nvcc --version; nproc; } > "$out/device.log" 2>&1

prefix=$(mktemp -d -t statmc-deps.XXXXXX)
ls "$debs"/*.deb > /dev/null 2>&1 || { echo "no $debs/*.deb: run --fetch-deps first" >&2; exit 1; }
for f in "$debs"/*.deb; do dpkg -x "$f" "$prefix"; done
export LD_LIBRARY_PATH="$prefix/usr/lib/x86_64-linux-gnu:${LD_LIBRARY_PATH:-}"
nvcc=$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)

step configure cmake -S . -B build-gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTATMC_CORE_ONLY=ON \
  -DSTATMC_CUDA=ON -DCMAKE_CUDA_COMPILER="$nvcc" -DCMAKE_PREFIX_PATH="$prefix/usr" \
  -DBoost_INCLUDE_DIR="$prefix/usr/include" || exit 1
step build cmake --build build-gpu -j "$(nproc)" --target test_core test_cuda bench_cuda || exit 1
step cuda-tests ctest --test-dir build-gpu -L cuda --output-on-failure
grep -E "tests passed|tests failed|\(Failed\)" "$out/cuda-tests.log" >> "$out/results.txt"
step core-tests build-gpu/tests/core/test_core --gtest_brief=1
step bench build-gpu/bench/bench_cuda --benchmark_out="$out/bench.json" --benchmark_out_format=json
grep -E "median" "$out/bench.log" >> "$out/results.txt"
cat "$out/results.txt"
