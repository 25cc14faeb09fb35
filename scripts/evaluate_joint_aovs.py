"""Joint against separate AOV denoising (docs/method.md §14), measured with import statmc.

Two light contributions rendered apart by statmc-render stand for two light groups: AOV
"a" is the Cornell box, AOV "b" Veach MIS, both at the same size and sample count with
their own seeds. The beauty is their sum, sample by sample: means and per-sample central
moments add (M2 and M3 add; M4 = M4a + M4b + 6 s2a s2b for independent samples). The
references are the same renders at many samples, summed the same way.

Usage (after the build): PYTHONPATH=build/python /usr/bin/python3 scripts/evaluate_joint_aovs.py OUT_DIR
Prints a Markdown table (relMSE of each AOV and of the beauty, and the sum mismatch).
"""

import os
import subprocess
import sys

import numpy as np

import statmc
from image_metrics import relmse

RENDER = "build/renderer/statmc-render"
SCENES = {"a": "../shared/scenes/cornell-box/scene.pbrt", "b": "../shared/scenes/veach-mis/scene.pbrt"}
SIZE, SPP, REFERENCE_SPP = "320x240", 16, 1024


def render(scene, spp, seed, path):
    if not os.path.exists(path):
        subprocess.run([RENDER, scene, "--resolution", SIZE, "--spp", str(spp), "--seed",
                        str(seed), "--quiet", "-o", path], check=True)
    return statmc.read_statistics(path)


def summed(a, b):
    """The statistics of per-sample sums of two independent renders with equal counts."""
    assert np.array_equal(a["sampleCount"], b["sampleCount"])
    n = a["sampleCount"]
    image = statmc.Image({
        "beauty": a["beauty"] + b["beauty"],
        "sampleCount": n,
        "variance": a["variance"] + b["variance"],
        "M3": a["M3"] + b["M3"],
        # Per-sample central moments: M2 = s2 (n - 1)/n, the variance layer being s2.
        "M4": a["M4"] + b["M4"] + 6 * (a["variance"] * (n - 1) / n) * (b["variance"] * (n - 1) / n),
        "albedo": a["albedo"], "normal": a["normal"],
    }, attributes={"statmc:formatVersion": 2})
    for name, part in (("a", a), ("b", b)):
        for layer in ("beauty", "variance", "M3", "M4"):
            key = name if layer == "beauty" else f"{name}.{layer}"
            image[key] = part[layer]
    return image


def means_only(image):
    """`image` without the AOVs' statistics: what the K-pass route gives light groups."""
    return {k: v for k, v in image.items() if not (k.startswith(("a.", "b.")))}


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out/joint-aovs"
    os.makedirs(out, exist_ok=True)
    noisy = {k: render(s, SPP, 1 + i, f"{out}/{k}-{SPP}spp.exr") for i, (k, s) in enumerate(SCENES.items())}
    ref = {k: render(s, REFERENCE_SPP, 100 + i, f"{out}/{k}-ref.exr")["beauty"]
           for i, (k, s) in enumerate(SCENES.items())}
    ref["beauty"] = ref["a"] + ref["b"]
    stats = summed(noisy["a"], noisy["b"])
    statmc.write_statistics(f"{out}/sum-{SPP}spp.exr", stats)
    runs = {
        "noisy input": stats,
        "separate (default method)": statmc.denoise(stats, aovs="a,b"),
        "separate (classic)": statmc.denoise(stats, aovs="a,b", method="classic"),
        # AOVs that carry only their means share the beauty's test; with their own
        # statistics, every AOV's test decides.
        "joint, the beauty's test (AOVs' means only)": statmc.denoise(means_only(stats), aovs="a,b",
                                                                      joint=True),
        "joint, every test (AOVs with statistics)": statmc.denoise(stats, aovs="a,b", joint=True),
    }
    print(f"{SIZE}, {SPP} spp per AOV, references {REFERENCE_SPP} spp\n")
    print("| | relMSE a | relMSE b | relMSE beauty | mean abs(a + b − beauty) / beauty |")
    print("| --- | --- | --- | --- | --- |")
    for name, image in runs.items():
        mismatch = np.mean(np.abs(image["a"] + image["b"] - image["beauty"]) /
                           (np.abs(image["beauty"]) + 1e-3))
        print(f"| {name} | {relmse(image['a'], ref['a']):.4g} | {relmse(image['b'], ref['b']):.4g} "
              f"| {relmse(image['beauty'], ref['beauty']):.4g} | {mismatch:.2g} |")


main()
