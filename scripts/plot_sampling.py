#!/usr/bin/python3
"""Charts and tables of docs/sampling.md from the CSVs of scripts/sampling_bench.sh.

usage: /usr/bin/python3 scripts/plot_sampling.py CSV_DIR IMAGE_DIR

Per configuration and iteration, cost and relative variance are averaged over the runs and
efficiency is 1 / (mean cost x mean relative variance); the headline ratios average those
over iterations (all of them, and from the second on, when the estimates exist)."""
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = defaultdict(list)
    with open(path) as f:
        for r in csv.DictReader(f):
            rows[r["label"]].append({k: (v if k == "label" else float(v)) for k, v in r.items()})
    return rows


def per_iteration(rows):
    """iteration -> mean over runs of cost, rel_var, relmse, elapsed, total_spp."""
    by_it = defaultdict(list)
    for r in rows:
        by_it[int(r["iteration"])].append(r)
    out = []
    for it in sorted(by_it):
        rs = by_it[it]
        m = {k: sum(r[k] for r in rs) / len(rs)
             for k in ("cost", "rel_var", "relmse", "relmse_trimmed", "cpu_elapsed", "total_spp")}
        m["iteration"] = it
        m["runs"] = len(rs)
        m["efficiency"] = 1.0 / (m["cost"] * m["rel_var"])
        out.append(m)
    return out


def mean(xs):
    return sum(xs) / len(xs)


def summary(its, first=0):
    sel = [m for m in its if m["iteration"] >= first]
    return {k: mean([m[k] for m in sel]) for k in ("cost", "rel_var", "efficiency")}


def ratio_table(its, heading):
    """ACRR against classic RR: cost, relative variance and efficiency ratios, averaged over
    all iterations and over those with estimates."""
    print("### %s (%d runs)\n" % (heading, its["classic"][0]["runs"]))
    print("| averaged over | cost ratio | rel. variance ratio (classic / ACRR) | efficiency ratio |")
    print("|---|---|---|---|")
    for first, what in ((0, "all iterations"), (1, "iterations 2..")):
        c, a = summary(its["classic"], first), summary(its["acrr"], first)
        print("| %s | x%.2f | ÷%.2f | x%.2f |" % (what, a["cost"] / c["cost"], c["rel_var"] / a["rel_var"],
                                                 a["efficiency"] / c["efficiency"]))


def ajar(csv_dir, img_dir):
    data = read(os.path.join(csv_dir, "ajar_efficiency.csv"))
    its = {k: per_iteration(v) for k, v in data.items()}
    fig, axes = plt.subplots(1, 3, figsize=(10, 3))
    for label, colour in (("classic", "tab:blue"), ("acrr", "tab:red")):
        x = [m["iteration"] + 1 for m in its[label]]
        for ax, key in zip(axes, ("efficiency", "cost", "rel_var")):
            ax.plot(x, [m[key] for m in its[label]], color=colour, label=label)
    for ax, title in zip(axes, ("efficiency 1/(cost x rel. var.)", "cost [CPU s / sample]", "rel. variance / sample")):
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("iteration (4 spp each)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_yscale("log")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(img_dir, "sampling_ajar_efficiency.png"), dpi=80)
    ratio_table(its, "Veach Ajar: ACRR vs classic RR")
    for label in ("classic", "acrr"):
        s = summary(its[label])
        print("\n%s: cost %.3g s/sample, rel. variance %.3g, efficiency %.3g, final relMSE %.4g in %.2f CPU s"
              % (label, s["cost"], s["rel_var"], s["efficiency"], its[label][-1]["relmse"], its[label][-1]["cpu_elapsed"]))
    print()
    return its


def sweep(csv_dir, img_dir, name, baseline, baseline_label, first, what, image, heading):
    """A tracked-bounce sweep (seed Figs. S1, S3): error against CPU time per number tracked,
    and the mean efficiency (iterations `first`..) relative to `baseline`'s."""
    data = read(os.path.join(csv_dir, name))
    labels = sorted(data, key=lambda s: int(s[4:]))
    b_eff = summary(baseline, first)["efficiency"]
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.2))
    cmap = plt.get_cmap("viridis")
    print("### %s\n" % heading)
    print("| tracked %s | CPU time [s] | relMSE | trimmed relMSE | trimmed relMSE x time "
          "| mean efficiency / %s's |" % (what, baseline_label))
    print("|---|---|---|---|---|---|")
    ratios = []
    for i, label in enumerate(labels):
        its = per_iteration(data[label])
        axes[0].loglog([m["cpu_elapsed"] for m in its], [m["relmse_trimmed"] for m in its],
                       color=cmap(i / max(1, len(labels) - 1)), label=label[4:])
        last = its[-1]
        ratio = summary(its, first)["efficiency"] / b_eff
        ratios.append((int(label[4:]), ratio))
        print("| %s | %.2f | %.4g | %.4g | %.4g | %.2f |" % (label[4:], last["cpu_elapsed"], last["relmse"],
                                                          last["relmse_trimmed"],
                                                          last["relmse_trimmed"] * last["cpu_elapsed"], ratio))
    last = baseline[-1]
    axes[0].loglog([m["cpu_elapsed"] for m in baseline], [m["relmse_trimmed"] for m in baseline], "k--",
                   label=baseline_label)
    print("| %s (%d runs) | %.2f | %.4g | %.4g | %.4g | 1 |\n" % (
        baseline_label, last["runs"], last["cpu_elapsed"], last["relmse"], last["relmse_trimmed"],
        last["relmse_trimmed"] * last["cpu_elapsed"]))
    axes[0].set_xlabel("CPU time [s]", fontsize=8)
    axes[0].set_ylabel("relMSE (0.1% largest errors dropped)", fontsize=8)
    axes[0].set_title("error vs time", fontsize=9)
    axes[0].legend(fontsize=6, ncol=3, title="tracked", title_fontsize=6)
    axes[1].plot([p[0] for p in ratios], [p[1] for p in ratios], "o-")
    axes[1].axhline(1, color="k", ls="--", label=baseline_label)
    axes[1].set_xlabel("tracked " + what, fontsize=8)
    axes[1].set_title("mean efficiency relative to " + baseline_label, fontsize=9)
    axes[1].legend(fontsize=7)
    for ax in axes:
        ax.tick_params(labelsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(img_dir, image), dpi=80)


