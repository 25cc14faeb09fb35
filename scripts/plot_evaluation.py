#!/usr/bin/python3
"""Charts and the report of docs/evaluation.md from statmc-evaluate's CSV files.

Usage: plot_evaluation.py results.csv timing.csv --ref-spp N [--tungsten check.txt ...]
                          --images DIR --report FILE
"""
import argparse
import csv
import os
import statistics
from collections import defaultdict

from evaluation_report import write_report

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ["noisy", "statmc", "statmc-noguides", "statmc-classic", "statmc-paper", "classic+ici",
           "classic+guide-noise", "classic+context",
           "moon-ci", "nlm",
           "cross-bilateral", "oidn", "oidn-guides", "verified-oidn-guides"]
LABELS = {
    "noisy": "noisy input",
    "statmc": "statmc default (albedo + normal)",
    "statmc-noguides": "statmc default (no guides)",
    "statmc-classic": "statmc classic: the default before the ladder (albedo + normal)",
    "statmc-paper": "statmc, paper's filter (method=paper, no guides)",
    "classic+ici": "classic + the default's ICI ladder alone",
    "classic+guide-noise": "classic + the default's guide-noise correction alone",
    "classic+context": "classic + the default's context test alone",
    "moon-ci": "Moon-CI style (plain test, α = 0.002)",
    "nlm": "NL-means, per-pixel variance (Rousselle 2012)",
    "cross-bilateral": "cross-bilateral on albedo + normal",
    "oidn": "OIDN 2 (pyoidn, CPU, colour only)",
    "oidn-guides": "OIDN 2 (pyoidn, CPU, colour + albedo + normal)",
    "verified-oidn-guides": "OIDN 2 with guides, verified by statmc (`--dup --oidn --verify`; "
                            "its time is OIDN's and the verify step's)",
}
# The charts draw these; the tables list every method.
CHART_METHODS = ["noisy", "statmc", "statmc-classic", "statmc-paper", "nlm", "cross-bilateral",
                 "oidn-guides", "verified-oidn-guides"]
# Not a method: what the reference's own sampling noise adds to every row's error (its
# variance of the mean, from the reference's statistics; bench/evaluation/evaluate.cpp).
REFERENCE_NOISE = "reference-noise"
STATMC = [m for m in METHODS if m.startswith("statmc") or m.startswith("classic+")]
METRICS = [("relmse", "relMSE, less the reference's share"), ("dssim", "DSSIM (Filmic view)"),
           ("mse", "MSE, less the reference's share"),
           ("energy", "light in the highlight windows, over the reference's"), ("mae", "MAE")]
# Metrics from which the reference's own share (its variance of the mean) is taken out: the
# noisy frames' seeds are not the reference's, so E[(x − ref)²] is the error against the
# truth plus that share, and the difference is unbiased.
LESS_SHARE = ("mse", "relmse")
# Energy is kept where it is no more than this much further from 1 than the noisy input's.
ENERGY_SLACK = 0.05


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def grouped(rows):
    """(scene, method, spp) -> list of rows over seeds."""
    out = defaultdict(list)
    for r in rows:
        out[(r["scene"], r["method"], int(r["spp"]))].append(r)
    return out


def mean_of(rows, key):
    return statistics.fmean(float(r[key]) for r in rows)


def value(g, scene, method, spp, metric):
    """The mean over seeds of a cell's metric, less the reference's share for LESS_SHARE."""
    v = mean_of(g[(scene, method, spp)], metric)
    floor = g.get((scene, REFERENCE_NOISE, spp))
    if metric in LESS_SHARE and floor:
        v -= mean_of(floor, metric)
    return v


def best_of(vals, metric):
    return min(vals, key=lambda m: abs(vals[m] - 1) if metric == "energy" else vals[m])


def total_seconds(rows):
    return statistics.fmean(float(r["render_seconds"]) + float(r["denoise_seconds"]) for r in rows)


