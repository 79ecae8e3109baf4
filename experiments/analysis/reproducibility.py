#!/usr/bin/python3
"""reproducibility.py: runs of one grid -> how far their results lie apart.

Owns the comparison of the runs of `make reproducibility`
(experiments/rules/reproducibility.smk: the same grid, commit and settings,
`make reproduce-table` as a user runs it: run A, then run B after every render
of A, then a third run with a busy loop on the other core): per cell and
estimate two runs' paired time ratios (precomputed / conventional, table.py's paired_ratio_*
columns, and the drift control trace_ratio_*) and paired relMSE differences
with their 95% intervals, whether the two intervals overlap, and the
difference of the ratios in percentage points; against the goals: every
cell's intervals overlap, the median |difference of the ratios| over the
cells at most REPRO_GOAL_PP and the largest at most REPRO_MAX_PP, the drift
control inside REPRO_DRIFT in every cell of both runs. The busy run against
A: the median |difference| against REPRO_BUSY_GOAL_PP, and what the load did
to each phase (the median ratio busy / A of each phase's repeat-minimum time
over the renders, per method). Where the noise arises: how far each phase's
repeat minimum moves between A and B (the same render in another process),
the drift control if each render's time were the minimum over the
processes of two or three runs, and the machine's slow spells in each run
(slow_spells: how many processes ran their photon pass slow, whether a
spell outlasts a process, and the groups the gauge left uneven). The images of
one seed are the same bit for bit in both runs (the renderer is
deterministic), so the error columns must agree exactly: the largest
difference of any render's relMSE between the runs is reported, and a
non-zero one is flagged as a failure of determinism, not as noise. The
reference the error columns are judged against is named with its measured
error (reference.describe: noise and kernel bias of a converged reference,
checked against the tightest target of run A's equal-error curve).
Writes OUT.csv (one row per cell and estimate) and OUT.md.
"""

import argparse
import math

import numpy as np
import pandas as pd

from experiments.analysis import reference
from experiments.analysis import report
from experiments.analysis import runs as layout
from experiments.analysis import stats
from experiments.analysis.report import fmt, fmt_fixed, isnum

WHERE = "reproducibility.py"
# (table.py column stem, the name in reproducibility.csv)
RATIOS = (("paired_ratio", "ratio"), ("paired_cpu_ratio", "cpu_ratio"), ("trace_ratio", "trace_ratio"))


def suffix(estimate):
    """Column suffix of an estimate in table.py's CSV: '' for paper."""
    return "" if estimate == "paper" else f"_{estimate}"


def estimates_of(table):
    """The estimates a table1.csv holds (paper, corrected), from its columns."""
    out = ["paper"] if "paired_ratio_percent" in table.columns else []
    out += [c[len("paired_ratio_percent_"):] for c in table.columns if c.startswith("paired_ratio_percent_")]
    return out


def compare(table_a, table_b):
    """One dict per (cell, estimate) of the precomputed rows both tables
    hold: both runs' paired ratios and error differences with intervals,
    overlap flags and the ratio differences in percentage points."""
    rows = []
    a = table_a[table_a["method"] != "conventional"].set_index(["photons", "nn"])
    b = table_b[table_b["method"] != "conventional"].set_index(["photons", "nn"])
    for est in estimates_of(table_a):
        sfx = suffix(est)
        for key in a.index:
            if key not in b.index:
                continue
            ra, rb = a.loc[key], b.loc[key]
            row = {"photons": key[0], "nn": key[1], "estimate": est,
                   "pairs_a": ra.get(f"pairs{sfx}", math.nan), "pairs_b": rb.get(f"pairs{sfx}", math.nan)}
            for stem, name in RATIOS:
                for run, r in (("a", ra), ("b", rb)):
                    for k, col in (("", f"{stem}_percent{sfx}"), ("_lo", f"{stem}_ci95_lo{sfx}"),
                                   ("_hi", f"{stem}_ci95_hi{sfx}")):
                        row[f"{name}_{run}{k}"] = float(r.get(col, math.nan))
                row[f"{name}_delta_pp"] = row[f"{name}_a"] - row[f"{name}_b"]
                row[f"{name}_overlap"] = stats.intervals_overlap((row[f"{name}_a_lo"], row[f"{name}_a_hi"]),
                                                                 (row[f"{name}_b_lo"], row[f"{name}_b_hi"]))
            for run, r in (("a", ra), ("b", rb)):
                for k in ("mean", "lo", "hi"):
                    row[f"relmse_diff_{k}_{run}"] = float(r.get(f"relmse_diff_{k}{sfx}", math.nan))
                row[f"relmse_diff_verdict_{run}"] = r.get(f"relmse_diff_verdict{sfx}", "")
            row["relmse_diff_overlap"] = stats.intervals_overlap(
                (row["relmse_diff_lo_a"], row["relmse_diff_hi_a"]), (row["relmse_diff_lo_b"], row["relmse_diff_hi_b"]))
            rows.append(row)
    return pd.DataFrame(rows)


