#!/usr/bin/python3
"""gather.py: the final-gathering study (make gather) -> gather.md, gather.csv
and a figure.

Owns the report of issue 37, items 7-9: per grid (a scene at a size), both
methods under final gathering over P_e x n x N (the gather rays, --gather N),
    - the fronts of time against relMSE (a cell: its seeds' median time, mean
      relMSE against the grid's converged reference);
    - the equal-error speed-up conventional / precomputed with its 95%
      bootstrap band (equal_error.bootstrap_times: the seeds resampled once
      for every cell of both methods where the cells share them, paired,
      else per cell) over the targets where at least DEFINED_MIN of the resamples reach
      both fronts;
    - the gather phase's own speed-up (the stats key gather_time:
      gather_thread_s, conventional over precomputed, pairs of one cell and
      seed: the geometric mean of the paired ratios over the grid's pairs,
      with its t interval, stats.paired_log_ratio);
    - the precompute as a share of the time saved (precompute_s of the
      precomputed render over the paired total time saved);
    - the memory increase (bytes_representatives over bytes_photon_map plus
      bytes_caustic_map);
    - the bound the work counters give: the speed-up if the lookups at y cost
      nothing beside the shared ray casting. The render phase's extra time of
      the conventional method over the paired precomputed render is fitted
      (least squares over the grid's pairs, no intercept) as c_map x the extra
      photon-map work (map_nodes + map_points) minus c_rep x the
      representatives' work (rep_nodes + rep_points); the bound of a cell is
      T_conv / (T_conv - c_map x the conventional render's extra map work),
      its median over cells reported;
    - item 9: per grid, the cheapest cell reaching each relMSE target over
      every mode: final gathering (method, P_e, n, N) and, where runs of the
      direct visualisation are given (another study's runs.csv of the same
      scene and size), the map seen directly (method, estimate, P_e, n).

Per grid the reference's own error (reference.py): its noise and kernel
bias from the JSON beside the reference EXR (columns ref_noise, ref_bias of
gather.csv, on every row of the grid; empty when it has none, as a POV-Ray
reference: not measured, and no number stands in for it) and
reference.describe's sentence in gather.md's References, checked against
the grid's tightest equal-error target (the smallest target of its
equal-error rows).

Input: the runs.csv of every sub-grid (experiments/analysis/collect.py, one
per scene, size and N) as --grid SCENE SIZE N RUNS_CSV; each ok run's stats
JSON (RUN.stats.json) for the gather keys; the reference of each scene and
size as --ref SCENE SIZE REF (the grids' `ref`, the column of their
cells.csv; a grid without one says so).
"""

import argparse
import math
import os
import sys

import numpy as np
import pandas as pd

from experiments.analysis import equal_error, metrics, reference, report, stats
from experiments.analysis.report import fmt, fmt_interval

METHODS = ("conventional", "precomputed")
DEFINED_MIN = 0.95  # a target counts where this share of resamples reaches both fronts
TARGETS = 6         # relMSE targets per grid, log-spaced over the fronts' common range
# the published figures the report sets beside ours
PUBLISHED = ("Christensen (1999): the indirect part 5-7x faster, precompute 2-5% of the time saved, +28% memory; "
             "pbrt-v2 radiance photons on its Cornell box, 256x192: 12.7x (100k photons) and 18.7x (500k) "
             "against three k = 50 estimates per gather hit, precompute 0.7-2% of the time saved, +12.5% memory")
# the published speed-ups of the gather (indirect) phase alone, low and high
# end, that the findings set the gather phase's intervals against
PUBLISHED_GATHER = (("Christensen's", 5.0, 7.0), ("pbrt-v2's", 12.7, 18.7))


def stats_of(run):
    """The gather keys of one render's stats JSON (nan where absent)."""
    st = report_load(run + ".stats.json")
    w = st.get("work", {}).get("render", {})
    g = st.get("gather_time", {})
    return {
        "gather": st.get("gather", math.nan),
        "gather_s": g.get("gather_thread_s", math.nan),
        "render_thread_s": g.get("render_thread_s", math.nan),
        "map_work": w.get("map_nodes", 0) + w.get("map_points", 0),
        "rep_work": w.get("rep_nodes", 0) + w.get("rep_points", 0),
        "bytes_photon_map": st.get("bytes_photon_map", math.nan),
        "bytes_representatives": st.get("bytes_representatives", 0),
        "bytes_caustic_map": st.get("bytes_caustic_map", 0),
        "lookups": st.get("gather_work", {}).get("lookups", math.nan),
    }


