#!/usr/bin/env bash
# ctest cycles.example: scripts/cycles-example.sh at a small size; statmc's denoised image
# must score a lower relMSE and DSSIM against Cycles' own reference than the mean of the
# passes it came from, and its jointly denoised light groups must add up to the denoised
# beauty. Exit 77 (skipped, shown by ctest) without blender.
set -euo pipefail
out=$1
export K=4 SPP=4 RES=96x72 REFERENCE=256
status=0
bash "$(dirname "$0")/../../scripts/cycles-example.sh" "$out" || status=$?
[ "$status" -eq 0 ] || exit "$status"
# Blender's own groups miss Combined by float rounding (~1e-6 here); so may the sums.
max_error=$(awk '/Max error/ { print $4 }' "$out/light-groups-diff.txt")
grep -q PASS "$out/light-groups-diff.txt" || awk -v e="${max_error:-1}" 'BEGIN { exit !(e < 1e-5) }' ||
  { echo "FAIL: the jointly denoised light groups miss the beauty by ${max_error:-?}" >&2; exit 1; }
echo "light groups: key + fill against the denoised beauty, max error ${max_error:-0}"
score() { awk -v m="$2" '$1 == m { print $2 }' "$out/$1-scores.txt"; }
for metric in relMSE DSSIM; do
  before=$(score statistics "$metric") after=$(score denoised "$metric")
  echo "$metric: mean of the passes $before, denoised $after"
  awk -v a="$after" -v b="$before" 'BEGIN { exit !(a < b) }' ||
    { echo "FAIL: denoising made $metric worse" >&2; exit 1; }
done