def max_image_difference(runs_a, runs_b):
    """(largest |relmse_ref A - B| over the renders both runs made ok, renders
    compared): 0 when the two runs' images are the same bit for bit."""
    keys = ["method", "estimate", "photons", "nn", "seed"]
    a = runs_a[runs_a["status"] == "ok"].set_index(keys)["relmse_ref"]
    b = runs_b[runs_b["status"] == "ok"].set_index(keys)["relmse_ref"]
    both = a.index.intersection(b.index)
    if len(both) == 0:
        return math.nan, 0
    return float(np.nanmax(np.abs(a.loc[both].to_numpy() - b.loc[both].to_numpy()))), len(both)


def summary(frame, goal_pp, max_pp=math.inf, drift=(-math.inf, math.inf)):
    """{median_abs_delta_pp, cells, overlap_cells, met, ...} over every
    (cell, estimate) row of FRAME for the main ratio (and the CPU ratio and
    the drift control beside it): met when every cell's intervals overlap,
    the median |delta| is at most GOAL_PP, the largest at most MAX_PP and the
    drift control's point estimate lies in DRIFT (lo, hi %) in every cell of
    both runs."""
    out = {"cells": len(frame), "goal_pp": goal_pp, "max_pp": max_pp, "drift_lo": drift[0], "drift_hi": drift[1]}
    for _, name in RATIOS:
        d = frame[f"{name}_delta_pp"].to_numpy(np.float64) if len(frame) else np.array([])
        d = d[np.isfinite(d)]
        out[f"{name}_median_abs_delta_pp"] = float(np.median(np.abs(d))) if d.size else math.nan
        out[f"{name}_max_abs_delta_pp"] = float(np.max(np.abs(d))) if d.size else math.nan
        out[f"{name}_mean_delta_pp"] = float(np.mean(d)) if d.size else math.nan
        out[f"{name}_overlap_cells"] = int(frame[f"{name}_overlap"].sum()) if len(frame) else 0
    out["relmse_diff_overlap_cells"] = int(frame["relmse_diff_overlap"].sum()) if len(frame) else 0
    tr = frame[["trace_ratio_a", "trace_ratio_b"]].to_numpy(np.float64) if len(frame) else np.zeros((0, 2))
    out["drift_inside_cells"] = int(np.sum(np.all((tr >= drift[0]) & (tr <= drift[1]), axis=1)))
    out["drift_min"] = float(np.nanmin(tr)) if tr.size else math.nan
    out["drift_max"] = float(np.nanmax(tr)) if tr.size else math.nan
    m, mx = out["ratio_median_abs_delta_pp"], out["ratio_max_abs_delta_pp"]
    out["met"] = bool(isnum(m) and m <= goal_pp and isnum(mx) and mx <= max_pp
                      and out["ratio_overlap_cells"] == out["cells"] and out["cells"] > 0
                      and out["drift_inside_cells"] == out["cells"])
    return out


PHASES = ("trace_s", "build_s", "precompute_s", "render_s", "total_s")


KEYS = ["method", "estimate", "photons", "nn", "seed"]


