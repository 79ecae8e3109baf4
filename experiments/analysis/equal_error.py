#!/usr/bin/python3
"""equal_error.py: runs.csv -> the speed-up at equal error (STEM.md, STEM.csv).

Owns the number users ask for: for a set of relMSE targets, the time each
method needs to reach the target, read off its Pareto front of (time, error)
cells by log-log interpolation (stats.time_at_error), and the speed-up
conventional time / precomputed time at the same error, per estimate. A
cell's time is the median over its seeds, its error the mean relMSE against
the reference over its seeds. Uncertainty: a bootstrap over seeds (the
seeds are drawn with replacement once for every cell of both methods, a
paired bootstrap, since a seed is one photon map shared by both methods;
per cell where the cells do not share their seeds; each draw a whole
render: its time and its error together; then cell medians and means,
fronts and interpolation are recomputed); intervals are the 2.5% and 97.5% quantiles
of the resamples where the value is defined. A speed-up is a headline (a
number a summary quotes: headline()) only where at least DEFINED_MIN of the
resamples reach the target on both fronts; the tightest target both fronts
reach is where the curve starts, not a speed-up to quote.
"""

import argparse
import math
import os

import numpy as np
import pandas as pd

from experiments.analysis import metrics
from experiments.analysis import report
from experiments.analysis import stats
from experiments.analysis.report import fmt, fmt_count, fmt_interval

METHODS = ("conventional", "precomputed")
TIME_LABEL = report.TIME_LABEL


def cell_samples(runs, estimate, method, time_col, seeds_out=None):
    """{(photons, nn): (times, errors)} per-seed arrays, in seed order, of
    the ok renders of one method and estimate that have an error against
    the reference (for the conventional method of a variant without its
    own, the renders it is compared with); SEEDS_OUT, a dict when given,
    receives each cell's seeds as a tuple."""
    mine = runs[(runs["estimate"] == estimate) & (runs["method"] == method)]
    # a variant's conventional renders are the ones it is compared with
    role = "grid" if (mine["role"] == "grid").any() or method != "conventional" else "comparison"
    return seed_samples(mine[(mine["role"] == role) & (mine["status"] == "ok")], ["photons", "nn"], time_col,
                        seeds_out)


def seed_samples(sel, by, time_col, seeds_out=None):
    """{cell: (times, errors)} per-seed arrays, in seed order, of the rows of
    SEL with a finite error and time, one cell per value of the columns BY
    (the key: those values as ints); SEEDS_OUT, a dict when given, receives
    each cell's seeds as a tuple (in the same order, so that two methods'
    arrays pair by position where their seeds agree)."""
    sel = sel[np.isfinite(sel[metrics.PRIMARY_COLUMN].astype(float)) & np.isfinite(sel[time_col].astype(float))]
    out = {}
    for key, g in sel.groupby(by, sort=True):
        g = g.sort_values("seed", kind="stable")
        cell = tuple(int(k) for k in (key if isinstance(key, tuple) else (key,)))
        out[cell] = (g[time_col].to_numpy(np.float64), g[metrics.PRIMARY_COLUMN].to_numpy(np.float64))
        if seeds_out is not None:
            seeds_out[cell] = tuple(int(x) for x in g["seed"])
    return out


def shared_indices(seeds, rng, replicates):
    """One (replicates, S) matrix of seed positions drawn with replacement,
    for every cell of every method at once, when every cell in SEEDS
    ({method: {cell: tuple of seeds}}) has the same S seeds: a seed is one
    photon map, shared by both methods, so a resample keeps a seed's renders
    together across cells and methods (a paired bootstrap). None when the
    cells' seeds differ (a render failed): each cell is then resampled on
    its own."""
    every = {s for per in seeds.values() for s in per.values()}
    if len(every) != 1:
        return None
    (one,) = every
    return stats.resample_indices(rng, len(one), replicates) if len(one) else None


def cell_points(samples):
    """(keys, times, errors, error half-widths): per cell the median time and
    the mean error with its 95% t half-width."""
    keys = list(samples)
    t = np.array([np.median(samples[k][0]) for k in keys])
    ei = [stats.t_interval(samples[k][1]) for k in keys]
    return keys, t, np.array([m for m, _ in ei]), np.array([h for _, h in ei])


