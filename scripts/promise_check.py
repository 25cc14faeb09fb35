"""The promise, checked on frames the evaluation does not tune on (docs/evaluation-notes.md:
"Verified OIDN on the promise check", "Scenes kept aside", "The frame's light"): the
evaluation's scenes at another resolution and other seeds, every sample count from 4 to
256, against long references whose own noise is subtracted. For each method and cell it
reports MSE, relMSE and DSSIM, the energy kept in windows around emitters and highlights,
and the light kept by the frame as a whole, beside the noisy input's.

Not part of CI: renders are cached in OUT and reused.

    python3 scripts/promise_check.py                       # this build's default and classic
    python3 scripts/promise_check.py --method before=OTHER_BUILD/oiiotool_ext/statmc   # another build too
    python3 scripts/promise_check.py --report --against default   # each method over the default

A method is NAME=STATMC[:MODIFIERS]; the default list is default=build's statmc,
classic=build's statmc with method=classic. A chain is NAME=COMMANDS, the build's statmc
running them between the noisy frame and -o (e.g. oidn="--oidn:guides=0"); --oidn adds OIDN
with guides, OIDN on the colour alone, and OIDN verified (--dup --oidn --verify), which need
the OIDN library (STATMC_OIDN_LIBRARY, docs/method.md §15), and verifies the reference itself
in every cell: --report prints the share of pixels verify rejected of each.
"""

import argparse
import csv
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from image_metrics import EPS  # noqa: E402

SCENES = {
    "cornell-box": "../shared/scenes/cornell-box/scene.pbrt",
    "veach-mis": "../shared/scenes/veach-mis/scene.pbrt",
    "veach-ajar": "../shared/scenes/veach-ajar/scene.pbrt",
    "caustic-corner": "bench/evaluation/scenes/caustic-corner/scene.pbrt",
}
# Scenes kept aside from every choice of the default (docs/evaluation-notes.md): named with
# --scenes, never run by default.
KEPT_ASIDE = {
    "lamp-shelf": "bench/evaluation/scenes/lamp-shelf/scene.pbrt",
}
KNOWN_SCENES = {**SCENES, **KEPT_ASIDE}


def scene_names(names, known, tool):
    """The scenes of `--scenes`, every one checked against `known` before any is rendered."""
    scenes = names.split()
    for scene in scenes:
        if scene not in known:
            sys.exit(f"{tool}: no scene {scene!r} (known: {' '.join(known)})")
    return scenes


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def render(args, scene, spp, seed, path):
    if not os.path.exists(path):
        run([args.render, os.path.join(ROOT, KNOWN_SCENES[scene]), "-o", path + ".part.exr",
             "--spp", str(spp), "--resolution", args.resolution, "--seed", str(seed), "-q"])
        os.replace(path + ".part.exr", path)
    return path


def highlight_windows(reference_rgb):
    """Pixels near the reference's brightest: luminance above both its 99.5th percentile and
    4 times its median, grown by 2 pixels within the image (statmc-evaluate's rule too)."""
    lum = reference_rgb @ np.array([0.2126, 0.7152, 0.0722])
    bright = np.pad(lum >= max(np.percentile(lum, 99.5), 4 * np.median(lum)), 2)
    h, w = lum.shape
    grown = np.zeros((h, w), bool)
    for dy in range(5):
        for dx in range(5):
            grown |= bright[dy:dy + h, dx:dx + w]
    return grown


def scores(x, ref, ref_share, window):
    """MSE and relMSE less the reference's own share, the energy ratio in `window`, and the
    whole frame's (light removed or added anywhere, not only around highlights)."""
    d2 = (x - ref) ** 2
    mse = float(d2.mean()) - ref_share["mse"]
    rel = float((d2 / (ref ** 2 + EPS)).mean()) - ref_share["relmse"]
    energy = float(x[window].sum() / max(ref[window].sum(), 1e-12))
    light = float(x.sum() / max(ref.sum(), 1e-12))
    return mse, rel, energy, light


