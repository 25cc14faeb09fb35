#!/usr/bin/env python3
"""Scores the sequences scripts/evaluate_temporal.sh denoised and writes
docs/evaluation-temporal.md with its charts (the metrics are defined in docs/method.md §13):

  relMSE   per frame, mean over pixels and R,G,B of (x - r)^2 / (r^2 + 0.01), as statmc
           --compare computes it;
  flicker  the relative RMSE of the frame-to-frame change against the reference's:
           sqrt(mean over t >= 2, pixels, R,G,B of ((x_t - x_{t-1}) - (r_t - r_{t-1}))^2
           / (r_t^2 + 0.01)).
"""
import argparse
import csv
import os

import numpy as np
import OpenImageIO as oiio

from evaluation_report import write_report
from image_metrics import EPS, relmse
from image_metrics import tonemap as tonemap_float


def rgb(path):
    buf = oiio.ImageBuf(path)
    names = list(buf.spec().channelnames)
    pixels = buf.get_pixels(oiio.FLOAT)
    return pixels[:, :, [names.index(c) for c in ("R", "G", "B")]]


def flicker(xs, rs):
    terms = [((xs[t] - xs[t - 1]) - (rs[t] - rs[t - 1])) ** 2 / (rs[t] ** 2 + EPS)
             for t in range(1, len(xs))]
    return float(np.sqrt(np.mean(terms)))


def sequence(directory, prefix, frames):
    return [rgb(os.path.join(directory, f"{prefix}.{k:04d}.exr")) for k in range(1, frames + 1)]


def timing(directory):
    """Seconds per frame by label: K=0, K=1, K=2 and, where OIDN ran, oidn and verified."""
    with open(os.path.join(directory, "timing.csv")) as f:
        return {(f"K={row['k']}" if row["k"].isdigit() else row["k"]):
                float(row["seconds_per_frame"]) for row in csv.DictReader(f)}


# OIDN per frame and verified OIDN per frame (`--oidn`, `--dup --oidn --verify`), where
# evaluate_temporal.sh could run them.
OIDN_LABELS = ("oidn", "verified")


def score(directory, refs, frames):
    """relMSE and MSE (mean, per frame) and flicker of the noisy input, of K = 0, 1, 2 and of
    OIDN and verified OIDN per frame where they are there."""
    rows = {}
    noisy = sequence(directory, "f", frames)
    runs = [("noisy", noisy)] + [(f"K={k}", sequence(directory, f"d{k}", frames))
                                 for k in (0, 1, 2)]
    runs += [(label, sequence(directory, label, frames)) for label in OIDN_LABELS
             if os.path.exists(os.path.join(directory, f"{label}.0001.exr"))]
    for label, xs in runs:
        per_frame = [relmse(x, r) for x, r in zip(xs, refs)]
        mse = float(np.mean([np.mean((x - r) ** 2) for x, r in zip(xs, refs)]))
        rows[label] = {"relmse": float(np.mean(per_frame)), "per_frame": per_frame, "mse": mse,
                       "flicker": flicker(xs, refs), "images": xs}
    worst = max(max(rows[k]["per_frame"][t] / rows["noisy"]["per_frame"][t]
                    for t in range(frames)) for k in ("K=0", "K=1", "K=2"))
    for k in ("K=1", "K=2"):
        rows[k]["worst_against_per_frame"] = max(
            rows[k]["per_frame"][t] / rows["K=0"]["per_frame"][t] for t in range(frames))
    return rows, worst


def tonemap(x):
    return (tonemap_float(x) * 255 + 0.5).astype(np.uint8)