def report_load(path):
    """The JSON object in PATH (runs.load_json); exits 1 naming the file when it is unreadable or
    not JSON."""
    from experiments.analysis import runs as layout
    try:
        return layout.load_json(path)
    except layout.RunError as e:
        report.die("gather.py", str(e))


def load_grids(grids, time_col):
    """One frame of every ok render of the sub-grids GRIDS [(scene, size, N,
    runs_csv)], with columns scene, size, N and the gather keys."""
    frames = []
    for scene, size, n_gather, path in grids:
        r = report.read_csv(path, ["method", "status", "photons", "nn", "seed", "run", time_col,
                                   metrics.PRIMARY_COLUMN, "precompute_s", "total_s"], "gather.py",
                            "(experiments/analysis/collect.py writes it)")
        r = r[(r["status"] == "ok") & (r.get("role", "grid") == "grid")].copy()
        r["scene"], r["size"], r["N"] = scene, size, int(n_gather)
        extra = [stats_of(run) for run in r["run"]]
        for k in (extra[0] if extra else {}):
            r[k] = [e[k] for e in extra]
        frames.append(r)
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def samples_of(runs, method, time_col, seeds_out=None):
    """{(P_e, n, N): (times, errors)} of one method's ok renders, in seed
    order; SEEDS_OUT, a dict when given, receives each cell's seeds."""
    return equal_error.seed_samples(runs[runs["method"] == method], ["photons", "nn", "N"], time_col, seeds_out)


def cell_label(key):
    """'P_e=50000 n=10 N=64' of a gather cell KEY (P_e, n, N)."""
    return f"P_e={key[0]} n={key[1]} N={key[2]}"


def fronts(samples):
    """(keys, times, errors, front indices) of one method's cells."""
    keys = list(samples)
    t = np.array([np.median(samples[k][0]) for k in keys])
    e = np.array([np.mean(samples[k][1]) for k in keys])
    return keys, t, e, stats.pareto_front(t, e)


def equal_error_rows(samples, rng, replicates, seeds=None):
    """Per target over the fronts' common range: both times, the speed-up,
    its band and the share of resamples defined; SEEDS ({method: {cell:
    seeds}}) pairs the bootstrap where every cell shares its seeds
    (equal_error.shared_indices)."""
    f = {m: fronts(samples[m]) for m in METHODS}
    errs = [list(f[m][2][f[m][3]]) for m in METHODS]
    rng_ = equal_error.common_range(errs)
    if rng_ is None:
        return []
    lo, hi = rng_
    targets = [lo] if lo == hi else [float(x) for x in np.exp(np.linspace(math.log(hi), math.log(lo), TARGETS))]
    targets[0], targets[-1] = hi, lo  # exp(log(x)) may round past a front's end
    shared = equal_error.shared_indices(seeds, rng, replicates) if seeds else None
    boot = {m: equal_error.bootstrap_times(samples[m], targets, rng, replicates, shared) for m in METHODS}
    with np.errstate(divide="ignore", invalid="ignore"):
        speed = boot["conventional"] / boot["precomputed"]
    rows = []
    for i, x in enumerate(targets):
        point = {m: stats.time_at_error(f[m][1][f[m][3]], f[m][2][f[m][3]], x) for m in METHODS}
        slo, shi, d = stats.percentile_interval(speed[:, i])
        rows.append({"target": x, "conventional_s": point["conventional"], "precomputed_s": point["precomputed"],
                     "speedup": point["conventional"] / point["precomputed"] if point["precomputed"] > 0 else math.nan,
                     "lo": slo, "hi": shi, "defined": d, "counts": d >= DEFINED_MIN})
    return rows