def joined(runs_a, runs_c, phase):
    """(A's, C's) values of PHASE over the renders both runs made ok with a
    positive time, as arrays in one order, and the renders' keys (KEYS)."""
    a = runs_a[runs_a["status"] == "ok"].set_index(KEYS)[phase]
    c = runs_c[runs_c["status"] == "ok"].set_index(KEYS)[phase]
    both = a.index.intersection(c.index)
    va, vc = a.loc[both].to_numpy(np.float64), c.loc[both].to_numpy(np.float64)
    ok = (va > 0) & (vc > 0)
    return va[ok], vc[ok], both[ok]


def phase_load(runs_a, runs_c):
    """One dict per (method, phase) of the ratio C / A of the phase's time
    (each a repeat minimum) over the renders both runs made: its median,
    smallest and largest (median_ratio, min_ratio, max_ratio), the median
    and 90th percentile of |C / A - 1| (median_abs_change, p90_abs_change)
    and the renders compared."""
    rows = []
    for method in sorted(set(runs_a["method"]) & set(runs_c["method"])):
        ma, mc = runs_a[runs_a["method"] == method], runs_c[runs_c["method"] == method]
        for ph in PHASES:
            if ph not in runs_a.columns or ph not in runs_c.columns:
                continue
            va, vc, _ = joined(ma, mc, ph)
            r = vc / va
            q = (lambda f, x: float(f(x)) if x.size else math.nan)  # noqa: E731
            rows.append({"method": method, "phase": ph[:-2], "renders": int(r.size),
                         "median_ratio": q(np.median, r), "min_ratio": q(np.min, r), "max_ratio": q(np.max, r),
                         "median_abs_change": q(np.median, np.abs(r - 1)),
                         "p90_abs_change": q(lambda x: np.percentile(x, 90), np.abs(r - 1))})
    return rows


def process_change(runs_a, runs_b, phase="total_s"):
    """(median, 90th percentile) of |B / A - 1| of PHASE's repeat-minimum
    time over the renders (both methods) both runs made ok: how far the same
    render's time moves between two processes; (nan, nan) without any."""
    va, vb, _ = joined(runs_a, runs_b, phase)
    if not va.size:
        return math.nan, math.nan
    d = np.abs(vb / va - 1)
    return float(np.median(d)), float(np.percentile(d, 90))


def pooled_drift(runs, drift):
    """The drift control if every render's time were the minimum over the
    processes of several runs: RUNS is a list of runs.csv frames of the same
    grid; per (estimate, P_e, n) the paired ratio precomputed / conventional
    of the trace time (stats.paired_log_ratio over the seeds, each time the
    minimum over RUNS' renders of that seed), in %. Returns {"cells",
    "inside" (cells within DRIFT), "min", "max"}; cells 0 when the runs
    share no pair."""
    frames = [r[r["status"] == "ok"].set_index(KEYS)["trace_s"] for r in runs]
    both = frames[0].index
    for f in frames[1:]:
        both = both.intersection(f.index)
    t = pd.concat([f.loc[both] for f in frames], axis=1).min(axis=1).rename("trace_s").reset_index()
    values = []
    for _, g in t.groupby(["estimate", "photons", "nn"]):
        q = g[g["method"] == "precomputed"].set_index("seed")["trace_s"]
        c = g[g["method"] == "conventional"].set_index("seed")["trace_s"]
        seeds = sorted(set(q.index) & set(c.index))
        ratio = stats.paired_log_ratio(q.loc[seeds].to_numpy(), c.loc[seeds].to_numpy())[0]
        if isnum(ratio):
            values.append(100 * ratio)
    v = np.array(values)
    return {"cells": int(v.size), "inside": int(np.sum((v >= drift[0]) & (v <= drift[1]))),
            "min": float(v.min()) if v.size else math.nan, "max": float(v.max()) if v.size else math.nan}


def rounds_only(runs):
    """RUNS with each render's trace_s as the rounds alone timed it: the
    minimum over its first processes - gauge_added processes (the stats'
    time_s_processes), the processes the gauge added (TIME_GAUGE) left
    out. None when no render has an added process or a stats file it
    needs is missing or has no time_s_processes."""
    if "gauge_added" not in runs or not (runs["gauge_added"].fillna(0) > 0).any():
        return None
    out = runs.copy()
    for i, row in runs[runs["gauge_added"].fillna(0) > 0].iterrows():
        try:
            st = layout.load_json(row["run"] + ".stats.json")
            t = st["time_s_processes"]["trace"][: int(row["processes"]) - int(row["gauge_added"])]
        except (layout.RunError, KeyError, TypeError, ValueError):
            return None
        out.at[i, "trace_s"] = min(t)
    return out