def report(path, against=None):
    """results.csv as markdown: per scene and metric, a row per cell (sample count and seed,
    or passes), a column per method; a method's figure is starred where it is above the noisy
    input's (energy and light: more than 5% further from 1). With `against`, report_against
    instead."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if against:
        report_against(rows, against)
        return
    methods = list(dict.fromkeys(r["method"] for r in rows))
    cells = {(r["scene"], int(r["spp"]), r["cell"], r["method"]): r for r in rows}
    report_rejections(rows)
    for scene in dict.fromkeys(r["scene"] for r in rows):
        keys = sorted({(k[1], k[2]) for k in cells if k[0] == scene})
        for metric in ("mse", "relmse", "dssim", "energy", "light"):
            if metric not in rows[0]:  # results written before the metric was
                continue
            print(f"\n{scene}, {metric}\n")
            print("| spp | cell | " + " | ".join(methods) + " |")
            print("|---" * (len(methods) + 2) + "|")
            for spp, cell in keys:
                noisy = float(cells[(scene, spp, cell, "noisy")][metric])
                out = []
                for m in methods:
                    row = cells.get((scene, spp, cell, m))
                    if row is None:
                        out.append("")
                        continue
                    v = float(row[metric])
                    worse = (abs(v - 1) > abs(noisy - 1) + 0.05 if metric in ("energy", "light")
                             else v > noisy)
                    out.append(f"{v:.4g}" + ("*" if worse and m != "noisy" else ""))
                print(f"| {spp} | {cell} | " + " | ".join(out) + " |")


def by_cell(rows):
    """results.csv's rows by cell, (scene, spp, cell), then by method."""
    cells = {}
    for r in rows:
        cells.setdefault((r["scene"], int(r["spp"]), r["cell"]), {})[r["method"]] = r
    return cells


def report_rejections(rows):
    """Per cell, the share of pixels verify rejected of each verified output and, where it
    was measured, of the reference itself as the candidate."""
    verified = [m for m in dict.fromkeys(r["method"] for r in rows)
                if any(r["method"] == m and r.get("rejected") for r in rows)]
    null = any(r.get("reference_rejected") for r in rows)
    if not verified and not null:
        return
    print("\nverify's rejections (share of pixels)\n")
    print("| scene | spp | cell | " + " | ".join(verified + ["the reference"] * null) + " |")
    print("|---" * (len(verified) + null + 3) + "|")
    for (scene, spp, cell), c in by_cell(rows).items():
        shares = [c[m].get("rejected", "") if m in c else "" for m in verified]
        if null:
            shares.append(next(iter(c.values())).get("reference_rejected", ""))
        print(f"| {scene} | {spp} | {cell} | " +
              " | ".join(f"{float(v):.3%}" if v != "" else "" for v in shares) + " |")


def report_against(rows, base):
    """results.csv's rows against method `base`: per other method and cell, its MSE, relMSE
    and DSSIM over base's, each cell's figures flagged where more than 3% above base's or
    newly above the noisy input's (the accuracy rule for a faster variant, issue 44), and
    the worst."""
    cells = by_cell(rows)
    metrics = ("mse", "relmse", "dssim")
    for method in dict.fromkeys(r["method"] for r in rows):
        if method in (base, "noisy"):
            continue
        print(f"\n{method} / {base}\n")
        print("| scene | spp | cell | MSE | relMSE | DSSIM | flags |")
        print("|---|---|---|---|---|---|---|")
        worst, flagged = dict.fromkeys(metrics, 0.0), 0
        for key, c in sorted(cells.items()):
            if method not in c or base not in c:
                continue
            ratio = {m: float(c[method][m]) / float(c[base][m]) for m in metrics}
            flags = [f"{m} > 1.03" for m in metrics if ratio[m] > 1.03]
            flags += [f"{m} newly above noisy" for m in metrics
                      if float(c[method][m]) > float(c["noisy"][m]) >= float(c[base][m])]
            flagged += bool(flags)
            for m in metrics:
                worst[m] = max(worst[m], ratio[m])
            print(f"| {key[0]} | {key[1]} | {key[2]} | " +
                  " | ".join(f"{ratio[m]:.4f}" for m in metrics) + f" | {', '.join(flags)} |")
        print("\nworst: " + ", ".join(f"{m} {worst[m]:.4f}" for m in metrics) +
              f"; cells flagged: {flagged}")


def method_list(args, statmc_cli):
    """(name, statmc, the commands between the noisy frame and -o) for every method asked."""
    methods = [("default", statmc_cli, ["--denoise"]),
               ("classic", statmc_cli, ["--denoise:method=classic"])]
    if args.no_defaults:
        methods = []
    for text in args.method:
        name, rest = text.split("=", 1)
        exe, _, modifiers = rest.partition(":")
        methods.append((name, exe, ["--denoise" + (":" + modifiers if modifiers else "")]))
    chains = list(args.chain)
    if args.oidn:
        chains += ["oidn=--oidn", "oidn-colour=--oidn:guides=0", "verified=--dup --oidn --verify"]
    for text in chains:
        name, commands = text.split("=", 1)
        methods.append((name, statmc_cli, commands.split()))
    return methods


def add_common_arguments(parser, out_name):
    """The options both checks take: where renders are cached, the build, the frames'
    resolution, the references' sample count, and the methods (method_list)."""
    parser.add_argument("--out", default=os.path.join(ROOT, "build", out_name))
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--resolution", default="320x180")
    parser.add_argument("--ref-spp", type=int, default=4096)
    parser.add_argument("--method", action="append", default=[])
    parser.add_argument("--chain", action="append", default=[])
    parser.add_argument("--oidn", action="store_true")
    parser.add_argument("--no-defaults", action="store_true",
                        help="leave out the default and classic methods")
    parser.add_argument("--report", action="store_true",
                        help="print OUT/results.csv as markdown tables and stop")
    parser.add_argument("--against", metavar="METHOD",
                        help="with --report: every other method's figures over METHOD's")