def pairs_of(runs):
    """The conventional and precomputed renders of one cell and seed side by side."""
    key = ["photons", "nn", "N", "seed"]
    c = runs[runs["method"] == "conventional"].set_index(key)
    p = runs[runs["method"] == "precomputed"].set_index(key)
    return c.join(p, lsuffix="_c", rsuffix="_p", how="inner").reset_index()


def work_bound(pairs, time_col):
    """(c_map, c_rep, median bound, per-pair bounds): the fit of the
    conventional render's extra render time over its pair and the speed-up
    if the lookups at y cost nothing (module docstring)."""
    if len(pairs) < 2:
        return math.nan, math.nan, math.nan, np.array([])
    dt = (pairs["render_s_c"] - pairs["render_s_p"]).to_numpy(np.float64)
    dmap = (pairs["map_work_c"] - pairs["map_work_p"]).to_numpy(np.float64)
    rep = pairs["rep_work_p"].to_numpy(np.float64)
    A = np.column_stack([dmap, -rep])
    coef, *_ = np.linalg.lstsq(A, dt, rcond=None)
    c_map, c_rep = float(coef[0]), float(coef[1])
    t = pairs[f"{time_col}_c"].to_numpy(np.float64)
    free = t - c_map * dmap
    with np.errstate(divide="ignore", invalid="ignore"):
        b = np.where(free > 0, t / free, math.nan)
    return c_map, c_rep, float(np.nanmedian(b)) if np.isfinite(b).any() else math.nan, b


def grid_summary(runs, time_col, rng, replicates):
    """Everything one grid's section says: a dict."""
    seeds = {m: {} for m in METHODS}
    samples = {m: samples_of(runs, m, time_col, seeds[m]) for m in METHODS}
    out = {"cells": {m: len(samples[m]) for m in METHODS}, "rows": [], "gather": (math.nan,) * 3,
           "share": (math.nan,) * 3, "share_pairs": (0, 0), "memory": math.nan, "bound": (math.nan,) * 3, "samples": samples}
    if all(samples[m] for m in METHODS):
        out["rows"] = equal_error_rows(samples, rng, replicates, seeds)
    pairs = pairs_of(runs)
    if len(pairs):
        out["gather"] = stats.paired_log_ratio(pairs["gather_s_c"], pairs["gather_s_p"])[:3]
        saved = (pairs[f"{time_col}_c"] - pairs[f"{time_col}_p"]).to_numpy(np.float64)
        pre = pairs["precompute_s_p"].to_numpy(np.float64)
        with np.errstate(divide="ignore", invalid="ignore"):
            share = np.where(saved > 0, pre / saved, math.nan)
        out["share"] = stats.median_range(share)
        out["share_pairs"] = (int(np.isfinite(share).sum()), int(share.size))
        p = runs[runs["method"] == "precomputed"]
        base = p["bytes_photon_map"] + p["bytes_caustic_map"]
        out["memory"] = float(np.median(p["bytes_representatives"] / base)) if len(p) else math.nan
        c_map, c_rep, b, _ = work_bound(pairs, time_col)
        out["bound"] = (b, c_map, c_rep)
    return out


def best_per_target(modes, targets):
    """Per target, the cheapest cell that reaches it: MODES {mode: {key:
    (times, errors)}}; a row (target, mode, setting, time) per target, or
    none when no cell reaches it."""
    rows = []
    for x in targets:
        best = None
        for mode, samples in modes.items():
            for key, (t, e) in samples.items():
                tm, em = float(np.median(t)), float(np.mean(e))
                if em <= x and (best is None or tm < best[3]):
                    best = (x, mode, key, tm)
        rows.append(best if best else (x, "", None, math.nan))
    return rows


def not_told_apart(modes, row):
    """The cells (mode, setting) that also reach ROW's target (a
    best_per_target row) and whose range of times over seeds overlaps the
    cheapest one's: the cells its time does not tell apart from it, so that
    'cheapest' ranks none of them; [] when none does or none reaches it."""
    x, mode, key, _ = row
    if key is None:
        return []
    t0 = modes[mode][key][0]
    lo, hi = float(np.min(t0)), float(np.max(t0))
    return [(m, k) for m, samples in modes.items() for k, (t, e) in samples.items()
            if (m, k) != (mode, key) and float(np.mean(e)) <= x and float(np.min(t)) <= hi and lo <= float(np.max(t))]