def mis(csv_dir, img_dir):
    data = read(os.path.join(csv_dir, "mis_equal_time.csv"))
    fig, ax = plt.subplots(figsize=(5, 3.2))
    print("### Veach MIS: SMIS vs standard MIS at equal CPU time (8-spp iterations, 12 CPU s)\n")
    print("| MIS | runs | spp reached | CPU time [s] | final relMSE | trimmed relMSE | mean efficiency |")
    print("|---|---|---|---|---|---|---|")
    for label, colour in (("standard", "tab:blue"), ("selective", "tab:red")):
        rows = data[label]
        runs = sorted({int(r["run"]) for r in rows})
        finals = [max((r for r in rows if int(r["run"]) == k), key=lambda r: r["iteration"]) for k in runs]
        for k in runs:
            rr = [r for r in rows if int(r["run"]) == k]
            ax.loglog([r["cpu_elapsed"] for r in rr], [r["relmse_trimmed"] for r in rr], color=colour, alpha=0.7,
                      label=label if k == 0 else None)
        eff = mean([1.0 / (r["cost"] * r["rel_var"]) for r in rows if r["iteration"] >= 1])
        print("| %s | %d | %.0f | %.2f | %.4g | %.4g | %.3g |" % (
            label, len(runs), mean([f["total_spp"] for f in finals]), mean([f["cpu_elapsed"] for f in finals]),
            mean([f["relmse"] for f in finals]), mean([f["relmse_trimmed"] for f in finals]), eff))
    print()
    ax.set_xlabel("CPU time [s]", fontsize=8)
    ax.set_ylabel("relMSE (0.1% largest errors dropped)", fontsize=8)
    ax.set_title("Veach MIS: error vs CPU time", fontsize=9)
    ax.tick_params(labelsize=7)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(img_dir, "sampling_mis_equal_time.png"), dpi=80)


def progressive(csv_dir, name, title, baseline, other):
    """Per-configuration totals of a progressive-schedule run: time, error, and the spp
    `other` would reach in `baseline`'s time at its own rate."""
    data = read(os.path.join(csv_dir, name))
    print("### %s\n" % title)
    print("| config | runs | spp | CPU time [s] | denoising (wall) [s] | final relMSE | trimmed relMSE | relMSE x time |")
    print("|---|---|---|---|---|---|---|---|")
    totals = {}
    for label in (baseline, other):
        rows = data[label]
        runs = sorted({int(r["run"]) for r in rows})
        finals = [max((r for r in rows if int(r["run"]) == k), key=lambda r: r["iteration"]) for k in runs]
        t = mean([f["cpu_elapsed"] for f in finals])
        d = mean([sum(r.get("denoise_seconds", 0) for r in rows if int(r["run"]) == k) for k in runs])
        e = mean([f["relmse"] for f in finals])
        et = mean([f["relmse_trimmed"] for f in finals])
        spp = finals[0]["total_spp"]
        totals[label] = (spp, t, e)
        print("| %s | %d | %.0f | %.2f | %.2f | %.4g | %.4g | %.4g |" % (label, len(runs), spp, t, d, e, et, e * t))
    (spp_b, t_b, e_b), (spp_o, t_o, e_o) = totals[baseline], totals[other]
    print("\n%s: CPU time x%.2f, relMSE x%.2f at equal spp; in %s's %.2f CPU s it would reach %.0f spp "
          "(%s: %.0f)\n" % (other, t_o / t_b, e_o / e_b, baseline, t_b, spp_o * t_b / t_o, baseline, spp_b))