def tools(args):
    """The build's statmc command, its Python package, and the methods asked for."""
    statmc_cli = os.path.join(args.build, "oiiotool_ext", "statmc")
    sys.path.insert(0, os.path.join(args.build, "python"))
    import statmc
    return statmc, statmc_cli, method_list(args, statmc_cli)


class Reference:
    """A statistics image of a long render: its RGB mean, its own share of MSE and relMSE
    (its variance over its count), and the highlight windows it defines."""

    def __init__(self, statmc, path):
        image = statmc.read_statistics(path)
        self.path = path
        self.rgb = image["beauty"][:, :, :3].astype(np.float64)
        share = image["variance"][:, :, :3] / image["sampleCount"]
        self.share = {"mse": float(share.mean()),
                      "relmse": float((share / (self.rgb ** 2 + EPS)).mean())}
        self.window = highlight_windows(self.rgb)


def score_frame(statmc, methods, noisy_path, prefix, reference, cell, null_with=None):
    """Runs every method on one noisy frame (outputs PREFIX-NAME.exr) and scores them and the
    noisy input against the reference; returns one row per method, `cell`'s keys first.
    A verified output's row holds the share of pixels verify rejected (else ""). With
    `null_with` (a statmc command), the reference itself is verified as the candidate too,
    and every row of the cell holds the share of it rejected (verify's rate on a candidate
    about as right as the frame can be checked against; docs/method.md §15)."""
    outputs = [("noisy", noisy_path)]
    for name, exe, commands in methods:
        out = f"{prefix}-{name}.exr"
        run([exe, noisy_path] + commands + ["-o", out])
        outputs.append((name, out))
    if null_with:
        out = f"{prefix}-reference-verified.exr"
        run([null_with, noisy_path, reference.path, "--verify", "-o", out])
        cell = {**cell, "reference_rejected": rejected_share(statmc.read_statistics(out))}
    rows = []
    for name, path in outputs:
        image = statmc.read_statistics(path)
        x = image["beauty"][:, :, :3].astype(np.float64)
        mse, rel, energy, light = scores(x, reference.rgb, reference.share, reference.window)
        dssim = statmc.compare(path, reference.path).metrics["DSSIM"]
        rows.append({**cell, "method": name, "mse": mse, "relmse": rel, "dssim": dssim,
                     "energy": energy, "light": light, "ref_mse_share": reference.share["mse"],
                     "ref_relmse_share": reference.share["relmse"],
                     "rejected": rejected_share(image)})
        print(f"{cell['scene']:15s} {cell['spp']:5d} {cell['cell']:14s} {name:11s} "
              f"MSE {mse:.4g} relMSE {rel:.4g} DSSIM {dssim:.4f} energy {energy:.3f} "
              f"light {light:.3f}",
              flush=True)
    return rows


def rejected_share(image):
    """verify's statmc:verifyRejected of an output, "" where it was not verified."""
    return image.attributes.get("statmc:verifyRejected", "")


def write_rows(path, rows):
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    add_common_arguments(parser, "promise")
    parser.add_argument("--spps", default="4 16 64 256")
    parser.add_argument("--seeds", default="11 12")
    parser.add_argument("--scenes", default=" ".join(SCENES))
    args = parser.parse_args()
    if args.report:
        report(os.path.join(args.out, "results.csv"), args.against)
        return
    args.render = os.path.join(args.build, "renderer", "statmc-render")
    statmc, statmc_cli, methods = tools(args)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for scene in scene_names(args.scenes, KNOWN_SCENES, "promise_check"):
        d = os.path.join(args.out, scene)
        os.makedirs(d, exist_ok=True)
        reference = Reference(statmc, render(
            args, scene, args.ref_spp, 1000,
            os.path.join(d, f"reference-{args.ref_spp}-{args.resolution}.exr")))
        for spp in [int(s) for s in args.spps.split()]:
            for seed in [int(s) for s in args.seeds.split()]:
                noisy_path = render(args, scene, spp, seed,
                                    os.path.join(d, f"noisy-{args.resolution}-{spp}-{seed}.exr"))
                rows += score_frame(statmc, methods, noisy_path,
                                    os.path.join(d, f"{spp}-{seed}"), reference,
                                    {"scene": scene, "spp": spp, "cell": f"seed {seed}"},
                                    statmc_cli if args.oidn else None)
    write_rows(os.path.join(args.out, "results.csv"), rows)


if __name__ == "__main__":
    main()
