#!/usr/bin/python3
"""scenes.py: the cross-scene study (`make scenes`) -> scenes.md and a figure.

Owns the comparison of the scenes' grids (experiments/rules/scenes.smk renders
Table 1's grid for each scene against our converged render of it):
per scene, the speed-up at equal error (from its equal-error CSV: the
precomputed method's time against the conventional one's at the same relMSE,
with its bootstrap interval), the share of the conventional render spent in
the k-nearest search (its eye pass minus the precomputed eye pass, which
casts the same rays but looks up one representative, over its total; per
cell, median over seeds), and where the precomputed method's error lies: the
mean over seeds of (precomputed - conventional) / reference at one cell,
drawn per scene, with the share of the difference's energy in its
brightest 1% of pixels (1% when spread evenly). The figure is FIGURES/
scenes.png; numbers come from the CSVs named in the footer and the table.
"""

import argparse
import os

import numpy as np
import pandas as pd

from experiments.analysis import metrics
from experiments.analysis import plotting
from experiments.analysis import reference
from experiments.analysis import report
from experiments.analysis.plotting import plt
from experiments.analysis.report import fmt, fmt_ci


def knn_share(table, photons, nn):
    """(share of the conventional total spent in the kNN, (speed-up, lo,
    hi)) at one cell of a table1.csv, paper estimate: the speed-up is
    conventional / precomputed time, the table's paired ratio over seeds
    inverted (geometric mean of the per-seed ratios, 95% t interval); nan
    where the cell or the column is missing."""
    nan3 = (float("nan"),) * 3
    conv = table[(table.method == "conventional") & (table.photons == photons) & (table.nn == nn)]
    prec = table[(table.method == "precomputed") & (table.photons == photons) & (table.nn == nn)]
    if conv.empty or prec.empty:
        return float("nan"), nan3
    c, p = conv.iloc[0], prec.iloc[0]
    share = (c.render_median_s - p.render_median_s) / c.total_median_s
    ratio = [float(p.get(k, float("nan"))) for k in
             ("paired_ratio_percent", "paired_ratio_ci95_hi", "paired_ratio_ci95_lo")]
    speed = tuple(100.0 / r if report.isnum(r) and r > 0 else float("nan") for r in ratio)
    return float(share), speed


def mean_difference(runs, photons, nn, ref):
    """Mean over seeds of (precomputed - conventional) / (reference + 0.01 mean)
    in luminance, paper estimate, same seeds; and the seeds used."""
    ok = runs[(runs.status == "ok") & (runs.estimate == "paper") & (runs.photons == photons) & (runs.nn == nn)
              & (runs.role == "grid")]
    pairs = []
    for seed, g in ok.groupby("seed"):
        by = {r.method: r.run for r in g.itertuples()}
        if "conventional" in by and "precomputed" in by:
            pairs.append((by["conventional"] + ".exr", by["precomputed"] + ".exr"))
    if not pairs:
        return None, 0
    r = plotting.luminance(ref)
    floor = r + 0.01 * float(r.mean())
    acc = np.zeros_like(r)
    for cpath, ppath in pairs:
        acc += (plotting.luminance(metrics.read_exr(ppath)) - plotting.luminance(metrics.read_exr(cpath))) / floor
    return acc / len(pairs), len(pairs)