def breakdown(csv_dir, name, title):
    """Where a configuration's render time goes, per camera sample, from the time stamp
    counters of bench_sampling --breakdown (averaged over runs)."""
    path = os.path.join(csv_dir, name)
    if not os.path.exists(path):
        return
    data = read(path)
    print("### %s\n" % title)
    print("| config | rays / sample | shadow rays / sample | cycles / sample: closest hit | shadow rays "
          "| per-bounce statistics | shading, sampling, film | all | denoising the estimates, share of wall time |")
    print("|---|---|---|---|---|---|---|---|---|")
    for label, rows in data.items():
        tot = {k: sum(r[k] for r in rows) for k in rows[0] if k not in ("label", "run")}
        n = tot["samples"]
        rest = tot["tile_cycles"] - tot["trace_cycles"] - tot["shadow_cycles"] - tot["bounce_cycles"]
        print("| %s | %.2f | %.2f | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f%% |" % (
            label, (tot["rays"] - tot["shadow_rays"]) / n, tot["shadow_rays"] / n, tot["trace_cycles"] / n,
            tot["shadow_cycles"] / n, tot["bounce_cycles"] / n, rest / n, tot["tile_cycles"] / n,
            100 * tot["denoise_seconds"] / tot["seconds"]))
    print()


def radius(csv_dir):
    """The per-bounce filter's radius, one batch at 640x360 (sampling_bench.sh section 6)."""
    path = os.path.join(csv_dir, "radius_ajar.csv")
    if not os.path.exists(path):
        return
    ajar_its = {k: per_iteration(v) for k, v in read(path).items()}
    c = ajar_its["classic"]
    print("### The per-bounce filter's radius (640x360, one batch, 2 runs each)\n")
    print("| config | efficiency / classic RR's (all; iterations 2..) | rel. variance ratio | cost ratio |")
    print("|---|---|---|---|")
    for label in sorted(k for k in ajar_its if k != "classic"):
        a, a1 = summary(ajar_its[label]), summary(ajar_its[label], 1)
        cc, cc1 = summary(c), summary(c, 1)
        print("| %s | x%.2f; x%.2f | ÷%.2f | x%.2f |" % (label, a["efficiency"] / cc["efficiency"],
                                                      a1["efficiency"] / cc1["efficiency"],
                                                      cc["rel_var"] / a["rel_var"], a["cost"] / cc["cost"]))
    print()
    breakdown(csv_dir, "radius_breakdown.csv", "The same batch: where the time goes")
    mis_rows = read(os.path.join(csv_dir, "radius_mis.csv"))
    for label in sorted(k for k in mis_rows if k != "standard"):
        progressive(csv_dir, "radius_mis.csv", "The same batch: Veach MIS, " + label, "standard", label)


def main():
    csv_dir, img_dir = sys.argv[1], sys.argv[2]
    os.makedirs(img_dir, exist_ok=True)
    its = ajar(csv_dir, img_dir)
    progressive(csv_dir, "ajar_progressive.csv", "Veach Ajar, progressive schedule to 256 spp", "classic", "acrr")
    sweep(csv_dir, img_dir, "ajar_sweep.csv", its["classic"], "classic RR", 0, "bounces",
          "sampling_bounce_sweep.png", "Tracked-bounce sweep (Veach Ajar, ACRR, 32 x 4 spp, 2 runs each)")
    progressive(csv_dir, "mis_progressive.csv", "Veach MIS, progressive schedule to 512 spp", "standard",
                "selective")
    mis(csv_dir, img_dir)
    standard = per_iteration(read(os.path.join(csv_dir, "mis_progressive.csv"))["standard"])
    sweep(csv_dir, img_dir, "mis_sweep.csv", standard, "standard MIS", 1, "vertices", "sampling_mis_sweep.png",
          "SMIS tracked-vertex sweep (Veach MIS, progressive to 512 spp, 2 runs each; efficiency from iteration 2)")
    breakdown(csv_dir, "ajar_breakdown.csv", "Where the time goes: Veach Ajar, 160x90, 32 x 4 spp")
    breakdown(csv_dir, "big_breakdown.csv", "Where the time goes at 640x360: Veach Ajar (32 x 4 spp) "
              "and Veach MIS (progressive to 128 spp)")
    radius(csv_dir)
    big = os.path.join(csv_dir, "big_efficiency.csv")
    if os.path.exists(big):
        ratio_table({k: per_iteration(v) for k, v in read(big).items()},
                    "Veach Ajar at 640x360: ACRR vs classic RR")
        print()
    if os.path.exists(os.path.join(csv_dir, "big_mis.csv")):
        progressive(csv_dir, "big_mis.csv", "Veach MIS at 640x360, progressive schedule to 128 spp", "standard",
                    "selective")


if __name__ == "__main__":
    main()
