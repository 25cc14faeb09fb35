"""The firefly guard on the untransformed route (variance AOVs, K passes): relMSE of the
denoised frame against a 1024-spp render, with the guard (fireflies=256, the default) and
without it (fireflies=0, what that route had before), for the default and classic methods.

statmc-render frames are stripped to a variance AOV (mean, variance, count, M3, M4,
guides: no Box-Cox layers), so the denoiser tests the untransformed means.

Usage (after the build): PYTHONPATH=build/python /usr/bin/python3 scripts/evaluate_untransformed_guard.py OUT_DIR
Prints a Markdown table.
"""

import os
import subprocess
import sys


import statmc
from image_metrics import relmse

RENDER = "build/renderer/statmc-render"
SCENES = ["cornell-box", "veach-mis", "veach-ajar"]
SIZE, REFERENCE_SPP = "320x240", 1024
KEEP = ["beauty", "sampleCount", "variance", "M3", "M4", "albedo", "normal"]


def render(scene, spp, seed, path):
    if not os.path.exists(path):
        subprocess.run([RENDER, f"../shared/scenes/{scene}/scene.pbrt", "--resolution", SIZE,
                        "--spp", str(spp), "--seed", str(seed), "--quiet", "-o", path],
                       check=True)
    return statmc.read_statistics(path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/untransformed-guard"
    os.makedirs(out, exist_ok=True)
    print(f"{SIZE}; relMSE against {REFERENCE_SPP} spp; variance-AOV route (untransformed test)\n")
    print("| scene | spp | noisy | default, guard | default, no guard | classic, guard "
          "| classic, no guard |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for scene in SCENES:
        reference = render(scene, REFERENCE_SPP, 1000, f"{out}/{scene}-ref.exr")["beauty"]
        for spp in (4, 16, 64):
            full = render(scene, spp, spp, f"{out}/{scene}-{spp}.exr")
            aov = statmc.Image({k: full[k] for k in KEEP}, channels=full.channels,
                               attributes={"statmc:formatVersion": 2})
            row = [relmse(aov["beauty"], reference)]
            for method in ("default", "classic"):
                for fireflies in (256, 0):
                    denoised = statmc.denoise(aov, method=method, fireflies=fireflies)
                    row.append(relmse(denoised["beauty"], reference))
            print(f"| {scene} | {spp} | " + " | ".join(f"{v:.4g}" for v in row) + " |",
                  flush=True)


main()