def group_processes(runs):
    """{(estimate, P_e, n, seed): [(method, trace seconds)] in the order the
    processes ran} over the ok renders of RUNS: each render's processes'
    photon-pass minima (its stats' time_s_processes; one process: time_s)
    and their places in their rounds (its record's pair_pos_processes;
    process i of a member ran in round i). None when a file is missing or
    has no photon-pass time."""
    groups = {}
    for _, row in runs[runs["status"] == "ok"].iterrows():
        try:
            st = layout.load_json(row["run"] + ".stats.json")
            rec = layout.load_json(row["run"] + ".run.json")
            t = (st.get("time_s_processes") or {}).get("trace") or [st["time_s"]["trace"]]
            pos = rec.get("pair_pos_processes") or [rec.get("pair_pos", 0)] * len(t)
        except (layout.RunError, KeyError, TypeError, ValueError):
            return None
        key = (row["estimate"], int(row["photons"]), int(row["nn"]), int(row["seed"]))
        groups.setdefault(key, []).extend((i, int(p), row["method"], float(x)) for i, (p, x) in enumerate(zip(pos, t)))
    return {k: [(m, x) for _, _, m, x in sorted(v)] for k, v in groups.items()}


def slow_spells(runs, pct):
    """How the machine's slow spells fall on the processes of RUNS (a run of
    the grid): a process is slow when its photon pass (the same work in
    both methods) took more than PCT % over the run's 10th percentile of
    the processes with its photon count. Returns {"processes", "slow" (the
    share of slow processes), "after_slow" (the share of slow processes
    among those that ran right after a slow one of the same group; nan
    without such), "uneven": [(estimate, P_e, n, seed, gap %)] the groups
    whose two members' least photon passes lie more than PCT % apart: one
    member never ran in the state the other caught}, or None without the
    renders' files."""
    groups = group_processes(runs)
    if not groups:
        return None
    by_p = {}
    for (_, photons, _, _), procs in groups.items():
        by_p.setdefault(photons, []).extend(x for _, x in procs)
    ref = {p: float(np.percentile(v, 10)) for p, v in by_p.items()}
    slow, after, uneven = [], [], []
    for key, procs in sorted(groups.items()):
        flags = [x > ref[key[1]] * (1 + pct / 100) for _, x in procs]
        slow += flags
        after += [b for a, b in zip(flags, flags[1:]) if a]
        least = {}
        for m, x in procs:
            least[m] = min(least.get(m, math.inf), x)
        if len(least) == 2:
            gap = 100 * (max(least.values()) / min(least.values()) - 1)
            if gap > pct:
                uneven.append((*key, gap))
    return {"processes": len(slow), "slow": float(np.mean(slow)),
            "after_slow": float(np.mean(after)) if after else math.nan, "uneven": uneven}


def spell_lines(named, pct):
    """Markdown lines on the machine's slow spells in each run of NAMED
    [(name, runs)] (slow_spells); none when no run has its files."""
    rows, unevens = [], []
    for name, runs in named:
        sp = slow_spells(runs, pct) if runs is not None else None
        if sp is None:
            continue
        rows.append([name, str(sp["processes"]), fmt_fixed(100 * sp["slow"], 0), fmt_fixed(100 * sp["after_slow"], 0),
                     str(len(sp["uneven"]))])
        unevens += [f"{name}: {e} P_e={p} n={n} seed {s} ({fmt_fixed(g, 1)}%)" for e, p, n, s, g in sp["uneven"]]
    if not rows:
        return []
    lines = ["", f"The machine's slow spells: a process counts as slow when its photon pass (the same work in both "
             f"methods) took more than {fmt(pct)}% over its run's 10th percentile for its photon count. A spell that "
             "outlasts one process shows as a slow process followed by another more often than slow processes "
             "occur at all; a group whose members' least photon passes lie more than "
             f"{fmt(pct)}% apart after the gauge had one member never catch the state the other did, and its seed's "
             "drift control leans by that much:", ""]
    lines += report.md_table(["run", "processes", "slow %", "slow after a slow one %", "uneven groups"], rows)
    if unevens:
        lines += ["", "Uneven groups: " + "; ".join(unevens) + "."]
    return lines


