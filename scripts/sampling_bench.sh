#!/usr/bin/env bash
# Sampling-efficiency measurements of docs/sampling.md (seed C.2 style), small enough for
# a 2-core machine (≈ 20 minutes): Veach Ajar ACRR vs classic RR (C.2's constant 4-spp
# iterations, and the progressive schedule), the tracked-bounce sweeps of ACRR and SMIS,
# Veach MIS SMIS vs standard MIS (progressive to 512 spp, and at equal time with constant
# 8-spp iterations), and where the time goes at $BIG_RES (tracing, shadow rays, per-bounce
# statistics, the rest of shading, denoising the estimates). CSVs go to $OUT (not committed); then
#   /usr/bin/python3 scripts/plot_sampling.py $OUT docs/images
# draws the charts and prints the tables.
set -euo pipefail
BUILD=${BUILD:-build}
OUT=${OUT:-bench-out/sampling}
SCENES=${SCENES:-../shared/scenes}
RES=${RES:-160x90}
REF_SPP=${REF_SPP:-2048}
RUNS=${RUNS:-4}
BIG_RES=${BIG_RES:-640x360}
render="$BUILD/renderer/statmc-render"
bench="$BUILD/bench/bench_sampling"
ajar="$SCENES/veach-ajar/scene.pbrt"
mis="$SCENES/veach-mis/scene.pbrt"
mkdir -p "$OUT"

# References of our own renderer (classic RR, standard MIS), seeds apart from the runs'.
[ -f "$OUT/ajar-ref.exr" ] || "$render" "$ajar" -o "$OUT/ajar-ref.exr" --resolution "$RES" --spp "$REF_SPP" --seed 1000 -q
[ -f "$OUT/mis-ref.exr" ] || "$render" "$mis" -o "$OUT/mis-ref.exr" --resolution "$RES" --spp "$REF_SPP" --seed 1000 -q

# 1. Veach Ajar: 32 iterations of 4 spp, roulette from the first hit for both (as C.2).
rm -f "$OUT/ajar_efficiency.csv"
rm -f "$OUT/ajar_breakdown.csv"
for rr in classic acrr; do
  "$bench" "$ajar" --reference "$OUT/ajar-ref.exr" --csv "$OUT/ajar_efficiency.csv" --label "$rr" \
    --rr "$rr" --rr-start-bounce 0 --iterations 32 --spp-per-iteration 4 --runs "$RUNS" \
    --breakdown "$OUT/ajar_breakdown.csv"
done

# 1b. The same with the progressive schedule 4, 4, 8, ..., 128 (256 spp, 7 denoising passes).
rm -f "$OUT/ajar_progressive.csv"
for rr in classic acrr; do
  "$bench" "$ajar" --reference "$OUT/ajar-ref.exr" --csv "$OUT/ajar_progressive.csv" --label "$rr" \
    --rr "$rr" --rr-start-bounce 0 --progressive-spp 256 --runs "$RUNS"
done

# 2. Tracked-bounce sweep: ACRR with 1..8 tracked bounces, same schedule, 2 runs each.
rm -f "$OUT/ajar_sweep.csv"
for n in 1 2 3 4 5 6 7 8; do
  "$bench" "$ajar" --reference "$OUT/ajar-ref.exr" --csv "$OUT/ajar_sweep.csv" --label "acrr$n" \
    --rr acrr --rr-bounces "$n" --rr-start-bounce 0 --iterations 32 --spp-per-iteration 4 --runs 2
done

# 3. Veach MIS, progressive schedule to 512 spp (8 denoising passes), 3 runs each.
rm -f "$OUT/mis_progressive.csv"
for m in standard selective; do
  "$bench" "$mis" --reference "$OUT/mis-ref.exr" --csv "$OUT/mis_progressive.csv" --label "$m" \
    --mis "$m" --progressive-spp 512 --runs 3
done