def direct_samples(path, time_col):
    """{mode: {key: (times, errors)}} of a direct-visualisation runs.csv, one
    mode per method and estimate."""
    r = report.read_csv(path, ["method", "estimate", "status", "photons", "nn", time_col, metrics.PRIMARY_COLUMN],
                        "gather.py", "(the runs.csv of a study of the map seen directly)")
    r = r[(r["status"] == "ok") & np.isfinite(r[metrics.PRIMARY_COLUMN].astype(float))]
    if "role" in r:
        r = r[r["role"] == "grid"]
    out = {}
    for (m, est, p, n), d in r.groupby(["method", "estimate", "photons", "nn"]):
        out.setdefault(f"direct {m} {est}", {})[(int(p), int(n))] = (d[time_col].to_numpy(np.float64),
                                                                      d[metrics.PRIMARY_COLUMN].to_numpy(np.float64))
    return out


def setting_label(key):
    """The label of a setting KEY: cell_label's of a gather cell (P_e, n, N), 'P_e=50000 n=10' of
    a cell of the map seen directly (P_e, n), '' for None."""
    if key is None:
        return ""
    return cell_label(key) if len(key) == 3 else f"P_e={key[0]} n={key[1]}"


def grid_reference(ref, rows):
    """{"ref", "ref_noise", "ref_bias", "tightest", "sentence"} of one grid:
    its reference REF's noise and bias in relMSE (reference.measured: nan
    when not measured), the grid's tightest equal-error target (the
    smallest target of its equal-error ROWS; None without one) and
    reference.describe's sentence checked against it. Exits 2 (bad input)
    naming a reference's JSON that is not JSON or lacks the numbers."""
    t = [r["target"] for r in rows if report.isnum(r["target"]) and math.isfinite(r["target"])]
    tightest = min(t) if t else None
    try:
        _info, noise, bias = reference.measured(ref)
    except ValueError as e:
        report.die("gather.py", str(e), report.EXIT_BAD_INPUT)
    # nan, not None: the sentence then says that there is no target to check it against
    sentence = (reference.describe(ref, math.nan if tightest is None else tightest) if ref else
                "No reference is named for it (--ref): its own error is not reported here.")
    return {"ref": ref, "ref_noise": noise, "ref_bias": bias, "tightest": tightest, "sentence": sentence}


def references_md(refs):
    """The lines of gather.md's References section; REFS: {(scene, size):
    grid_reference}."""
    out = ["## References", "",
           "Per grid its reference's own error, from the JSON beside it (experiments/analysis/reference.py: the "
           "noise of the mean over the reference's seeds, from their halves, and the kernel bias, from halving "
           "P_e; both in relMSE), checked against the grid's tightest equal-error target (the smallest target "
           f"of its equal-error table): each should be at most {reference.MARGIN:.0%} of it. A reference without "
           "that JSON (a POV-Ray render) has its error not measured; no number is given for it. Columns "
           "`ref_noise` and `ref_bias` of the CSV hold the same numbers per grid.", ""]
    out += [f"- **{scene} at {size}**: {r['sentence']}" for (scene, size), r in refs.items()]
    return out