def noise_lines(runs_a, runs_b, runs_c, drift, pct=4.0):
    """Markdown lines of where the time noise arises: how far a phase's
    repeat minimum moves between two processes of the same render (A and B:
    same bits, same work, another time), and the drift control if each
    render's time were the minimum over the processes of two or three runs."""
    lines = ["## Where the noise arises", "",
             "Each render's time is the minimum over the repeats inside one process. Between two processes of "
             "the same render (A and B: the same bits and the same work counters, another time), that minimum "
             "moves by (|B / A - 1|, over the renders both runs made):", ""]
    lines += report.md_table(["method", "phase", "renders", "median |change| %", "90th percentile %", "range B / A"],
                             [[r["method"], r["phase"], str(r["renders"]), fmt_fixed(100 * r["median_abs_change"], 1),
                               fmt_fixed(100 * r["p90_abs_change"], 1),
                               f"{fmt_fixed(r['min_ratio'], 3)}-{fmt_fixed(r['max_ratio'], 3)}"]
                              for r in phase_load(runs_a, runs_b) if r["renders"] > 0])
    pools = [("A", [runs_a]), ("B", [runs_b]), ("min over A and B", [runs_a, runs_b])]
    if runs_c is not None:
        pools.append(("min over A, B and busy", [runs_a, runs_b, runs_c]))
    rounds = [(name, rounds_only(r)) for name, r in (("A", runs_a), ("B", runs_b))]
    pools += [(f"{name}, the rounds alone (without the gauge's processes)", [r]) for name, r in rounds
              if r is not None]
    lines += ["", "The drift control if each render's time were the minimum over the processes of several runs "
              "(a design with that many more processes per render; the per-seed geometric mean of the trace ratio):", ""]
    rows = []
    for name, rs in pools:
        d = pooled_drift(rs, drift)
        rows.append([name, str(len(rs)), f"{d['inside']} of {d['cells']}",
                     f"{fmt_fixed(d['min'], 1)}-{fmt_fixed(d['max'], 1)}"])
    lines += report.md_table(["renders' times", "runs pooled", f"cells inside [{fmt(drift[0])}%, "
                              f"{fmt(drift[1])}%]", "range %"], rows)
    if any(r is not None for _, r in rounds):
        lines += ["", "The gauge (TIME_GAUGE) adds a process to a render whose least photon pass lies more than "
                  "TIME_GAUGE % above its pair's, so it holds every seed's trace ratio near 100%: the drift "
                  "control of A and B is in part its doing, and the rows \"the rounds alone\" show it without. "
                  "The test it leaves independent is A against B."]
    lines += spell_lines([("A", runs_a), ("B", runs_b), ("busy", runs_c)], pct)
    return lines + [""]


def interval_text(row, name, run):
    """'r [lo, hi]' of one run's ratio NAME in ROW."""
    return f"{fmt_fixed(row[f'{name}_{run}'], 1)} [{fmt_fixed(row[f'{name}_{run}_lo'], 1)}, " \
           f"{fmt_fixed(row[f'{name}_{run}_hi'], 1)}]"


def comparison_table(frame, other):
    """The Markdown table of a comparison FRAME of run A against run OTHER."""
    o = other.upper() if len(other) == 1 else other
    header = ["estimate", "P_e", "n", "ratio A %", f"ratio {o} %", "delta pp", "overlap", "CPU A %", f"CPU {o} %",
              "trace A %", f"trace {o} %", "relMSE diff A", f"relMSE diff {o}"]
    rows = []
    for _, r in frame.iterrows():
        rows.append([r["estimate"], str(r["photons"]), str(r["nn"]), interval_text(r, "ratio", "a"),
                     interval_text(r, "ratio", "b"), fmt_fixed(r["ratio_delta_pp"], 2),
                     "yes" if r["ratio_overlap"] else "**no**", interval_text(r, "cpu_ratio", "a"),
                     interval_text(r, "cpu_ratio", "b"), interval_text(r, "trace_ratio", "a"),
                     interval_text(r, "trace_ratio", "b"),
                     f"{fmt(r['relmse_diff_mean_a'])} [{fmt(r['relmse_diff_lo_a'])}, {fmt(r['relmse_diff_hi_a'])}]",
                     f"{fmt(r['relmse_diff_mean_b'])} [{fmt(r['relmse_diff_lo_b'])}, {fmt(r['relmse_diff_hi_b'])}]"])
    return report.md_table(header, rows)