def error_vs_time(rows, scene, metric, label, path):
    g = grouped(rows)
    spps = sorted({k[2] for k in g if k[0] == scene})
    plt.figure(figsize=(6.4, 4.2))
    for m in CHART_METHODS:
        pts = [(total_seconds(g[(scene, m, s)]), value(g, scene, m, s, metric))
               for s in spps if (scene, m, s) in g]
        if pts:
            xs, ys = zip(*pts)
            style = "k--" if m == "noisy" else "-o"
            plt.plot(xs, ys, style, label=LABELS[m], markersize=3)
    plt.xscale("log")
    plt.yscale("log")
    plt.xlabel("render + denoise time (s)")
    plt.ylabel(label)
    plt.title(f"{scene}: {label} against time (spp {spps[0]}…{spps[-1]})")
    plt.grid(True, which="both", alpha=0.3)
    plt.legend(fontsize=7)
    plt.tight_layout()
    plt.savefig(path, dpi=90)
    plt.close()


def timing_chart(rows, path):
    plt.figure(figsize=(6.4, 4.2))
    by_res = defaultdict(list)
    for r in rows:
        by_res[(int(r["width"]), int(r["height"]))].append((int(r["radius"]), float(r["denoise_seconds"])))
    for (w, h), pts in sorted(by_res.items()):
        pts.sort()
        plt.plot([p[0] for p in pts], [p[1] * 1000 for p in pts], "-o", label=f"{w}×{h}")
    plt.yscale("log")
    plt.xlabel("radius r (px)")
    plt.ylabel("denoise time (ms), whole operator")
    plt.title("statmc denoise time against radius and resolution")
    plt.grid(True, which="both", alpha=0.3)
    plt.legend()
    plt.tight_layout()
    plt.savefig(path, dpi=90)
    plt.close()


def table(rows, scene, metric):
    g = grouped(rows)
    spps = sorted({k[2] for k in g if k[0] == scene})
    lines = ["| method | " + " | ".join(f"{s} spp" for s in spps) + " |",
             "| --- |" + " --- |" * len(spps)]
    for m in METHODS:
        if not any((scene, m, s) in g for s in spps):
            continue
        best = []
        for s in spps:
            vals = {mm: value(g, scene, mm, s, metric) for mm in METHODS if mm != "noisy" and (scene, mm, s) in g}
            best.append(best_of(vals, metric) if vals else None)
        cells = []
        for s, b in zip(spps, best):
            v = value(g, scene, m, s, metric)
            cells.append(f"**{v:.4g}**" if m == b else f"{v:.4g}")
        lines.append(f"| {LABELS[m]} | " + " | ".join(cells) + " |")
    floor = [g.get((scene, REFERENCE_NOISE, s)) for s in spps]
    if metric in LESS_SHARE and all(floor):
        lines.append("| *the reference's share, taken out of every row above* | " +
                     " | ".join(f"*{mean_of(f, metric):.4g}*" for f in floor) + " |")
    return "\n".join(lines)


def time_table(rows, scene):
    g = grouped(rows)
    spps = sorted({k[2] for k in g if k[0] == scene})
    lines = ["| | " + " | ".join(f"{s} spp" for s in spps) + " |", "| --- |" + " --- |" * len(spps)]
    lines.append("| render (s) | " + " | ".join(f"{mean_of(g[(scene, 'noisy', s)], 'render_seconds'):.2f}" for s in spps) + " |")
    for m in METHODS[1:]:
        if all((scene, m, s) in g for s in spps):
            lines.append(f"| {LABELS[m]} (s) | " + " | ".join(f"{mean_of(g[(scene, m, s)], 'denoise_seconds'):.3f}" for s in spps) + " |")
    return "\n".join(lines)


