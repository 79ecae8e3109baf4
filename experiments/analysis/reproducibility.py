#!/usr/bin/python3
"""reproducibility.py: two runs of one grid -> how far their results lie apart.

Owns the comparison of runs A and B of `make reproducibility`
(experiments/rules/reproducibility.smk: the same grid, commit and settings, the
pairs of the two runs interleaved in time): per cell and estimate both runs'
paired time ratios (precomputed / conventional, table.py's paired_ratio_*
columns, and the drift control trace_ratio_*) and paired relMSE differences
with their 95% intervals, whether the two intervals overlap, and the
difference of the ratios in percentage points; the median |difference of
the ratios| over the cells against the goal (REPRO_GOAL_PP). The images of
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


def summary(frame, goal_pp):
    """{median_abs_delta_pp, cells, overlap_cells, met, ...} over every
    (cell, estimate) row of FRAME for the main ratio (and the CPU ratio and
    the drift control beside it)."""
    out = {"cells": len(frame), "goal_pp": goal_pp}
    for _, name in RATIOS:
        d = frame[f"{name}_delta_pp"].to_numpy(np.float64) if len(frame) else np.array([])
        d = d[np.isfinite(d)]
        out[f"{name}_median_abs_delta_pp"] = float(np.median(np.abs(d))) if d.size else math.nan
        out[f"{name}_max_abs_delta_pp"] = float(np.max(np.abs(d))) if d.size else math.nan
        out[f"{name}_mean_delta_pp"] = float(np.mean(d)) if d.size else math.nan
        out[f"{name}_overlap_cells"] = int(frame[f"{name}_overlap"].sum()) if len(frame) else 0
    out["relmse_diff_overlap_cells"] = int(frame["relmse_diff_overlap"].sum()) if len(frame) else 0
    m = out["ratio_median_abs_delta_pp"]
    out["met"] = bool(isnum(m) and m <= goal_pp and out["ratio_overlap_cells"] == out["cells"] and out["cells"] > 0)
    return out


def interval_text(row, name, run):
    """'r [lo, hi]' of one run's ratio NAME in ROW."""
    return f"{fmt_fixed(row[f'{name}_{run}'], 1)} [{fmt_fixed(row[f'{name}_{run}_lo'], 1)}, " \
           f"{fmt_fixed(row[f'{name}_{run}_hi'], 1)}]"


def markdown(frame, summ, img_diff, img_n, runs_a, runs_b, taskset, ref_text=""):
    """The text of reproducibility.md."""
    first = runs_a.iloc[0]
    load = pd.concat([runs_a["loadavg_1min"], runs_b["loadavg_1min"]]).to_numpy(np.float64)
    lines = ["# Reproducibility: the grid rendered twice", "",
             f"Runs A and B: the same grid ({first['scene']} at {first['width']}x{first['height']}, "
             f"{first['subpixels']}x{first['subpixels']} subpixels, {int(runs_a['seed'].nunique())} seeds, "
             f"{first['threads']} thread(s)), their pairs interleaved in time (pair k of A, then of B, the order "
             "alternating with k), "
             + (f"every render pinned with `taskset -c {taskset}`" if taskset else "no CPU pinning") + ". "
             f"Machine: {report.machine()}; 1-minute load average at the renders' starts: median "
             f"{fmt(float(np.nanmedian(load)))}, range {fmt(float(np.nanmin(load)))}-{fmt(float(np.nanmax(load)))}; "
             f"commit {report.commit()}; {report.today()}.", "",
             "Ratios are table.py's paired ratios (per-seed log ratio of precomputed to conventional render "
             "time, the renderer's own timer, 95% t interval over seeds), in %; the drift control is the same "
             "ratio of the photon-trace phase (identical code in both methods). delta = A - B in percentage "
             "points (pp).", ""]
    goal = summ["goal_pp"]
    lines += [f"**Goal**: every cell's two intervals overlap and the median |delta| of the time ratios is at most "
              f"{fmt(goal)} pp. **Result**: median |delta| {fmt_fixed(summ['ratio_median_abs_delta_pp'], 2)} pp "
              f"(largest {fmt_fixed(summ['ratio_max_abs_delta_pp'], 2)} pp, mean delta "
              f"{fmt_fixed(summ['ratio_mean_delta_pp'], 2)} pp); the intervals overlap in "
              f"{summ['ratio_overlap_cells']} of {summ['cells']} cells: the goal is "
              + ("**met**." if summ["met"] else "**not met**."), "",
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
    header = ["estimate", "P_e", "n", "ratio A %", "ratio B %", "delta pp", "overlap", "CPU A %", "CPU B %",
              "trace A %", "trace B %", "relMSE diff A", "relMSE diff B"]
    rows = []
    for _, r in frame.iterrows():
        rows.append([r["estimate"], str(r["photons"]), str(r["nn"]), interval_text(r, "ratio", "a"),
                     interval_text(r, "ratio", "b"), fmt_fixed(r["ratio_delta_pp"], 2),
                     "yes" if r["ratio_overlap"] else "**no**", interval_text(r, "cpu_ratio", "a"),
                     interval_text(r, "cpu_ratio", "b"), interval_text(r, "trace_ratio", "a"),
                     interval_text(r, "trace_ratio", "b"),
                     f"{fmt(r['relmse_diff_mean_a'])} [{fmt(r['relmse_diff_lo_a'])}, {fmt(r['relmse_diff_hi_a'])}]",
                     f"{fmt(r['relmse_diff_mean_b'])} [{fmt(r['relmse_diff_lo_b'])}, {fmt(r['relmse_diff_hi_b'])}]"])
    lines += report.md_table(header, rows)
    return "\n".join(lines) + "\n"


def main(argv=None):
    """Entry point; exits 1 on a missing or malformed input."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--table-a", required=True)
    ap.add_argument("--table-b", required=True)
    ap.add_argument("--runs-a", required=True)
    ap.add_argument("--runs-b", required=True)
    ap.add_argument("--goal-pp", type=float, default=3.0)
    ap.add_argument("--taskset", default="")
    ap.add_argument("--ref", default="", help="the reference EXR of the error columns (its JSON beside it, if any)")
    ap.add_argument("--equal-error-a", default="", help="run A's equal-error CSV: the tightest target the reference judges")
    ap.add_argument("--out", required=True, help="stem of OUT.md and OUT.csv")
    args = ap.parse_args(argv)
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
    summ = summary(frame, args.goal_pp)
    img_diff, img_n = max_image_difference(ra, rb)
    out = frame.copy()
    for k, v in summ.items():
        out[f"summary_{k}"] = v
    out["max_relmse_ref_difference"] = img_diff
    report.write_csv_atomic(out, args.out + ".csv")
    ref_text = ""
    if args.ref:
        ref_text = reference.describe(args.ref, reference.tightest_of(args.equal_error_a) if args.equal_error_a else None)
    report.write_atomic(args.out + ".md", markdown(frame, summ, img_diff, img_n, ra, rb, args.taskset, ref_text))


if __name__ == "__main__":
    main()