def load_text(runs):
    """'median M, range LO-HI' of the 1-minute load averages at the renders' starts."""
    load = runs["loadavg_1min"].to_numpy(np.float64)
    return f"median {fmt(float(np.nanmedian(load)))}, range {fmt(float(np.nanmin(load)))}-{fmt(float(np.nanmax(load)))}"


def pinning_text(runs):
    """How the renders of RUNS ran: 'every render pinned to CPU N (...)',
    'pinned to CPUs ...' or 'not pinned' (records without a CPU)."""
    cpus = runs["cpu"].dropna().astype(int).unique() if "cpu" in runs else []
    if len(cpus) == 0:
        return "not pinned"
    if len(cpus) == 1 and runs["cpu"].notna().all():
        return f"every render pinned to CPU {cpus[0]}, as every study's timed renders are (TIME_CPU)"
    return "pinned to CPUs " + ", ".join(str(c) for c in sorted(cpus)) + " (some renders not pinned)"


def processes_text(runs):
    """How many processes each render of RUNS was timed in: 'each render
    timed in N processes, ...' or '' (one, or records before processes)."""
    n = runs["processes"].dropna().astype(int).unique() if "processes" in runs else []
    if len(n) == 0 or (len(n) == 1 and n[0] == 1):
        return ""
    many = "-".join(str(x) for x in sorted({int(min(n)), int(max(n))}))
    g = runs["gauge_added"].fillna(0) if "gauge_added" in runs else pd.Series(dtype=float)
    added = (f"; the photon pass's gauge (TIME_GAUGE) added {int(g.sum())} processes to {int((g > 0).sum())} of "
             f"{len(runs)} renders" if (g > 0).any() else "")
    return (f"; each render timed in {many} processes, the methods alternating (A B B A), its time the minimum "
            f"over every repeat of every process (TIME_PROCESSES){added}")