# how many targets EE_TARGETS=auto spaces inside the fronts' common range
AUTO_TARGETS = 5


def auto_targets(fronts, count=AUTO_TARGETS):
    """COUNT relMSE targets spaced evenly in log inside the error range that
    every front in FRONTS (lists of errors) covers, rounded to two
    significant digits; [] when the ranges do not overlap."""
    if any(len(e) == 0 for e in fronts):
        return []
    lo = max(min(e) for e in fronts)
    hi = min(max(e) for e in fronts)
    if not lo < hi:
        return []
    raw = [lo * (hi / lo) ** ((i + 0.5) / count) for i in range(count)]
    return sorted({float(f"{x:.2g}") for x in raw}, reverse=True)


# the share of bootstrap resamples that must reach a target on both fronts
# before its speed-up is ranked or quoted (below it the interval describes
# only the resamples that reach it)
DEFINED_MIN = 0.95


def headline(rows):
    """The row a summary quotes among ROWS (curve rows: dicts or pandas rows
    with target, speedup, defined_fraction): the tightest (smallest) target
    where at least DEFINED_MIN of the resamples reach both fronts and the
    speed-up is defined; None when there is none."""
    ok = [r for r in rows if r["defined_fraction"] >= DEFINED_MIN and np.isfinite(float(r["speedup"]))]
    return min(ok, key=lambda r: float(r["target"])) if ok else None


# points of the equal-error curve, spaced evenly in log relMSE over the
# whole range both fronts span
CURVE_POINTS = 41


def common_range(fronts):
    """(lo, hi): the relMSE range every front in FRONTS (lists of errors)
    spans: lo = the largest of the fronts' smallest errors, the tightest
    target both reach; hi = the smallest of their largest errors. None when
    a front is empty or the ranges do not overlap."""
    if any(len(e) == 0 for e in fronts):
        return None
    lo = max(min(e) for e in fronts)
    hi = min(max(e) for e in fronts)
    return (lo, hi) if lo <= hi else None


def curve_targets(fronts, count=CURVE_POINTS):
    """COUNT relMSE targets spaced evenly in log over common_range(FRONTS),
    both ends included, tightest (smallest) first; [] without a common
    range, [lo] when it is one value."""
    rng_ = common_range(fronts)
    if rng_ is None:
        return []
    lo, hi = rng_
    if lo == hi:
        return [lo]
    x = [float(v) for v in np.exp(np.linspace(math.log(lo), math.log(hi), count))]
    x[0], x[-1] = lo, hi  # the ends exactly: the tightest target is a front's own cell
    return x


def bootstrap_times(samples, targets, rng, replicates, shared=None):
    """(replicates, len(targets)) array: the front time at each target for
    each bootstrap resample of the cells' seeds (nan where undefined); with
    SHARED (shared_indices) every cell takes the same draw of seeds, else
    each cell's are drawn on its own."""
    keys = list(samples)
    t_b = np.empty((replicates, len(keys)))
    e_b = np.empty((replicates, len(keys)))
    for j, k in enumerate(keys):
        t, e = samples[k]
        idx = shared if shared is not None else stats.resample_indices(rng, t.size, replicates)
        t_b[:, j] = np.median(t[idx], axis=1)
        e_b[:, j] = e[idx].mean(axis=1)
    out = np.full((replicates, len(targets)), math.nan)
    for b in range(replicates):
        f = stats.pareto_front(t_b[b], e_b[b])
        ft, fe = t_b[b, f], e_b[b, f]
        for i, target in enumerate(targets):
            out[b, i] = stats.time_at_error(ft, fe, target)
    return out