def write(runs, direct, time_col, out, figure, rng, replicates, pm, refs=None):
    """gather.md, gather.csv and the figure; REFS: {(scene, size): the
    reference EXR} (--ref)."""
    refs = refs or {}
    grid_refs = {}
    lines = ["# Final gathering: the precomputed method against the conventional one", "",
             f"Machine: {report.machine()}; load average at the report: {report.loadavg_now()}; commit {report.commit()}; "
             f"renderer {report.renderer_note(pm)}; {report.today()}.", "",
             f"Time: {report.TIME_LABEL.get(time_col, time_col)}. Error: {metrics.PRIMARY_COLUMN} against each grid's "
             "converged reference. Intervals: 95%, bootstrap over seeds (one draw for every cell of both methods where "
             "the cells share their seeds, paired). Equal-error speed-ups count only at targets "
             f"where at least {DEFINED_MIN:.0%} of the resamples reach both fronts.", "",
             f"Published: {PUBLISHED}.", ""]
    csv_rows = []
    summaries = {}
    for (scene, size), g in runs.groupby(["scene", "size"], sort=False):
        s = grid_summary(g, time_col, rng, replicates)
        summaries[(scene, size)] = s
        grid_refs[(scene, size)] = grid_reference(refs.get((scene, size), ""), s["rows"])
        first = len(csv_rows)
        counted = [r for r in s["rows"] if r["counts"]]
        lo = min((r["lo"] for r in counted), default=math.nan)
        hi = max((r["hi"] for r in counted), default=math.nan)
        lines += [f"## {scene} at {size}", "",
                  f"Cells: {s['cells']['conventional']} conventional, {s['cells']['precomputed']} precomputed; "
                  f"N in {{{' '.join(str(n) for n in sorted(g['N'].unique()))}}}.", ""]
        if s["rows"]:
            lines += report.md_table(
                ["relMSE target", "conventional s", "precomputed s", "speed-up", "95% band", "resamples defined"],
                [[fmt(r["target"]), fmt(r["conventional_s"]), fmt(r["precomputed_s"]), fmt(r["speedup"]),
                  fmt_interval(r["lo"], r["hi"]), f"{r['defined']:.0%}" + ("" if r["counts"] else " (not counted)")]
                 for r in s["rows"]]) + [""]
        else:
            lines += ["The two fronts share no relMSE range: no equal-error speed-up.", ""]
        gr, glo, ghi = s["gather"]
        sh, shlo, shhi = s["share"]
        b, c_map, c_rep = s["bound"]
        lines += [f"- equal-error speed-up over the counted targets: band {fmt_interval(lo, hi)}"
                  + (" (above 1)" if lo > 1 else ""),
                  f"- gather phase (gather_thread_s) speed-up, the geometric mean of the paired ratios (cell and "
                  f"seed) with its 95% t interval: {fmt(gr)} {fmt_interval(glo, ghi)}",
                  f"- precompute as a share of the time saved: median {fmt(sh)} (range {fmt(shlo)}-{fmt(shhi)}) over "
                  f"the {s['share_pairs'][0]} of {s['share_pairs'][1]} pairs where the precomputed render saved time",
                  f"- memory: the representatives add {fmt(100 * s['memory'])}% to the photon maps",
                  f"- bound from the work counters (lookups at y free): {fmt(b)} "
                  f"(fit: {fmt(1e9 * c_map)} ns per map node or point, {fmt(1e9 * c_rep)} ns per representative node or point)",
                  ""]
        for r in s["rows"]:
            csv_rows.append({"scene": scene, "size": size, "kind": "equal_error", **{k: r[k] for k in
                             ("target", "conventional_s", "precomputed_s", "speedup", "lo", "hi", "defined")}})
        csv_rows.append({"scene": scene, "size": size, "kind": "gather_phase", "speedup": gr, "lo": glo, "hi": ghi})
        csv_rows.append({"scene": scene, "size": size, "kind": "precompute_share", "speedup": sh, "lo": shlo, "hi": shhi})
        csv_rows.append({"scene": scene, "size": size, "kind": "memory_increase", "speedup": s["memory"]})
        csv_rows.append({"scene": scene, "size": size, "kind": "work_bound", "speedup": b})
        # item 9: the best configuration per target over every mode
        modes = {f"gather {m}": s["samples"][m] for m in METHODS}
        modes.update(direct.get((scene, size), {}))
        errs = [float(np.mean(e)) for smp in modes.values() for _, e in smp.values()]
        if errs:
            targets = [float(f"{x:.2g}") for x in np.exp(np.linspace(math.log(max(errs)), math.log(min(errs)), TARGETS))]
            best = best_per_target(modes, targets)
            ties = [not_told_apart(modes, row) for row in best]
            lines += ["Which configuration to pick: the cell with the smallest median time among those whose mean "
                      "relMSE reaches each target, over every mode; beside it the other reaching cells whose range of "
                      "times over seeds overlaps its own, which it is not told apart from:", ""]
            lines += report.md_table(["relMSE target", "mode", "setting", "time s", "not told apart from"],
                                     [[fmt(x), m or "none reaches it", setting_label(k), fmt(t),
                                       "; ".join(f"{tm} {setting_label(tk)}" for tm, tk in tie) or "-"]
                                      for (x, m, k, t), tie in zip(best, ties)]) + [""]
            for (x, m, k, t), tie in zip(best, ties):
                csv_rows.append({"scene": scene, "size": size, "kind": "best", "target": x, "mode": m,
                                 "setting": setting_label(k), "conventional_s": t, "ties": len(tie)})
        for row in csv_rows[first:]:
            row.update(ref_noise=grid_refs[(scene, size)]["ref_noise"], ref_bias=grid_refs[(scene, size)]["ref_bias"])
    lines += references_md(grid_refs) + [""]
    report.write_atomic(out + ".md", "\n".join(lines) + "\n")
    report.write_csv_atomic(pd.DataFrame(csv_rows), out + ".csv")
    if figure:
        plot(summaries, figure)


