"""The promise on a real renderer's frames (docs/evaluation-notes.md, "The Cycles suite"):
three Blender Cycles scenes (bench/evaluation/cycles_scenes.py) through the K-pass route,
K = 4, 8 and 16 passes of S samples each, scored as scripts/promise_check.py scores
statmc-render's frames: MSE and relMSE less the reference's own share, DSSIM, and the energy
kept around emitters and highlights, beside the mean of the passes.

The reference is 4 passes of REF_SPP/4 samples with other seeds, merged by `--passes`, so
its own share comes from its passes' spread. Renders are cached in OUT; not part of CI.

    python3 scripts/cycles_check.py --oidn        # about 25 minutes on 2 cores, most of it
                                                  # the references
    python3 scripts/cycles_check.py --report      # the tables again
"""

import argparse
import glob
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from promise_check import (Reference, add_common_arguments, report, scene_names,  # noqa: E402
                           score_frame, tools, write_rows)

SCENES = ("glints", "caustic", "dof")
# Kept aside from every choice of the default (docs/evaluation-notes.md): named with
# --scenes, never run by default.
KEPT_ASIDE = ("interior",)
KNOWN_SCENES = SCENES + KEPT_ASIDE


def blender(*command, log):
    with open(log, "w") as f:
        status = subprocess.run(["blender", "-b", *command], stdout=f, stderr=subprocess.STDOUT)
    return status.returncode


def scene_file(args, scene, d):
    path = os.path.join(d, f"{scene}-{args.resolution}.blend")
    if not os.path.exists(path):
        blender("--factory-startup", "-P",
                os.path.join(ROOT, "bench", "evaluation", "cycles_scenes.py"), "--",
                "--scene", scene, "--resolution", args.resolution, "--save", path,
                log=path + ".log")
        if not os.path.exists(path):
            sys.exit(f"cycles_check: blender did not write {path} (see {path}.log)")
    return path


def passes(args, blend, k, samples, seed, d):
    """K passes of `samples` samples with seeds seed .. seed+K-1 (cached)."""
    files = sorted(glob.glob(os.path.join(d, "pass*-0001.exr")))
    if len(files) < k:
        status = blender(blend, "-P",
                         os.path.join(ROOT, "blender", "statmc_cycles_passes.py"), "--",
                         str(k), d, "--samples", str(samples), "--seed", str(seed),
                         "--adaptive", "off", log=d + ".log")
        files = sorted(glob.glob(os.path.join(d, "pass*-0001.exr")))
        # Blender now and then fails on its way out after writing everything.
        if len(files) < k:
            sys.exit(f"cycles_check: blender wrote {len(files)} of {k} passes into {d} "
                     f"(exit {status}; see {d}.log)")
    return files


def merged(statmc_cli, files, path):
    if not os.path.exists(path):
        subprocess.run([statmc_cli, *files, "--passes", "-o", path + ".part.exr"], check=True,
                       stdout=subprocess.DEVNULL)
        os.replace(path + ".part.exr", path)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_common_arguments(parser, "cycles-check")
    parser.add_argument("--samples", default="4 16", help="samples per pass")
    parser.add_argument("--passes", default="4 8 16", help="passes K")
    parser.add_argument("--seed", type=int, default=1, help="the first pass's seed")
    parser.add_argument("--scenes", default=" ".join(SCENES))
    args = parser.parse_args()
    args.out = os.path.abspath(args.out)  # Blender saves only to absolute paths
    if args.report:
        report(os.path.join(args.out, "results.csv"), args.against)
        return
    if not shutil.which("blender"):
        sys.exit("cycles_check: blender is not installed (apt-get install blender)")
    statmc, statmc_cli, methods = tools(args)
    ks = [int(k) for k in args.passes.split()]
    rows = []
    for scene in scene_names(args.scenes, KNOWN_SCENES, "cycles_check"):
        d = os.path.join(args.out, scene)
        os.makedirs(d, exist_ok=True)
        blend = scene_file(args, scene, d)
        ref_dir = os.path.join(d, f"reference-{args.ref_spp}")
        reference = Reference(statmc, merged(
            statmc_cli, passes(args, blend, 4, args.ref_spp // 4, 100000, ref_dir),
            ref_dir + ".exr"))
        for samples in [int(s) for s in args.samples.split()]:
            pass_dir = os.path.join(d, f"passes-{samples}spp-seed{args.seed}")
            files = passes(args, blend, max(ks), samples, args.seed, pass_dir)
            for k in ks:
                noisy = merged(statmc_cli, files[:k], f"{pass_dir}-K{k}.exr")
                rows += score_frame(statmc, methods, noisy, f"{pass_dir}-K{k}", reference,
                                    {"scene": scene, "spp": k * samples,
                                     "cell": f"K={k} x {samples}"},
                                    statmc_cli if args.oidn else None)
    write_rows(os.path.join(args.out, "results.csv"), rows)


if __name__ == "__main__":
    main()