def analyse(runs, estimate, time_col, targets_arg, rng, replicates):
    """Everything one estimate's section needs: a dict with the cells, the
    fronts, the targets and, per target, times and speed-up with intervals."""
    res = {"estimate": estimate, "cells": {}, "fronts": {}, "targets": [], "rows": [], "samples": {},
           "curve": [], "tightest": None, "headline": None, "range": None}
    samples = res["samples"]
    seeds = {m: {} for m in METHODS}
    for m in METHODS:
        samples[m] = cell_samples(runs, estimate, m, time_col, seeds[m])
        keys, t, e, h = cell_points(samples[m])
        res["cells"][m] = (keys, t, e, h)
        res["fronts"][m] = stats.pareto_front(t, e)
    if any(len(samples[m]) == 0 for m in METHODS):
        return res
    front_errors = [list(res["cells"][m][2][res["fronts"][m]]) for m in METHODS]
    if targets_arg.strip() in ("", "auto"):
        targets = auto_targets(front_errors)
    else:
        targets = sorted({float(x) for x in targets_arg.split()}, reverse=True)
    res["targets"] = targets
    curve = curve_targets(front_errors)
    res["range"] = common_range(front_errors)
    # the tightest target both reach, the curve over the common range, the
    # requested targets: one computation, told apart by "kind"
    kinds = (["tightest"] if curve else []) + ["curve"] * len(curve) + ["target"] * len(targets)
    targets = (curve[:1] + curve if curve else []) + targets
    if not targets:
        return res
    point, between = {}, {}
    for m in METHODS:
        keys, t, e, _ = res["cells"][m]
        f = res["fronts"][m]
        point[m] = [stats.time_at_error(t[f], e[f], x) for x in targets]
        segs = [stats.front_segment(e[f], x) for x in targets]
        between[m] = ["" if sg is None else " .. ".join(dict.fromkeys(label(keys[f[k]]) for k in sg)) for sg in segs]
    shared = shared_indices(seeds, rng, replicates)
    res["paired"] = shared is not None
    boot = {m: bootstrap_times(samples[m], targets, rng, replicates, shared) for m in METHODS}
    speed = boot["conventional"] / boot["precomputed"]
    res["curve"], res["tightest"] = [], None
    for i, x in enumerate(targets):
        row = {"estimate": estimate, "kind": kinds[i], "target": x, "time": time_col}
        for m in METHODS:
            lo, hi, d = stats.percentile_interval(boot[m][:, i])
            row[f"{m}_s"], row[f"{m}_lo"], row[f"{m}_hi"], row[f"{m}_defined"] = point[m][i], lo, hi, d
            row[f"{m}_between"] = between[m][i]
        lo, hi, d = stats.percentile_interval(speed[:, i])
        row["speedup"] = point["conventional"][i] / point["precomputed"][i] if point["precomputed"][i] > 0 else math.nan
        row["lo"], row["hi"], row["defined_fraction"] = lo, hi, d
        {"target": res["rows"], "curve": res["curve"]}.get(kinds[i], []).append(row)
        if kinds[i] == "tightest":
            res["tightest"] = row
    res["headline"] = headline(res["curve"])
    return res


def paired_text(results):
    """How the bootstrap drew the seeds of RESULTS (analyse's dicts): one
    draw shared by every cell of both methods (paired), or per cell."""
    paired = [r for r in results if r.get("paired")]
    shared = ("the seeds are drawn with replacement once for every cell of both methods (paired: a seed is one "
              "photon map, the same in both methods, so a resample keeps a seed's renders together)")
    own = "every cell's seeds are drawn with replacement on their own"
    if len(paired) == len(results):
        return shared
    if not paired:
        return own + " (the cells do not share their seeds)"
    return (shared + " for the " + ", ".join(r["estimate"] for r in paired) + " estimate; for the others, "
            + own + " (their cells do not share their seeds)")


def label(key):
    """'P_e=50k, n=10' for a cell key (photons, nn)."""
    p, n = key
    return f"P_e={p // 1000}k, n={n}" if p % 1000 == 0 else f"P_e={p}, n={n}"


