#!/usr/bin/env python3
"""Helper of scripts/speed_vs_oidn.sh.

  speed_vs_oidn.py time FRAME.exr   times OIDN (pyoidn, CPU) on the frame's colour, and on
                                    colour + albedo + normal: median of 5 calls, as JSON
  speed_vs_oidn.py table DIR        the Markdown table of statmc's and OIDN's medians from
                                    DIR/statmc-RES.json (bench_denoise) and DIR/oidn-RES.json
"""
import glob
import json
import os
import statistics
import sys
import time


def time_oidn(path):
    import numpy as np
    import OpenImageIO as oiio
    import pyoidn

    buf = oiio.ImageBuf(path)
    spec = buf.spec()
    pixels = buf.get_pixels(oiio.FLOAT)

    def planes(names):
        return np.ascontiguousarray(pixels[:, :, [spec.channelindex(n) for n in names]])

    colour = np.maximum(planes(["R", "G", "B"]), 0)
    albedo = np.clip(planes(["albedo.R", "albedo.G", "albedo.B"]), 0, 1)
    normal = np.clip(planes(["normal.X", "normal.Y", "normal.Z"]), -1, 1)

    def median_ms(run):
        run()  # the first call builds the network
        times = []
        for _ in range(5):
            start = time.perf_counter()
            run()
            times.append(time.perf_counter() - start)
        return 1000 * statistics.median(times)

    print(json.dumps({
        "colour_ms": median_ms(lambda: pyoidn.denoise(colour, hdr=True)),
        "guides_ms": median_ms(lambda: pyoidn.denoise(colour, albedo, normal, hdr=True)),
    }))


def table(directory):
    print("| frame | statmc classic | statmc default | OIDN (CPU) | OIDN / classic | "
          "OIDN / default |")
    print("| --- | --- | --- | --- | --- | --- |")
    for statmc_json in sorted(glob.glob(os.path.join(directory, "statmc-*.json"))):
        res = os.path.basename(statmc_json)[len("statmc-"):-len(".json")]
        with open(statmc_json) as f:
            runs = json.load(f)["benchmarks"]
        with open(os.path.join(directory, f"oidn-{res}.json")) as f:
            oidn = json.load(f)
        # BM_DenoiseOperator/0/<guides>/<method>/..._median, real time in ms.
        median = {}
        for r in runs:
            if r.get("aggregate_name") == "median":
                _, threads, guides, method = r["run_name"].split("/")[:4]
                median[(int(guides), int(method))] = r["real_time"]
        for guides, label, oidn_ms in ((0, "colour only", oidn["colour_ms"]),
                                       (1, "albedo + normal", oidn["guides_ms"])):
            classic, default = median[(guides, 0)], median[(guides, 1)]
            print(f"| {res}, {label} | {classic:.0f} ms | {default:.0f} ms | {oidn_ms:.0f} ms | "
                  f"{oidn_ms / classic:.1f}× | {oidn_ms / default:.1f}× |")


if __name__ == "__main__":
    if sys.argv[1] == "time":
        time_oidn(sys.argv[2])
    else:
        table(sys.argv[2])
