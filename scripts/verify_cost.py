#!/usr/bin/env python3
"""What verify costs beside the default denoise (docs/performance.md, "Verified OIDN").

    STATMC_OIDN_LIBRARY=… python3 scripts/verify_cost.py FRAME.exr [--build build] [--runs 5]

Reads the frame once, runs OIDN on it once (the candidate), then times, from memory and
through the Python module (each call converts the image both ways, so every row pays the
same copies): the default denoise, verify with fallback=mean (its own test alone) and
verify with the default fallback, which denoises the rejected pixels alone. Medians of
--runs calls, one run, on whatever cores the machine has.
"""
import argparse
import os
import statistics
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def median_seconds(runs, call):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        result = call()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("frame")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import statmc

    image = statmc.read_statistics(args.frame)
    candidate = statmc.oidn(image)["beauty"][:, :, :3]
    denoise, _ = median_seconds(args.runs, lambda: statmc.denoise(image))
    mean, _ = median_seconds(args.runs, lambda: statmc.verify(image, candidate, fallback="mean"))
    full, verified = median_seconds(args.runs, lambda: statmc.verify(image, candidate))
    rejected = float((verified["diagnostics"][:, :, 0] > 0).mean())
    print(f"frame {args.frame}: {image['beauty'].shape[1]}x{image['beauty'].shape[0]}, "
          f"{rejected:.2%} of the pixels rejected, medians of {args.runs}")
    print("| call | seconds | / default denoise |")
    print("| --- | --- | --- |")
    for name, seconds in (("default denoise", denoise), ("verify, fallback=mean", mean),
                          ("verify, default fallback", full)):
        print(f"| {name} | {seconds:.3f} | {seconds / denoise:.2f}× |")


if __name__ == "__main__":
    main()