def concentration(diff, top=0.01):
    """Share of sum(diff^2) in the `top` fraction of pixels with the largest |diff|."""
    e = np.sort((diff * diff).ravel())[::-1]
    total = float(e.sum())
    if total <= 0:
        return float("nan")
    return float(e[: max(1, int(round(top * e.size)))].sum() / total)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", action="append", nargs=5, required=True,
                    metavar=("SCENE", "TABLE_CSV", "RUNS_CSV", "EQUAL_ERROR_CSV", "REFERENCE"))
    ap.add_argument("--cell", default="p100000-n50", help="the (P_e, n) of the difference images, pP-nN")
    ap.add_argument("--size", required=True)
    ap.add_argument("--grid", default="")
    ap.add_argument("--ref-photons", required=True, help="P_e of the converged references")
    ap.add_argument("--ref-nn", required=True, help="n of the converged references")
    ap.add_argument("--ref-seed", required=True, help="--seed of the converged references (no grid seed)")
    ap.add_argument("--figures", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    try:
        cell_p, cell_n = (int(x[1:]) for x in a.cell.split("-"))
    except ValueError:
        report.die(a.cell, "--cell is not pP-nN", report.EXIT_BAD_INPUT)

    rows, images, times = [], [], set()
    for scene, table_csv, runs_csv, ee_csv, ref_path in a.scene:
        name = os.path.splitext(os.path.basename(scene))[0]
        for f in (table_csv, runs_csv, ee_csv, ref_path):
            if not os.path.exists(f):
                report.die(f, "missing (run make scenes)")
        table = report.read_csv(table_csv, ["method", "photons", "nn"], "scenes.py")
        runs = report.read_csv(runs_csv, ["method", "estimate", "photons", "nn", "seed", "status", "role", "run"], "scenes.py")
        ee = report.read_csv(ee_csv, ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction"],
                             "scenes.py")
        if "time" in ee.columns:
            times |= set(ee["time"].dropna())
        share, speed = knn_share(table, cell_p, cell_n)
        shares = [knn_share(table, p, n)[0] for p, n in table[["photons", "nn"]].drop_duplicates().itertuples(index=False)]
        ref = metrics.read_exr(ref_path)
        diff, seeds = mean_difference(runs, cell_p, cell_n, ref)
        empty = table[(table.method == "precomputed") & (table.photons == cell_p) & (table.nn == cell_n)]
        row = {"scene": name, "knn_share": share, "knn_share_min": float(np.nanmin(shares)),
               "knn_share_max": float(np.nanmax(shares)), "speedup_total": speed[0],
               "speedup_total_lo": speed[1], "speedup_total_hi": speed[2],
               "concentration_top1": concentration(diff) if diff is not None else float("nan"),
               "diff_seeds": seeds,
               "empty_estimates_prec": float(empty.iloc[0].empty_estimates) if not empty.empty else float("nan")}
        for est in ("paper", "corrected"):
            e = ee[(ee.estimate == est) & (ee.kind == "target") & (ee.defined_fraction == 1)]
            if e.empty:
                row[f"ee_{est}"] = "no target both fronts reach"
                row[f"ee_{est}_median"] = float("nan")
                continue
            parts = [f"{fmt(r.target, 2)}: {fmt_ci(r.speedup, r.lo, r.hi)}"
                     for r in e.itertuples()]
            row[f"ee_{est}"] = "; ".join(parts)
            row[f"ee_{est}_median"] = float(e.speedup.median())
            row[f"ee_{est}_min_lo"] = float(e.lo.min())
            row[f"ee_{est}_max_hi"] = float(e.hi.max())
        rows.append(row)
        images.append((name, ref, diff))

    os.makedirs(a.figures, exist_ok=True)
    fig_path = os.path.join(a.figures, "scenes.png")
    n = len(images)
    fig, axes = plt.subplots(n, 2, figsize=(9.5, 3.0 * n + 0.6), squeeze=False)
    lim = max((np.percentile(np.abs(d), 99) for _, _, d in images if d is not None), default=1.0)
    for i, (name, ref, diff) in enumerate(images):
        ax = axes[i][0]
        ax.imshow(plotting.srgb(ref))
        ax.set_title(f"{name}: our converged render (the reference)")
        ax.axis("off")
        ax = axes[i][1]
        if diff is not None:
            im = ax.imshow(diff, cmap="RdBu_r", vmin=-lim, vmax=lim)
            ax.set_title(f"{name}: (precomputed - conventional) / reference, P_e={plotting.kilo(cell_p)}, n={cell_n}")
            fig.colorbar(im, ax=ax, fraction=0.035, pad=0.02)
        ax.axis("off")
    plotting.footer(fig, f"Data: {', '.join(s[1] for s in a.scene)} and their runs ({a.size}, paper estimate; mean "
                         f"over the seeds both methods rendered; luminance; the reference plus 1% of its mean below). "
                         f"Red: the precomputed image brighter. One symmetric scale for every scene "
                         f"(99th percentile of |difference|, clipped).")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    plotting.save(fig, fig_path)

    d = pd.DataFrame(rows)
    d.to_csv(a.out + ".csv.tmp", index=False)
    os.replace(a.out + ".csv.tmp", a.out + ".csv")
    md = ["# Where the speed-up holds, and where it breaks: the cross-scene study", "",
          f"Generated by `make scenes` (experiments/rules/scenes.smk, experiments/analysis/scenes.py) on {report.today()}; "
          f"{report.machine()}; commit {report.commit()}. Every scene's grid: {a.grid}, at {a.size}, against our "
          f"converged render of that scene (corrected estimate, P_e = {a.ref_photons}, n = {a.ref_nn}, "
          f"mean of seeds {a.ref_seed}, which no grid render uses: the method's "
          "error is measured against the photon map's own limit, not against POV-Ray, whose agreement with us is "
          "checked per scene by tests/scenes.test.sh). Per scene, the full tables are "
          "`scenes/table-<scene>.md` and `scenes/equal-error-<scene>.md`; data: "
          f"[`{os.path.basename(a.out)}.csv`]({os.path.basename(a.out)}.csv).", "",
          "## The references' own error", ""] + [
          "- " + reference.describe(sc[4], reference.tightest_of(sc[3])) for sc in a.scene] + ["",
          "## Speed-up at equal error", "",
          "The precomputed method's time against the conventional one's at the same relMSE (each method's "
          "Pareto front of (median time, mean relMSE over seeds), interpolated; 95% bootstrap interval over "
          "seeds in brackets; the targets are those both fronts reach; time: "
          + ("; ".join(report.TIME_LABEL.get(t, t) for t in sorted(times)) or "as the equal-error files give it")
          + "):", ""]
    md += report.md_table(["scene", "paper estimate: relMSE target: speed-up [95% CI]", "corrected estimate"],
                          [[r["scene"], r["ee_paper"], r["ee_corrected"]] for r in rows])
    md += ["", "## The share of the kNN, and the speed-up of the total", "",
           f"At P_e = {plotting.kilo(cell_p)}, n = {cell_n} (paper estimate; medians over seeds): the share of the "
           "conventional render's total time spent in the k-nearest search (its eye pass minus the precomputed eye "
           "pass, which casts the same rays), its range over the grid's cells, and conventional / precomputed time at "
           "this cell, paired per seed (the geometric mean of the per-seed ratios with its 95% t interval, from the "
           "table's paired time ratio). Where the error lies: the share of the squared difference precomputed - "
           "conventional that sits in its 1% largest pixels (1% if spread evenly), and the precomputed method's "
           "diffuse hits without an agreeing representative (black samples).", ""]
    md += report.md_table(
        ["scene", "kNN share of the conventional total", "range over the grid", "conventional / precomputed time [95% CI]",
         "difference energy in the top 1% of pixels", "empty precomputed estimates (median over seeds)"],
        [[r["scene"], f"{r['knn_share']:.0%}", f"{r['knn_share_min']:.0%} - {r['knn_share_max']:.0%}",
          fmt_ci(r["speedup_total"], r["speedup_total_lo"], r["speedup_total_hi"]), f"{r['concentration_top1']:.0%}", fmt(r["empty_estimates_prec"])]
         for r in rows],
        align="lrrrrr")
    md += ["", "![(precomputed - conventional) / reference per scene](figures/scenes.png)", ""]
    with open(a.out + ".md.tmp", "w") as f:
        f.write("\n".join(md) + "\n")
    os.replace(a.out + ".md.tmp", a.out + ".md")
    print(f"wrote {a.out}.md, {a.out}.csv and {fig_path}")


if __name__ == "__main__":
    main()
