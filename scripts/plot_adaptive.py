"""Sample-count maps of adaptive renders beside their denoised images (docs/sampling.md).

Usage, after scripts/evaluate_adaptive.py has written OUT_DIR:
  PYTHONPATH=build/python /usr/bin/python3 scripts/plot_adaptive.py OUT_DIR docs/images
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import statmc  # noqa: E402
from image_metrics import tonemap  # noqa: E402

SCENES = ("veach-ajar", "veach-mis", "cornell-box")


def main():
    out, images = sys.argv[1], sys.argv[2]
    fig, axes = plt.subplots(2, len(SCENES), figsize=(4 * len(SCENES), 5.2))
    for col, scene in enumerate(SCENES):
        frame = statmc.read_statistics(os.path.join(out, f"{scene}-adaptive-1.exr"))
        counts = frame["sampleCount"][..., 0]
        axes[0, col].imshow(tonemap(statmc.denoise(frame)["beauty"]))
        axes[0, col].set_title(f"{scene}, denoised", fontsize=9)
        shown = axes[1, col].imshow(counts, cmap="magma", norm=matplotlib.colors.LogNorm())
        axes[1, col].set_title(f"samples per pixel ({counts.min():.0f}..{counts.max():.0f}, "
                               f"mean {counts.mean():.0f})", fontsize=9)
        fig.colorbar(shown, ax=axes[1, col], fraction=0.046, pad=0.02)
    for ax in axes.ravel():
        ax.set_axis_off()
    fig.tight_layout()
    fig.savefig(os.path.join(images, "adaptive_counts.png"), dpi=72)


main()