# 3b. Veach MIS at equal time: 8-spp iterations until 12 CPU seconds have passed, 3 runs each.
rm -f "$OUT/mis_equal_time.csv"
for m in standard selective; do
  "$bench" "$mis" --reference "$OUT/mis-ref.exr" --csv "$OUT/mis_equal_time.csv" --label "$m" \
    --mis "$m" --iterations 1000 --spp-per-iteration 8 --time-budget 12 --runs 3
done

# 4. SMIS tracked-bounce sweep (seed Fig. S3): 1..8 tracked vertices, progressive to 512 spp.
rm -f "$OUT/mis_sweep.csv"
for n in 1 2 3 4 5 6 7 8; do
  "$bench" "$mis" --reference "$OUT/mis-ref.exr" --csv "$OUT/mis_sweep.csv" --label "smis$n" \
    --mis selective --mis-bounces "$n" --progressive-spp 512 --runs 2
done

# 5. Where the time goes at a frame size where the per-bounce denoise is a realistic share:
# Veach Ajar (32 x 4 spp, both roulettes from the first hit) and Veach MIS (progressive to
# 128 spp), 2 runs each, with time stamp counters around Embree's queries and the per-bounce
# statistics. References at 512 spp: their noise is 1/128 of a 4-spp iteration's.
[ -f "$OUT/ajar-big-ref.exr" ] || "$render" "$ajar" -o "$OUT/ajar-big-ref.exr" --resolution "$BIG_RES" --spp 512 --seed 1000 -q
[ -f "$OUT/mis-big-ref.exr" ] || "$render" "$mis" -o "$OUT/mis-big-ref.exr" --resolution "$BIG_RES" --spp 512 --seed 1000 -q
rm -f "$OUT/big_efficiency.csv" "$OUT/big_breakdown.csv" "$OUT/big_mis.csv"
for rr in classic acrr; do
  "$bench" "$ajar" --reference "$OUT/ajar-big-ref.exr" --csv "$OUT/big_efficiency.csv" --label "$rr" \
    --rr "$rr" --rr-start-bounce 0 --iterations 32 --spp-per-iteration 4 --runs 2 \
    --breakdown "$OUT/big_breakdown.csv"
done
for m in standard selective; do
  "$bench" "$mis" --reference "$OUT/mis-big-ref.exr" --csv "$OUT/big_mis.csv" --label "$m" \
    --mis "$m" --progressive-spp 128 --runs 2 --breakdown "$OUT/big_breakdown.csv"
done

# 6. The per-bounce filter's radius (--estimates-radius; default 10) at 640x360, one batch
# (between batches CPU time moved by up to 8% on this VM): classic RR and ACRR at radius 20
# and 10, standard MIS and SMIS at radius 20 and 10, 2 runs each, with the breakdown.
rm -f "$OUT/radius_ajar.csv" "$OUT/radius_mis.csv" "$OUT/radius_breakdown.csv"
"$bench" "$ajar" --reference "$OUT/ajar-big-ref.exr" --csv "$OUT/radius_ajar.csv" --label classic \
  --rr classic --rr-start-bounce 0 --iterations 32 --spp-per-iteration 4 --runs 2 \
  --breakdown "$OUT/radius_breakdown.csv"
for r in 20 10; do
  "$bench" "$ajar" --reference "$OUT/ajar-big-ref.exr" --csv "$OUT/radius_ajar.csv" --label "acrr-r$r" \
    --rr acrr --rr-start-bounce 0 --iterations 32 --spp-per-iteration 4 --runs 2 \
    --estimates-radius "$r" --breakdown "$OUT/radius_breakdown.csv"
done
"$bench" "$mis" --reference "$OUT/mis-big-ref.exr" --csv "$OUT/radius_mis.csv" --label standard \
  --mis standard --progressive-spp 128 --runs 2 --breakdown "$OUT/radius_breakdown.csv"
for r in 20 10; do
  "$bench" "$mis" --reference "$OUT/mis-big-ref.exr" --csv "$OUT/radius_mis.csv" --label "selective-r$r" \
    --mis selective --progressive-spp 128 --runs 2 --estimates-radius "$r" \
    --breakdown "$OUT/radius_breakdown.csv"
done