def markdown(frame, summ, img_diff, img_n, runs_a, runs_b, ref_text="", busy=None, pct=4.0):
    """The text of reproducibility.md; BUSY: (frame, summary, phase rows,
    runs) of the busy run against A, or None. The drift window is SUMM's;
    PCT the gauge's threshold (slow_spells)."""
    first = runs_a.iloc[0]
    lines = ["# Reproducibility: `make reproduce-table` rendered again", "",
             f"Run A is Table 1's own renders; run B is the same grid ({first['scene']} at "
             f"{first['width']}x{first['height']}, {first['subpixels']}x{first['subpixels']} subpixels, "
             f"{int(runs_a['seed'].nunique())} seeds, {first['threads']} thread(s), the same `--repeats`) rendered "
             f"again after every render of A, as a second user would: not interleaved; "
             f"{pinning_text(pd.concat([runs_a, runs_b]))}{processes_text(pd.concat([runs_a, runs_b]))}. "
             f"Machine: {report.machine()}; 1-minute load average at the renders' starts: A {load_text(runs_a)}, "
             f"B {load_text(runs_b)}; commit {report.commit()}; {report.today()}.", "",
             "Ratios are table.py's paired ratios (per-seed log ratio of precomputed to conventional render "
             "time, each time the minimum of the render's repeats, 95% t interval over seeds), in %; the drift "
             "control is the same ratio of the photon-trace phase (identical code in both methods, so 100% but "
             "for noise). delta = A - B in percentage points (pp).", ""]
    dl, dh = summ["drift_lo"], summ["drift_hi"]
    lines += [f"**Goal**: in every cell the two intervals overlap, the median |delta| of the time ratios is at most "
              f"{fmt(summ['goal_pp'])} pp and the largest at most {fmt(summ['max_pp'])} pp, and the drift control "
              f"lies within [{fmt(dl)}%, {fmt(dh)}%] in every cell of both runs. **Result**: median |delta| "
              f"{fmt_fixed(summ['ratio_median_abs_delta_pp'], 2)} pp, largest "
              f"{fmt_fixed(summ['ratio_max_abs_delta_pp'], 2)} pp (mean delta "
              f"{fmt_fixed(summ['ratio_mean_delta_pp'], 2)} pp); the intervals overlap in "
              f"{summ['ratio_overlap_cells']} of {summ['cells']} cells; the drift control lies inside in "
              f"{summ['drift_inside_cells']} of {summ['cells']} cells (range {fmt_fixed(summ['drift_min'], 1)}%-"
              f"{fmt_fixed(summ['drift_max'], 1)}%): the goal is " + ("**met**." if summ["met"] else "**not met**."), "",
              f"CPU-time ratio (secondary): median |delta| {fmt_fixed(summ['cpu_ratio_median_abs_delta_pp'], 2)} pp, "
              f"overlap in {summ['cpu_ratio_overlap_cells']} of {summ['cells']} cells. Drift control: median "
              f"|delta| {fmt_fixed(summ['trace_ratio_median_abs_delta_pp'], 2)} pp.", ""]
    if ref_text:
        lines += [ref_text, ""]
    if isnum(img_diff):
        lines += [f"Errors: over the {img_n} renders both runs made, the largest difference of a render's relMSE "
                  f"between A and B is {fmt(img_diff)}"
                  + (" (the images are the same bit for bit: the error columns reproduce exactly, and so does "
                     "every paired error difference)." if img_diff == 0 else
                     ": **not zero**: the renderer was not deterministic between the runs (a bug, not noise)."),
                  f"The paired relMSE differences' intervals overlap in {summ['relmse_diff_overlap_cells']} of "
                  f"{summ['cells']} cells.", ""]
    lines += ["## A against B", ""] + comparison_table(frame, "b") + [""]
    if "trace_s" in runs_a.columns and "trace_s" in runs_b.columns:
        lines += noise_lines(runs_a, runs_b, busy[3] if busy is not None else None,
                             (summ["drift_lo"], summ["drift_hi"]), pct)
    if busy is not None:
        bframe, bsumm, phases, runs_c = busy
        lines += ["## A against the run with a busy loop on the other core", "",
                  "The same grid a third time, after B, with a process spinning in a loop beside every render "
                  f"(`launch.py --busy-loop`; load at the renders' starts {load_text(runs_c)}). "
                  f"**Goal**: median |delta| at most {fmt(bsumm['goal_pp'])} pp. **Result**: median |delta| "
                  f"{fmt_fixed(bsumm['ratio_median_abs_delta_pp'], 2)} pp, largest "
                  f"{fmt_fixed(bsumm['ratio_max_abs_delta_pp'], 2)} pp, mean delta (A - busy) "
                  f"{fmt_fixed(bsumm['ratio_mean_delta_pp'], 2)} pp; the intervals overlap in "
                  f"{bsumm['ratio_overlap_cells']} of {bsumm['cells']} cells: the goal is "
                  + ("**met**." if isnum(bsumm["ratio_median_abs_delta_pp"])
                     and bsumm["ratio_median_abs_delta_pp"] <= bsumm["goal_pp"] else "**not met**."), "",
                  "What the loop did to each phase: the ratio busy / A of the phase's time (the minimum of its "
                  "repeats), over the renders both runs made (a phase of under 1 ms is noise):", ""]
        lines += report.md_table(["method", "phase", "renders", "median busy / A", "range"],
                                 [[r["method"], r["phase"], str(r["renders"]), fmt_fixed(r["median_ratio"], 3),
                                   f"{fmt_fixed(r['min_ratio'], 3)}-{fmt_fixed(r['max_ratio'], 3)}"]
                                  for r in phases if r["renders"] > 0])
        lines += ["", "### The table", ""] + comparison_table(bframe, "busy") + [""]
    return "\n".join(lines) + "\n"