def section(res, time_col):
    """Markdown lines of one estimate."""
    est = res["estimate"]
    out = ["", f"## {est} estimate", ""]
    if any(len(res["cells"][m][0]) == 0 for m in METHODS):
        missing = [m for m in METHODS if len(res["cells"][m][0]) == 0]
        return out + [f"No {' or '.join(missing)} render of this estimate with an error against the reference: "
                      "nothing to compare."]
    out += ["Pareto fronts (cells no other cell of the same method beats in both time and error), fastest first; "
            "time: median over seeds, relMSE: mean ± 95% t half-width over seeds:", ""]
    rows = []
    for m in METHODS:
        keys, t, e, h = res["cells"][m]
        for j in res["fronts"][m]:
            rows.append([m, label(keys[j]), fmt(t[j]), report.fmt_pm(e[j], h[j])])
    out += report.md_table(["method", "cell", "time s", "relMSE"], rows, ["l", "l", "r", "r"])
    t = res.get("tightest")
    if t is None:
        out += ["", "The two fronts reach no common relMSE: no tightest target both reach, and no curve."]
    else:
        lo_r, hi_r = res["range"]
        sp = [r["speedup"] for r in res["curve"] if report.isnum(r["speedup"])]
        sp95 = [r["speedup"] for r in res["curve"]
                if report.isnum(r["speedup"]) and r["defined_fraction"] >= DEFINED_MIN]
        h = res.get("headline")
        out += ["", f"**The tightest target both fronts reach**, where the curve starts: relMSE {fmt(t['target'])} "
                "(the larger of the two fronts' smallest errors, defined as such, not chosen from the curve): "
                f"conventional {fmt(t['conventional_s'])} s ({t['conventional_between']}), precomputed "
                f"{fmt(t['precomputed_s'])} s ({t['precomputed_between']}); {100 * t['defined_fraction']:.0f}% of "
                "the resamples reach it on both fronts (at the end of a front a resample often does not), so it "
                "marks where the curve starts and its speed-up is not a headline.", "",
                ("**Headline**: at relMSE " + fmt(h["target"]) + ", the tightest target of the curve that at least "
                 f"{100 * DEFINED_MIN:.0f}% of the resamples reach on both fronts ({100 * h['defined_fraction']:.0f}%), "
                 f"the speed-up is **{fmt(h['speedup'])}** {fmt_interval(h['lo'], h['hi'])}." if h is not None else
                 f"**No headline**: at no target of the curve do {100 * DEFINED_MIN:.0f}% of the resamples reach "
                 "both fronts."), "",
                f"**The curve** (`kind` = curve in the CSV, {len(res['curve'])} targets evenly in log over the whole "
                f"range both fronts span, {fmt(lo_r)} to {fmt(hi_r)}; figure `{os.path.basename(res['figure'])}`): "
                + ((f"speed-up from {fmt(min(sp95))} to {fmt(max(sp95))} at the {len(sp95)} targets at least "
                    f"{100 * DEFINED_MIN:.0f}% of the resamples reach" if sp95 else
                    f"no target that {100 * DEFINED_MIN:.0f}% of the resamples reach")
                   + f" (from {fmt(min(sp))} to {fmt(max(sp))} at its point estimates over the whole range, where "
                   "fewer resamples reach the ends); a single number is one point of it, and its peak is not a "
                   "summary." if sp else "undefined everywhere.")]
    if not res["targets"]:
        return out
    out += ["", "At each relMSE target: the time each method needs (its front interpolated in log-log between the "
            "two front cells named below it), and the speed-up = conventional time / precomputed time; [95% "
            "bootstrap interval]; \"defined\": the share of bootstrap resamples in which both fronts reach the "
            "target (the interval is taken over those). The interval covers the seeds' noise, not the error of "
            "the straight line between two grid cells: where those cells lie far apart (n from 10 to 100, say), "
            "the time in between is a model, and a finer grid there is the way to check it.", ""]
    rows = []
    for r in res["rows"]:
        rows.append([fmt(r["target"]),
                     f"{fmt(r['conventional_s'])} {fmt_interval(r['conventional_lo'], r['conventional_hi'])}"
                     f"<br>{r['conventional_between'] or 'outside the front'}",
                     f"{fmt(r['precomputed_s'])} {fmt_interval(r['precomputed_lo'], r['precomputed_hi'])}"
                     f"<br>{r['precomputed_between'] or 'outside the front'}",
                     f"**{fmt(r['speedup'])}** {fmt_interval(r['lo'], r['hi'])}",
                     f"{100 * r['defined_fraction']:.0f}%"])
    out += report.md_table(["relMSE target", "conventional s<br>(between cells)", "precomputed s<br>(between cells)",
                            "speed-up", "defined"], rows)

    # rank only where the interval is trustworthy: defined in >= 95% of the
    # resamples (else it is conditional on the resamples that reach the target)
    solid = [r for r in res["rows"] if r["defined_fraction"] >= DEFINED_MIN]
    faster = [r for r in solid if report.isnum(r["lo"]) and r["lo"] > 1]
    slower = [r for r in solid if report.isnum(r["hi"]) and r["hi"] < 1]
    unranked = [r for r in solid if r not in faster and r not in slower]
    thin = [r for r in res["rows"] if r not in solid]
    out.append("")
    if faster:
        out.append(f"- The precomputed method needs less time at relMSE {', '.join(fmt(r['target']) for r in faster)} "
                   "(the speed-up's interval lies above 1).")
    if slower:
        out.append(f"- The conventional method needs less time at relMSE {', '.join(fmt(r['target']) for r in slower)} "
                   "(the interval lies below 1).")
    if unranked:
        out.append(f"- No ranking at relMSE {', '.join(fmt(r['target']) for r in unranked)}: the interval "
                   "contains 1.")
    if thin:
        out.append(f"- No ranking at relMSE {', '.join(fmt(r['target']) for r in thin)} either: fewer than 95% "
                   "of the resamples reach the target on both fronts, so the interval describes only those that do "
                   "(the cells around the target swap places on the fronts from resample to resample).")
    seeds = min(min((len(v[0]) for v in res["samples"][m].values()), default=0) for m in METHODS)
    if seeds < 5:
        out.append(f"- Caution: with {seeds} seed(s) in a cell its bootstrap has only {math.comb(2 * seeds - 1, seeds)} "
                   "distinct resamples, so these intervals run narrow; rerun with more seeds (`SEEDS`, default 5) "
                   "before quoting them.")
    return out


