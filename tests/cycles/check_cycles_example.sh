#!/usr/bin/env bash
# ctest cycles.example: scripts/cycles-example.sh at a small size; statmc's denoised image
# must score a lower relMSE and DSSIM against Cycles' own reference than the mean of the
# passes it came from. Exit 77 (skipped, shown by ctest) without blender.
set -euo pipefail
out=$1
export K=4 SPP=4 RES=96x72 REFERENCE=256
status=0
bash "$(dirname "$0")/../../scripts/cycles-example.sh" "$out" || status=$?
[ "$status" -eq 0 ] || exit "$status"
score() { awk -v m="$2" '$1 == m { print $2 }' "$out/$1-scores.txt"; }
for metric in relMSE DSSIM; do
  before=$(score statistics "$metric") after=$(score denoised "$metric")
  echo "$metric: mean of the passes $before, denoised $after"
  awk -v a="$after" -v b="$before" 'BEGIN { exit !(a < b) }' ||
    { echo "FAIL: denoising made $metric worse" >&2; exit 1; }
done