def plot(summaries, path):
    """One panel per grid: both fronts, time against relMSE."""
    from experiments.analysis import plotting
    import matplotlib.pyplot as plt
    n = max(len(summaries), 1)
    cols = min(n, 3)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.4 * rows), squeeze=False)
    for ax, ((scene, size), s) in zip(axes.flat, summaries.items()):
        for m, style in zip(METHODS, ("o-", "s-")):
            keys, t, e, f = fronts(s["samples"][m]) if s["samples"][m] else ([], np.array([]), np.array([]), [])
            if len(keys):
                ax.loglog(e, t, style[0], alpha=0.3, color="C0" if m == METHODS[0] else "C1")
                ax.loglog(e[f], t[f], style, label=m, color="C0" if m == METHODS[0] else "C1")
        ax.set_title(f"{os.path.basename(scene)} {size}", fontsize=9)
        ax.set_xlabel("relMSE")
        ax.set_ylabel("time s")
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(summaries):]:
        ax.axis("off")
    fig.tight_layout()
    plotting.save(fig, path)


def parse_grid_args(items):
    """--grid SCENE SIZE N RUNS_CSV, repeated -> a list of tuples."""
    return [(s, z, int(n), p) for s, z, n, p in items]


def main(argv=None):
    """Command line: see the module docstring; writes OUT.md, OUT.csv and, with --figure, the figure. Exits 1
    when no grid has an ok render, 2 when one scene and size are given two references (--ref), and as its
    readers do on a missing or malformed input."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--grid", nargs=4, action="append", required=True, metavar=("SCENE", "SIZE", "N", "RUNS_CSV"))
    ap.add_argument("--ref", nargs=3, action="append", default=[], metavar=("SCENE", "SIZE", "REF"),
                    help="the reference EXR the grids of SCENE at SIZE are judged against (its own error is reported)")
    ap.add_argument("--direct", nargs=3, action="append", default=[], metavar=("SCENE", "SIZE", "RUNS_CSV"),
                    help="a study of the map seen directly at the same scene and size (item 9)")
    ap.add_argument("--time", default="total_s", choices=sorted(report.TIME_LABEL))
    ap.add_argument("--out", required=True, help="output stem: STEM.md and STEM.csv")
    ap.add_argument("--figure", default="")
    ap.add_argument("--bootstrap", type=int, default=2000)
    ap.add_argument("--bootstrap-seed", type=int, default=1)
    ap.add_argument("--pm", default="")
    a = ap.parse_args(argv)
    runs = load_grids(parse_grid_args(a.grid), a.time)
    if runs.empty:
        report.die("gather.py", "no ok render in any grid")
    direct = {}
    for scene, size, path in a.direct:
        if os.path.isfile(path):
            direct.setdefault((scene, size), {}).update(direct_samples(path, a.time))
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    rng = np.random.default_rng(a.bootstrap_seed)
    refs = {}
    for scene, size, ref in a.ref:
        if refs.get((scene, size), ref) != ref:
            print(f"gather.py: --ref {scene} {size}: two references ({refs[(scene, size)]} and {ref})",
                  file=sys.stderr)
            sys.exit(2)
        refs[(scene, size)] = ref
    write(runs, direct, a.time, a.out, a.figure, rng, a.bootstrap, a.pm, refs)


if __name__ == "__main__":
    main()