def figure(results, path, note):
    """The equal-error curve of each estimate (speed-up against relMSE
    target, log-log) with its 95% bootstrap band and the tightest target
    both fronts reach marked, as a PNG at PATH (nothing when no estimate has
    a curve)."""
    from experiments.analysis import plotting

    have = [r for r in results if r.get("curve")]
    if not have:
        return
    fig, axes = plotting.plt.subplots(1, len(have), figsize=(5.2 * len(have), 4.2), squeeze=False)
    for ax, res in zip(axes[0], have):
        c = res["curve"]
        x = np.array([r["target"] for r in c])
        y, lo, hi = (np.array([r[k] for r in c], dtype=np.float64) for k in ("speedup", "lo", "hi"))
        colour = plotting.METHOD_COLOUR["precomputed"]
        ax.fill_between(x, lo, hi, color=colour, alpha=0.25, linewidth=0, label="95% bootstrap band")
        ax.plot(x, y, color=colour, label="speed-up (conventional / precomputed time)")
        t = res["tightest"]
        ax.errorbar([t["target"]], [t["speedup"]], yerr=[[max(t["speedup"] - t["lo"], 0) if report.isnum(t["lo"]) else 0],
                                                         [max(t["hi"] - t["speedup"], 0) if report.isnum(t["hi"]) else 0]],
                    fmt="o", color="black", capsize=3, label=f"tightest target both reach ({fmt(t['target'])})")
        ax.axhline(1.0, color="#888888", linewidth=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        plotting.log_ticks(ax.xaxis, *ax.get_xlim())
        plotting.log_ticks(ax.yaxis, *ax.get_ylim())
        ax.set_xlabel("relMSE target")
        ax.set_ylabel("speed-up at equal error")
        ax.set_title(f"{res['estimate']} estimate")
        ax.legend(loc="best")
    fig.subplots_adjust(bottom=0.26, wspace=0.3)
    plotting.footer(fig, note)
    plotting.save(fig, path)


def main():
    """Command line: see the module docstring and experiments/rules/grid.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs-csv", required=True)
    ap.add_argument("--out", required=True, help="output stem: STEM.md and STEM.csv")
    ap.add_argument("--targets", default="auto", help="relMSE targets, or auto")
    ap.add_argument("--time", default="cpu_s", choices=sorted(TIME_LABEL))
    ap.add_argument("--bootstrap", type=int, default=2000)
    ap.add_argument("--bootstrap-seed", type=int, default=1)
    ap.add_argument("--pm", default="build/photonmap")
    args = ap.parse_args()
    need = ["role", "status", "estimate", "method", "photons", "nn", "seed", metrics.PRIMARY_COLUMN, args.time,
            "size", "subpixels", "threads", "loadavg_1min"]
    runs = report.read_csv(args.runs_csv, need, "equal_error.py")
    try:
        targets = [float(x) for x in args.targets.split()] if args.targets.strip() not in ("", "auto") else []
    except ValueError:
        report.die("equal_error.py", f"--targets '{args.targets}': not numbers or 'auto'", report.EXIT_BAD_INPUT)
    if any(not x > 0 for x in targets):
        report.die("equal_error.py", f"--targets '{args.targets}': relMSE targets must be positive", report.EXIT_BAD_INPUT)
    rng = np.random.default_rng(args.bootstrap_seed)
    grid = runs[runs["role"] == "grid"]
    estimates = list(dict.fromkeys(grid["estimate"]))
    results = [analyse(runs, e, args.time, args.targets, rng, args.bootstrap) for e in estimates]
    for res in results:
        res["figure"] = args.out + ".png"

    ok = grid[grid["status"] == "ok"]
    seeds = ok.groupby(["method", "estimate", "photons", "nn"])["seed"].nunique()
    load = stats.median_range(grid["loadavg_1min"].to_numpy(np.float64))
    has_ref = np.isfinite(ok[metrics.PRIMARY_COLUMN].astype(float)).any()
    out = ["# Speed-up at equal error", "",
           f"Generated by `make reproduce-table` on {report.today()} from "
           f"[`{os.path.basename(args.runs_csv)}`]({os.path.relpath(args.runs_csv, os.path.dirname(args.out) or '.')}) "
           f"({grid['size'].iloc[0]}, {grid['subpixels'].iloc[0]}x{grid['subpixels'].iloc[0]} subpixels, "
           f"seeds per cell: {fmt_count(seeds.median(), seeds.min(), seeds.max()) if len(seeds) else 'none'}); "
           f"data: [`{os.path.basename(args.out)}.csv`]({os.path.basename(args.out)}.csv). Machine: {report.machine()}; "
           f"1-minute load average at the start of the renders: median {fmt(load[0])}, range "
           f"{fmt(load[1])}-{fmt(load[2])}; commit {report.commit()}; renderer: {report.renderer_note(args.pm)}.", "",
           "The question: to reach a given error, how much faster is the precomputed method? Error: relMSE against "
           "the reference (see the table's Markdown for which), mean over seeds per cell. Time: "
           f"{TIME_LABEL[args.time]}, median over seeds per cell. For each method the cells (P_e, n) form a Pareto "
           "front; between two neighbouring front cells log(time) is interpolated linearly in log(relMSE). A target "
           "below a front's smallest error is not reached in the grid, one above its largest would need a cell "
           "cheaper than the grid's cheapest: both are left undefined rather than extrapolated. Intervals: "
           f"{args.bootstrap} bootstrap resamples over seeds (random seed {args.bootstrap_seed}); in each, "
           + paired_text(results) + " (a render's time and error together), and medians, means, "
           "fronts and interpolation are recomputed. Targets: "
           + (f"{AUTO_TARGETS} relMSE values spaced evenly in log inside the range both fronts reach, rounded to two "
              "significant digits (fewer where two round alike; `EE_TARGETS=auto`)."
              if args.targets.strip() in ("", "auto") else f"`EE_TARGETS={args.targets}`.")]
    if not has_ref:
        out += ["", "No render has an error against a reference (no reference of this size): nothing to compare."]
    for res in results:
        out += section(res, args.time)
    rows = [r for res in results for r in ([res["tightest"]] if res.get("tightest") else []) + res.get("curve", [])
            + res["rows"]]
    columns = ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction", "time"] + \
              [f"{m}_{k}" for m in METHODS for k in ("s", "lo", "hi", "defined", "between")]
    report.write_csv_atomic(pd.DataFrame(rows, columns=columns), args.out + ".csv", "%.6g")
    figure(results, args.out + ".png", f"Data: {args.out}.csv from {args.runs_csv} ({grid['size'].iloc[0]}; "
           f"{args.bootstrap} bootstrap resamples over seeds); time: {TIME_LABEL[args.time]}.")
    report.write_atomic(args.out + ".md", "\n".join(out) + "\n")
    print(f"wrote {args.out}.md and {args.out}.csv ({len(rows)} targets)")


if __name__ == "__main__":
    main()