def equal_time(rows, scene, budget_spp):
    """Each method at the most samples it can afford within the render time of budget_spp
    samples for the noisy input (render + denoise ≤ 1.05 × that)."""
    g = grouped(rows)
    spps = sorted({k[2] for k in g if k[0] == scene})
    if (scene, "noisy", budget_spp) not in g:
        return ""
    budget = total_seconds(g[(scene, "noisy", budget_spp)])
    lines = [f"Equal time: each method at the most samples whose render + denoise fits in "
             f"{budget:.2f} s (the {budget_spp}-spp render):", "",
             "| method | spp | time (s) | relMSE | DSSIM |", "| --- | --- | --- | --- | --- |"]
    for m in METHODS:
        fits = [s for s in spps if (scene, m, s) in g and total_seconds(g[(scene, m, s)]) <= 1.05 * budget]
        if not fits:
            lines.append(f"| {LABELS[m]} | — | — | — | — |")
            continue
        s_ = max(fits)
        r = g[(scene, m, s_)]
        lines.append(f"| {LABELS[m]} | {s_} | {total_seconds(r):.2f} | {value(g, scene, m, s_, 'relmse'):.4g} | {mean_of(r, 'dssim'):.4g} |")
    return "\n".join(lines)


def equal_time_chart(rows, scene, budget_spp, path):
    """Bars: each method's relMSE and DSSIM at the most samples it affords in the time of
    the budget_spp render (as equal_time's table)."""
    g = grouped(rows)
    if (scene, "noisy", budget_spp) not in g:
        return False
    budget = total_seconds(g[(scene, "noisy", budget_spp)])
    spps = sorted({k[2] for k in g if k[0] == scene})
    names, rel, dssim = [], [], []
    for m in METHODS:
        fits = [s for s in spps if (scene, m, s) in g and total_seconds(g[(scene, m, s)]) <= 1.05 * budget]
        if fits:
            r = g[(scene, m, max(fits))]
            names.append(f"{m}\n{max(fits)} spp")
            rel.append(value(g, scene, m, max(fits), "relmse"))
            dssim.append(mean_of(r, "dssim"))
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    for ax, vals, label in ((axes[0], rel, "relMSE"), (axes[1], dssim, "DSSIM")):
        ax.bar(range(len(vals)), vals, color=["0.6"] + ["C%d" % i for i in range(len(vals) - 1)])
        ax.set_xticks(range(len(vals)))
        ax.set_xticklabels(names, fontsize=6, rotation=30, ha="right")
        ax.set_yscale("log")
        ax.set_ylabel(label)
        ax.grid(True, axis="y", which="both", alpha=0.3)
    fig.suptitle(f"{scene}: equal time ({budget:.2f} s, the {budget_spp}-spp render)")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return True


def wins(rows):
    """Per scene, spp and metric, which method does best and the best of statmc's."""
    g = grouped(rows)
    out = []
    for scene in sorted({k[0] for k in g}):
        for s in sorted({k[2] for k in g if k[0] == scene}):
            for metric, _ in METRICS[:4]:
                vals = {m: value(g, scene, m, s, metric) for m in METHODS
                        if m != "noisy" and (scene, m, s) in g}
                best = best_of(vals, metric)
                ours = {m: vals[m] for m in STATMC if m in vals}
                out.append((scene, s, metric, best, vals[best], vals[best_of(ours, metric)]))
    return out


def verdict(g, scene, s, method, other, metric, factor=1.0):
    """'yes (a / b)' where `method` is at least as good as `other` (× factor) in the cell."""
    if (scene, other, s) not in g or (scene, method, s) not in g:
        return "—"
    a, b = value(g, scene, method, s, metric), value(g, scene, other, s, metric)
    if metric == "energy":  # kept: no more than ENERGY_SLACK further from 1 than the other
        ok = abs(a - 1) <= abs(b - 1) + ENERGY_SLACK
    else:
        ok = a <= factor * b
    return f"{'yes' if ok else '**no**'} ({a:.3g} / {b:.3g})"


def falls(g, scene, method, metric, spps):
    vals = [value(g, scene, method, s, metric) for s in spps]
    ok = all(b < a for a, b in zip(vals, vals[1:]))
    return f"{metric} {'yes' if ok else '**no**'} ({' → '.join(f'{v:.3g}' for v in vals)})"


