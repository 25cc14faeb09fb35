"""The README's verify figure: a frame of the promise check (scripts/promise_check.py --oidn
must have run), noisy | OIDN | verified OIDN | reference, and the rejection map
(diagnostics.rejected: where the samples refused OIDN's value). Not part of CI.

    /usr/bin/python3 scripts/verify_figure.py [--scene veach-mis --spp 64 --seed 11]
"""

import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def shown(rgb):
    """Scene-linear to a picture: Reinhard's x/(1+x), then the sRGB-like gamma 1/2.2."""
    return np.clip(rgb / (1 + rgb), 0, 1) ** (1 / 2.2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--promise", default=os.path.join(ROOT, "build", "promise"))
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--scene", default="veach-mis")
    parser.add_argument("--spp", type=int, default=64)
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--resolution", default="320x180")
    parser.add_argument("--verified", default="verified", help="the promise check's method name")
    parser.add_argument("-o", default=os.path.join(ROOT, "docs", "images", "verify-veach-mis.png"))
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import statmc  # noqa: E402

    d = os.path.join(args.promise, args.scene)
    tag = f"{args.spp}-{args.seed}"
    noisy = statmc.read_statistics(os.path.join(d, f"noisy-{args.resolution}-{tag}.exr"))
    oidn = statmc.read_statistics(os.path.join(d, f"{tag}-oidn.exr"))
    verified = statmc.read_statistics(os.path.join(d, f"{tag}-{args.verified}.exr"))
    ref = statmc.read_statistics(os.path.join(d, f"reference-4096-{args.resolution}.exr"))
    rejected = verified["diagnostics"][:, :, 0]
    panels = [("noisy", noisy), ("OIDN", oidn), ("verified OIDN", verified), ("reference", ref)]
    fig, axes = plt.subplots(1, 5, figsize=(16, 2.2))
    for ax, (title, image) in zip(axes, panels):
        ax.imshow(shown(image["beauty"][:, :, :3]))
        ax.set_title(title, fontsize=9)
    axes[4].imshow(rejected > 0, cmap="gray")
    axes[4].set_title(f"rejected ({100 * (rejected > 0).mean():.1f}% of pixels)", fontsize=9)
    for ax in axes:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(args.o, dpi=100)
    print(args.o)


if __name__ == "__main__":
    main()
