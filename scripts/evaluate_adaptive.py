"""Adaptive sampling against uniform sampling (docs/sampling.md, "Adaptive sampling").

For each scene: a reference of our own renderer (seed 1000), then uniform and adaptive
renders of the same schedule (same samples in all, so about the same time) over several
seeds, and adaptive renders with a noise threshold. Reports the render time (the header's
statmc:renderTime: tracing plus the adaptive allocations), the relMSE of the noisy mean
and of statmc's default denoise against the reference, a trimmed relMSE without the 0.1%
largest pixel-channel errors (a few fireflies decide short renders), and the equal-time
ratio (relMSE × time, adaptive over uniform: below 1 is a gain at equal time).

Usage (after the build):
  PYTHONPATH=build/python /usr/bin/python3 scripts/evaluate_adaptive.py [OUT_DIR]
Prints Markdown tables. About 12 minutes on 2 cores, most of it the references.
"""

import os
import subprocess
import sys

import numpy as np

import statmc
from image_metrics import relmse

RENDER = "build/renderer/statmc-render"
SCENES = [("veach-ajar", "320x180", 2048), ("veach-mis", "320x180", 4096),
          ("cornell-box", "256x256", 4096)]
SPP = 128
SEEDS = (1, 2, 3)
THRESHOLDS = (0.05, 0.1)
THRESHOLD_SPP = 1024


def render(scene, size, spp, seed, path, extra=()):
    if not os.path.exists(path):
        subprocess.run([RENDER, f"../shared/scenes/{scene}/scene.pbrt", "--resolution", size,
                        "--spp", str(spp), "--seed", str(seed), "--quiet", "-o", path,
                        *extra], check=True)
    return statmc.read_statistics(path)


def measure(image, reference):
    denoised = statmc.denoise(image)["beauty"]
    noisy = image["beauty"]
    counts = image["sampleCount"]
    return {
        "time": float(image.attributes["statmc:renderTime"]),
        "spp_mean": float(np.mean(counts)),
        "spp_min": float(np.min(counts)),
        "spp_max": float(np.max(counts)),
        "noisy": relmse(noisy, reference),
        "noisy_trim": relmse(noisy, reference, 0.001),
        "denoised": relmse(denoised, reference),
        "denoised_trim": relmse(denoised, reference, 0.001),
    }


def block_max(r):
    """The largest value of each 3x3 block, clipped at the borders."""
    p = np.pad(r, 1, mode="edge")
    h, w = r.shape
    return np.max([p[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)], axis=0)


def calibration(image, reference, threshold):
    """The pixels whose own mean meets the noise threshold at the end (the stop rule, with the
    reference in place of the denoised value), and the share of them whose mean misses the
    reference by more than the threshold: nominally at most 5% for a 95% interval."""
    n = image["sampleCount"][..., 0]
    denominator = reference ** 2 + 0.01
    r = block_max(np.max(image["variance"] / denominator, axis=2))
    met = 1.96 * np.sqrt(r / n) <= threshold
    error = np.max(np.abs(image["beauty"] - reference) / np.sqrt(denominator), axis=2)
    return float(np.mean(met)), float(np.mean(error[met] > threshold)) if met.any() else 0.0


def average(rows):
    return {k: float(np.mean([r[k] for r in rows])) for k in rows[0]}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/adaptive"
    os.makedirs(out, exist_ok=True)
    print(f"{SPP} spp (iterations 4, 4, 8, 16, 32, 64; adaptive from 16 spp), "
          f"{len(SEEDS)} seeds averaged; relMSE against our own reference\n")
    print("| scene | sampling | time [s] | spp min..max | noisy relMSE (trimmed) "
          "| denoised relMSE (trimmed) | equal-time ratio noisy / denoised |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for scene, size, ref_spp in SCENES:
        reference = render(scene, size, ref_spp, 1000, f"{out}/{scene}-ref.exr")["beauty"]
        results = {}
        for mode, extra in (("uniform", ()), ("adaptive", ("--adaptive",))):
            results[mode] = average([
                measure(render(scene, size, SPP, seed, f"{out}/{scene}-{mode}-{seed}.exr",
                               extra), reference) for seed in SEEDS])
        u = results["uniform"]
        for mode, r in results.items():
            ratio = ""
            if mode == "adaptive":
                ratio = (f"{r['noisy'] * r['time'] / (u['noisy'] * u['time']):.2f} / "
                         f"{r['denoised'] * r['time'] / (u['denoised'] * u['time']):.2f}")
            print(f"| {scene} | {mode} | {r['time']:.2f} | {r['spp_min']:.0f}..{r['spp_max']:.0f} "
                  f"| {r['noisy']:.4g} ({r['noisy_trim']:.4g}) "
                  f"| {r['denoised']:.4g} ({r['denoised_trim']:.4g}) | {ratio} |", flush=True)
    print(f"\nWith a noise threshold, up to {THRESHOLD_SPP} spp, seed 1\n")
    print("| scene | threshold | time [s] | mean spp (min..max) | noisy relMSE "
          "| denoised relMSE | pixels within the threshold | of those, mean off by more |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for scene, size, ref_spp in SCENES:
        reference = render(scene, size, ref_spp, 1000, f"{out}/{scene}-ref.exr")["beauty"]
        for t in THRESHOLDS:
            image = render(scene, size, THRESHOLD_SPP, 1, f"{out}/{scene}-t{t}.exr",
                           ("--adaptive", "--noise-threshold", str(t)))
            r = measure(image, reference)
            met, missed = calibration(image, reference, t)
            print(f"| {scene} | {t} | {r['time']:.2f} | {r['spp_mean']:.1f} "
                  f"({r['spp_min']:.0f}..{r['spp_max']:.0f}) | {r['noisy']:.4g} "
                  f"| {r['denoised']:.4g} | {100 * met:.1f}% | {100 * missed:.1f}% |", flush=True)


main()