def targets(rows):
    """The promise per cell (docs/evaluation-notes.md): the default against the noisy input
    and OIDN, and whether its error falls with spp."""
    g = grouped(rows)
    lines = ["| scene | spp | relMSE ≤ noisy | MSE ≤ noisy | DSSIM ≤ noisy | energy kept | "
             "MSE ≤ OIDN (guides) | relMSE ≤ OIDN (guides) |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    for scene in sorted({k[0] for k in g}):
        spps = sorted({k[2] for k in g if k[0] == scene and (scene, "statmc", k[2]) in g})
        for s in spps:
            cells = [verdict(g, scene, s, "statmc", "noisy", m)
                     for m in ("relmse", "mse", "dssim", "energy")]
            cells += [verdict(g, scene, s, "statmc", "oidn-guides", m) for m in ("mse", "relmse")]
            lines.append(f"| {scene} | {s} | " + " | ".join(cells) + " |")
        lines.append(f"| {scene} | all | falls with spp: " +
                     "; ".join(falls(g, scene, "statmc", m, spps) for m in ("relmse", "mse", "dssim")) +
                     " | | | | | |")
    return "\n".join(lines)


def verified_targets(rows):
    """Verified OIDN's targets per cell (docs/evaluation-notes.md): relMSE within 5% of the
    better of OIDN and the default, MSE at or below the noisy input's, the light kept."""
    g = grouped(rows)
    v = "verified-oidn-guides"
    lines = ["| scene | spp | relMSE ≤ 1.05 × OIDN (guides) | relMSE ≤ 1.05 × default | "
             "MSE ≤ noisy | energy kept |", "| --- | --- | --- | --- | --- | --- |"]
    for scene in sorted({k[0] for k in g}):
        spps = sorted({k[2] for k in g if k[0] == scene and (scene, v, k[2]) in g})
        if not spps:
            continue
        for s in spps:
            cells = [verdict(g, scene, s, v, "oidn-guides", "relmse", 1.05),
                     verdict(g, scene, s, v, "statmc", "relmse", 1.05),
                     verdict(g, scene, s, v, "noisy", "mse"),
                     verdict(g, scene, s, v, "noisy", "energy")]
            lines.append(f"| {scene} | {s} | " + " | ".join(cells) + " |")
        lines.append(f"| {scene} | all | falls with spp: " +
                     "; ".join(falls(g, scene, v, m, spps) for m in ("relmse", "mse")) + " | | | |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("results")
    ap.add_argument("timing")
    ap.add_argument("--ref-spp", type=int, required=True)
    ap.add_argument("--runs", type=int, default=3, help="timed runs behind each denoise time")
    ap.add_argument("--tungsten", nargs="*", default=[])
    ap.add_argument("--images", required=True)
    ap.add_argument("--report", required=True)
    a = ap.parse_args()
    rows, timing = read(a.results), read(a.timing)
    os.makedirs(a.images, exist_ok=True)
    rel = os.path.relpath(a.images, os.path.dirname(os.path.abspath(a.report)))
    scenes = sorted({r["scene"] for r in rows})
    seeds = sorted({r["seed"] for r in rows})
    res = {r["scene"]: f'{r["width"]}×{r["height"]}' for r in rows}

    doc = ["# Evaluation: accuracy against time, and where statmc loses", "",
           "Generated by `bash scripts/evaluate.sh` (statmc-evaluate + scripts/plot_evaluation.py);",
           "do not edit by hand. Each figure is the mean over seeds " + ", ".join(seeds) +
           f"; references are statmc-render at {a.ref_spp} spp (seed 1000).", "",
           "Methods: " + "; ".join(f"**{m}** — {LABELS[m]}" for m in METHODS) + ". statmc's filter runs",
           "at its defaults (r = 20, α = 0.005, σ_s = 10, firefly guard κ = 256; the default adds the",
           "ICI ladder at α = 0.005 with variances moderated at d₀ = 16 towards neighbours of the same mean (t-test at α = 0.05),",
           "the guide-noise correction, the context test over 3×3 boxes and the energy and residual checks over 7×7 windows, docs/method.md §5, §10–11, §16–17); the baselines at the",
           "parameters in `bench/evaluation/baselines/baselines.h` (NL-means: search 10, patch 3, k = 0.45;",
           "cross-bilateral: r = 10, σ_s = 4, σ_a = 0.1, σ_n = 0.2). Render time is statmc-render's",
           f"(2 threads); denoise time is the median of {a.runs} run(s) of the whole operator on this 2-core",
           "machine, reading planes already in memory. DSSIM is on luminance after the OCIO Filmic",
           "view of the shipped config.", ""]
    if a.tungsten:
        doc += ["## The references against Tungsten's", "",
                "Our references compared with the Tungsten renders in `../shared/scenes`, resampled",
                "to our resolution (`statmc --compare`):", ""]
        for t in a.tungsten:
            scene = os.path.basename(os.path.dirname(t))
            with open(t) as f:
                vals = " · ".join(line.strip() for line in f if line.startswith("  "))
            doc.append(f"- {scene}: {vals}")
        doc += ["", "Veach Ajar's pbrt file has a rough-metal floor where Tungsten's render shows a",
                "diffuse one, so that comparison is expected to differ (renderer/README.md).", ""]
    doc += ["## The default against its targets", "",
            "Each cell: yes/no, then (the default's value / the other's). MSE and relMSE are "
            "less the reference's share; energy is kept where it is no more than "
            f"{ENERGY_SLACK:g} further from 1 than the other's.", "", targets(rows), ""]
    verified = verified_targets(rows)
    if verified.count("\n") > 1:
        doc += ["## Verified OIDN against its targets", "",
                "Each cell: yes/no, then (verified OIDN's value / the other's).", "", verified, ""]
    doc += ["## Who wins", "",
            "Energy: nearest 1 wins. MSE and relMSE less the reference's share.", "",
            "| scene | spp | metric | best method | its value | best statmc |",
            "| --- | --- | --- | --- | --- | --- |"]
    for scene, s, metric, best, v, st in wins(rows):
        doc.append(f"| {scene} | {s} | {metric} | {best} | {v:.4g} | {st:.4g} |")
    doc.append("")
    for scene in scenes:
        doc += [f"## {scene} ({res[scene]})", ""]
        for metric, label in METRICS[:3]:
            img = f"eval-{scene}-{metric}.png"
            error_vs_time(rows, scene, metric, label, os.path.join(a.images, img))
            doc += [f"![{scene} {label}]({rel}/{img})", ""]
        for metric, label in METRICS:
            best = "nearest 1" if metric == "energy" else "lowest"
            doc += [f"{label} ({best} denoised value in bold):", "", table(rows, scene, metric), ""]
        doc += ["Time:", "", time_table(rows, scene), ""]
        spps = sorted({int(r["spp"]) for r in rows if r["scene"] == scene})
        budget_spp = spps[len(spps) // 2]
        img = f"eval-{scene}-equal-time.png"
        if equal_time_chart(rows, scene, budget_spp, os.path.join(a.images, img)):
            doc += [f"![{scene} at equal time]({rel}/{img})", ""]
        doc += [equal_time(rows, scene, budget_spp), ""]
    timing_chart(timing, os.path.join(a.images, "eval-timing.png"))
    doc += ["## Denoise time against resolution and radius", "",
            f"![denoise time]({rel}/eval-timing.png)", "",
            "| resolution | " + " | ".join(f"r = {r}" for r in sorted({int(t['radius']) for t in timing})) + " |",
            "| --- |" + " --- |" * len({t['radius'] for t in timing})]
    by_res = defaultdict(dict)
    for t in timing:
        by_res[(int(t["width"]), int(t["height"]))][int(t["radius"])] = float(t["denoise_seconds"])
    for (w, h), d in sorted(by_res.items()):
        doc.append(f"| {w}×{h} | " + " | ".join(f"{d[r] * 1000:.0f} ms" for r in sorted(d)) + " |")
    doc.append("")
    write_report(a.report, doc, "evaluation-notes.md")


if __name__ == "__main__":
    main()