def main(argv=None):
    """Entry point; exits 1 on a missing or malformed input."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--table-a", required=True)
    ap.add_argument("--table-b", required=True)
    ap.add_argument("--runs-a", required=True)
    ap.add_argument("--runs-b", required=True)
    ap.add_argument("--table-busy", default="", help="the busy run's table1.csv (optional)")
    ap.add_argument("--runs-busy", default="", help="the busy run's runs.csv (with --table-busy)")
    ap.add_argument("--goal-pp", type=float, default=1.5)
    ap.add_argument("--max-pp", type=float, default=4.0)
    ap.add_argument("--busy-goal-pp", type=float, default=3.0)
    ap.add_argument("--drift", default="97 103", help="'LO HI': the drift control's window, %%")
    ap.add_argument("--gauge", type=float, default=4.0,
                    help="TIME_GAUGE: a process is slow, a group uneven, above this %% (the machine's slow spells; 0: 4)")
    ap.add_argument("--ref", default="", help="the reference EXR of the error columns (its JSON beside it, if any)")
    ap.add_argument("--equal-error-a", default="", help="run A's equal-error CSV: the tightest target the reference judges")
    ap.add_argument("--out", required=True, help="stem of OUT.md and OUT.csv")
    args = ap.parse_args(argv)
    try:
        drift = tuple(float(x) for x in args.drift.split())
        assert len(drift) == 2
    except (ValueError, AssertionError):
        report.die(WHERE, f"--drift '{args.drift}': not 'LO HI' in %")
    need_t = ["photons", "nn", "method", "paired_ratio_percent", "paired_ratio_ci95_lo", "paired_ratio_ci95_hi"]
    ta = report.read_csv(args.table_a, need_t, WHERE)
    tb = report.read_csv(args.table_b, need_t, WHERE)
    need_r = ["scene", "width", "height", "subpixels", "threads", "method", "estimate", "photons", "nn", "seed",
              "status", "relmse_ref", "loadavg_1min"]
    ra = report.read_csv(args.runs_a, need_r, WHERE)
    rb = report.read_csv(args.runs_b, need_r, WHERE)
    frame = compare(ta, tb)
    if frame.empty:
        report.die(WHERE, "the two tables share no precomputed cell")
    summ = summary(frame, args.goal_pp, args.max_pp, drift)
    img_diff, img_n = max_image_difference(ra, rb)
    out = frame.copy()
    out.insert(0, "runs", "a-b")
    for k, v in summ.items():
        out[f"summary_{k}"] = v
    out["max_relmse_ref_difference"] = img_diff
    rc = report.read_csv(args.runs_busy, need_r, WHERE) if args.table_busy else None
    if all("trace_s" in r.columns and "total_s" in r.columns for r in (ra, rb)):
        # where the noise arises (noise_lines): the same render in two
        # processes, and the drift control timed over two or three runs
        out["summary_process_change_median"], out["summary_process_change_p90"] = process_change(ra, rb)
        out["summary_drift_inside_cells_a"] = pooled_drift([ra], drift)["inside"]
        out["summary_drift_inside_cells_b"] = pooled_drift([rb], drift)["inside"]
        out["summary_drift_inside_cells_min2"] = pooled_drift([ra, rb], drift)["inside"]
        if rc is not None and "trace_s" in rc.columns:
            out["summary_drift_inside_cells_min3"] = pooled_drift([ra, rb, rc], drift)["inside"]
    busy = None
    if args.table_busy:
        tc = report.read_csv(args.table_busy, need_t, WHERE)
        bframe = compare(ta, tc)
        bsumm = summary(bframe, args.busy_goal_pp)
        busy = (bframe, bsumm, phase_load(ra, rc), rc)
        bout = bframe.copy()
        bout.insert(0, "runs", "a-busy")
        for k, v in bsumm.items():
            bout[f"summary_{k}"] = v
        out = pd.concat([out, bout], ignore_index=True)
    report.write_csv_atomic(out, args.out + ".csv")
    ref_text = ""
    if args.ref:
        ref_text = reference.describe(args.ref, reference.tightest_of(args.equal_error_a) if args.equal_error_a else None)
    report.write_atomic(args.out + ".md", markdown(frame, summ, img_diff, img_n, ra, rb, ref_text, busy,
                                                    args.gauge if args.gauge > 0 else 4.0))


if __name__ == "__main__":
    main()
