#!/usr/bin/env python3
"""statmc's command line end to end against oiiotool's plain copy of the same frame, in one
run (not part of CI; about two minutes).

Renders the Cornell box at 1280x720, 16 spp, with statmc-render (once; the frame is shared
with scripts/speed_vs_oidn.sh), then runs each command below RUNS times, interleaved, and
prints the medians of wall time, CPU time (user + system) and peak memory, with each
command's ratio to `oiiotool frame.exr -o out.exr`. CPU time and peak memory come from the
kernel (wait4), so no timing tool is needed.

    /usr/bin/python3 scripts/io_vs_oiiotool.py            # BUILD=build RUNS=3
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, os.environ.get("BUILD", "build"))
RUNS = int(os.environ.get("RUNS", "3"))
SCENE = os.environ.get("SCENE", os.path.join(ROOT, "..", "shared", "scenes", "cornell-box",
                                             "scene.pbrt"))


def timed(command, env=None):
    """Wall seconds, CPU seconds and peak resident memory (MB) of one run of `command`
    (CPU time includes the children it waited for: statmc's isolated decoder)."""
    start = time.monotonic()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                             env=dict(os.environ, **env) if env else None)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"io_vs_oiiotool: failed ({status}): {' '.join(command)}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def main():
    subprocess.run(["cmake", "--build", BUILD, "--target", "statmc", "statmc-decode",
                    "statmc-render"], check=True,
                   stdout=subprocess.DEVNULL)
    statmc = os.path.join(BUILD, "oiiotool_ext", "statmc")
    frame_dir = os.path.join(BUILD, "speed-vs-oidn")
    frame = os.path.join(frame_dir, "cornell-1280x720.exr")
    if not os.path.exists(frame):
        os.makedirs(frame_dir, exist_ok=True)
        subprocess.run([os.path.join(BUILD, "renderer", "statmc-render"), SCENE, "--spp", "16",
                        "--resolution", "1280x720", "-q", "-o", frame], check=True)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.exr")
        # An empty STATMC_DECODER: no isolated decoder, so OpenEXR's checker reads the
        # file first (what statmc did before the decoder; docs/reliability.md).
        checker = {"STATMC_DECODER": ""}
        commands = [
            ("oiiotool: copy", ["oiiotool", frame, "-o", out]),
            ("statmc: copy", [statmc, frame, "-o", out]),
            ("statmc: denoise", [statmc, frame, "--denoise", "-o", out]),
            ("statmc, OpenEXR's checker instead of the decoder: denoise",
             [statmc, frame, "--denoise", "-o", out], checker),
            ("statmc: denoise, -o:keep=means", [statmc, frame, "--denoise", "-o:keep=means", out]),
            ("statmc --check-inputs 0: denoise",
             [statmc, "--check-inputs", "0", frame, "--denoise", "-o", out]),
            ("statmc --check-inputs 0: denoise, -o:keep=means",
             [statmc, "--check-inputs", "0", frame, "--denoise", "-o:keep=means", out]),
        ]
        runs = {c[0]: [] for c in commands}
        for _ in range(RUNS):
            for name, command, *env in commands:
                runs[name].append(timed(command, *env))
    medians = {name: [statistics.median(r[k] for r in rs) for k in range(3)]
               for name, rs in runs.items()}
    base_wall, base_cpu, base_memory = medians["oiiotool: copy"]
    size = os.path.getsize(frame) / 1e6
    print(f"{frame}: {size:.0f} MB; {os.cpu_count()} cores; medians of {RUNS}\n")
    print("| command | wall | CPU (user + sys) | peak memory | wall / oiiotool | CPU / oiiotool |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, (wall, cpu, memory) in medians.items():
        print(f"| {name} | {wall:.2f} s | {cpu:.2f} s | {memory:.0f} MB | "
              f"{wall / base_wall:.2f}× | {cpu / base_cpu:.2f}× |")


if __name__ == "__main__":
    main()
