#!/usr/bin/env bash
# Builds the fuzz targets of tests/fuzz with clang's libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer, and runs each for SECONDS (default 60).
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: scene_parser ply_reader
# layer_reader command_line operator_parameters; default all)
# Each target starts from its seeds in tests/fuzz/corpus/<target>/ and grows a working
# corpus in build-fuzz/corpus/<target>/; a crash, leak, hang (over 10 s on one input) or
# allocation over 2 GB is written to build-fuzz/artifacts/<target>/ and ends the script
# with exit 1. Keep a found input as a regression test: minimise it (-minimize_crash=1),
# fix the bug, and copy the input into tests/fuzz/corpus/<target>/ (docs/reliability.md).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(scene_parser ply_reader layer_reader command_line operator_parameters)
build=${FUZZ_BUILD_DIR:-build-fuzz}

CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTATMC_FUZZ=ON -DSTATMC_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target "${targets[@]/#/fuzz_}"

status=0
for t in "${targets[@]}"; do
    corpus="$build/corpus/$t"
    artifacts="$build/artifacts/$t"
    mkdir -p "$corpus" "$artifacts"
    log="$build/fuzz-$t.log"
    echo "== $t: ${seconds} s"
    # Leak checks are off: OIIO and OpenEXR keep process-wide caches that are freed at exit.
    if ! "$build/tests/fuzz/fuzz_$t" "$corpus" "tests/fuzz/corpus/$t" \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
        -detect_leaks=0 -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1; then
        status=1
        echo "$t: FOUND A PROBLEM (input in $artifacts/, log in $log):"
        grep -E "ERROR|SUMMARY|Test unit written|terminate called|what\(\)" "$log" | head -20 || true
    fi
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb|cov: " "$log" | tail -3 |
        sed "s/^/  $t: /" || true
done
exit $status
