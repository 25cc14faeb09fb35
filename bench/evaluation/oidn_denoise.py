#!/usr/bin/python3
"""The neural anchor of docs/evaluation.md: Intel Open Image Denoise (through the pyoidn
binding, CPU device, its trained weights) on statistics EXRs, for statmc-evaluate to score.

For each X.exr writes X.oidn.exr (colour only) and X.oidn-guides.exr (colour + albedo +
normal), R,G,B float, with statmc:denoiseSeconds = the median of 3 timed calls.
An evaluation-only dependency: the product never needs it.

Usage: oidn_denoise.py X.exr...
"""
import os
import statistics
import sys
import time

import numpy as np
import OpenImageIO as oiio
import pyoidn


def planes(buf, names):
    spec = buf.spec()
    idx = [spec.channelindex(n) for n in names]
    if min(idx) < 0:
        raise SystemExit(f"{buf.name}: missing channels {names}")
    pixels = buf.get_pixels(oiio.FLOAT)
    return np.ascontiguousarray(pixels[:, :, idx])


def timed(run):
    times, out = [], None
    for _ in range(3):
        start = time.perf_counter()
        out = run()
        times.append(time.perf_counter() - start)
    return out, statistics.median(times)


def write(path, like, rgb, seconds):
    spec = oiio.ImageSpec(like.spec().width, like.spec().height, 3, oiio.FLOAT)
    spec.x, spec.y = like.spec().x, like.spec().y
    spec.channelnames = ("R", "G", "B")
    spec.attribute("statmc:denoiseSeconds", float(seconds))
    out = oiio.ImageBuf(spec)
    out.set_pixels(oiio.ROI(), rgb.astype(np.float32))
    tmp = path + ".tmp.exr"
    if not out.write(tmp):
        raise SystemExit(f"{tmp}: {out.geterror()}")
    os.replace(tmp, path)


def main(paths):
    for path in paths:
        buf = oiio.ImageBuf(path)
        colour = np.maximum(planes(buf, ["R", "G", "B"]), 0)
        albedo = np.clip(planes(buf, ["albedo.R", "albedo.G", "albedo.B"]), 0, 1)
        normal = np.clip(planes(buf, ["normal.X", "normal.Y", "normal.Z"]), -1, 1)
        stem = path[:-4] if path.endswith(".exr") else path
        plain, t = timed(lambda: pyoidn.denoise(colour, hdr=True))
        write(stem + ".oidn.exr", buf, plain, t)
        guided, tg = timed(lambda: pyoidn.denoise(colour, albedo, normal, hdr=True))
        write(stem + ".oidn-guides.exr", buf, guided, tg)
        print(f"{path}: oidn {t:.3f} s, oidn-guides {tg:.3f} s")


if __name__ == "__main__":
    main(sys.argv[1:])