def write_png(path, image):
    h, w, _ = image.shape
    buf = oiio.ImageBuf(oiio.ImageSpec(w, h, 3, oiio.UINT8))
    if not buf.set_pixels(oiio.ROI(0, w, 0, h, 0, 1, 0, 3), np.ascontiguousarray(image)) or \
            not buf.write(path):
        raise SystemExit(buf.geterror())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--out", required=True)
    p.add_argument("--frames", type=int, required=True)
    p.add_argument("--spps", required=True)
    p.add_argument("--pan-spp", type=int, required=True)
    p.add_argument("--res", type=int, required=True)
    p.add_argument("--ref-spp", type=int, required=True)
    p.add_argument("--pan-ref-spp", type=int, required=True)
    p.add_argument("--report", required=True)
    p.add_argument("--images", required=True)
    a = p.parse_args()
    spps = [int(s) for s in a.spps.split()]
    n = a.frames

    static_ref = rgb(os.path.join(a.out, "static-ref.exr"))
    static = {}
    for spp in spps:
        d = os.path.join(a.out, f"static-{spp}")
        static[spp] = score(d, [static_ref] * n, n) + (timing(d),)
    pan_refs = sequence(os.path.join(a.out, "pan-ref"), "f", n)
    pan_dir = os.path.join(a.out, f"pan-{a.pan_spp}")
    pan = score(pan_dir, pan_refs, n) + (timing(pan_dir),)
    still = score(pan_dir + "-nomotion", pan_refs, n) + (timing(pan_dir + "-nomotion"),)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for label, style in [("noisy", "k:"), ("K=0", "o-"), ("K=1", "s-"), ("K=2", "^-")]:
        name = "per frame" if label == "K=0" else label
        axes[0].loglog(spps, [static[s][0][label]["flicker"] for s in spps], style, label=name)
        axes[1].loglog(spps, [static[s][0][label]["relmse"] for s in spps], style, label=name)
    axes[0].set_title("flicker (static camera)")
    axes[1].set_title("relMSE per frame (static camera)")
    for ax in axes:
        ax.set_xlabel("samples per pixel per frame")
        ax.set_xticks(spps)
        ax.set_xticklabels([str(s) for s in spps])
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.images, "temporal_flicker.png"), dpi=110)

    # A strip of four consecutive pan frames: noisy, per frame, K = 2, reference.
    rows = [pan[0]["noisy"]["images"], pan[0]["K=0"]["images"], pan[0]["K=2"]["images"],
            pan_refs]
    t0 = n // 2 - 2
    strip = np.concatenate([np.concatenate([tonemap(r[t]) for t in range(t0, t0 + 4)], axis=1)
                            for r in rows], axis=0)
    write_png(os.path.join(a.images, "temporal_strip.png"), strip)

    def table(results, caption):
        rows, worst, times = results
        lines = [caption, "", "| | relMSE (mean of frames) | MSE (mean of frames) | flicker "
                 "| time per frame (s) |", "| --- | --- | --- | --- | --- |"]
        names = {"K=0": "per frame (K = 0)", "K=1": "K = 1", "K=2": "K = 2",
                 "oidn": "OIDN 2 per frame (guides)", "verified": "verified OIDN per frame"}
        for label in ["noisy"] + [k for k in names if k in rows]:
            t = f"{times[label]:.3f}" if label in times else ""
            lines.append(f"| {names.get(label, label)} | {rows[label]['relmse']:.5g} "
                         f"| {rows[label]['mse']:.4g} | {rows[label]['flicker']:.4g} | {t} |")
        k0 = rows["K=0"]
        lines += ["", f"K = 2 against per frame: flicker {k0['flicker'] / rows['K=2']['flicker']:.2f}× "
                  f"lower, relMSE {k0['relmse'] / rows['K=2']['relmse']:.2f}× lower; "
                  f"K = 1: {k0['flicker'] / rows['K=1']['flicker']:.2f}× and "
                  f"{k0['relmse'] / rows['K=1']['relmse']:.2f}×. The worst frame of any denoised "
                  f"sequence has {worst:.3f}× its noisy input's relMSE; the worst frame with "
                  f"K = 1 and 2 has {rows['K=1']['worst_against_per_frame']:.2f}× and "
                  f"{rows['K=2']['worst_against_per_frame']:.2f}× the relMSE of the same "
                  f"frame denoised alone.", ""]
        return lines

    out = ["# Temporal denoising: flicker and error on two sequences", "",
           "Generated by `bash scripts/evaluate_temporal.sh` (scripts/temporal_metrics.py); do "
           "not edit by hand. The metrics and the method are in docs/method.md §13.", "",
           f"Sequences of {n} frames at {a.res}×{a.res}, made from the shared Cornell box by "
           f"scripts/temporal_scenes.py and rendered by `statmc-render --frames 1-{n} --fps 24` "
           "(each frame its own seed): a **static** camera, scored against one reference of "
           f"{a.ref_spp} spp, and a **pan** (the camera orbiting the box by 16° per second "
           f"at 24 frames per second, with the motion layer), scored frame by frame against references of "
           f"{a.pan_ref_spp} spp. The denoiser is statmc's default (`--denoise`, guides on) "
           "per frame (K = 0) and with `temporal=K`, beside OIDN 2 with guides per frame "
           "(`--oidn`, pyoidn's library, CPU) and verified OIDN per frame (`--dup --oidn "
           "--verify`) where the OIDN library was found; time per frame is the tool's wall "
           "time over the sequence, reading and writing included, on this 2-core machine.", "",
           "![flicker and relMSE against spp](images/temporal_flicker.png)", ""]
    for spp in spps:
        out += table(static[spp], f"## Static camera, {spp} spp per frame")
    out += table(pan, f"## Pan, {a.pan_spp} spp per frame, following the motion layer")
    out += table(still, f"## The same pan without its motion layer (temporal assumes a static "
                        f"camera)")
    out += ["Frames {}–{} of the pan: noisy, per frame, K = 2, reference (top to bottom).".format(
        t0 + 1, t0 + 4), "", "![pan strip](images/temporal_strip.png)", ""]
    write_report(a.report, out, "evaluation-temporal-notes.md")


if __name__ == "__main__":
    main()
