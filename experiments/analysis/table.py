#!/usr/bin/python3
"""table.py: runs.csv + cells.csv -> Table 1 as CSV and Markdown.

Owns the per-(P_e, n, method) summary over seeds and how it is shown: the
paper's time and ratio (experiments/paper-table1.csv) beside ours (median
over seeds with min-max; the precomputed/conventional time ratio as the
paired per-seed log ratio with a t interval over seeds), per-phase medians, and per estimate the error
against the reference (mean over seeds with a 95% t-interval, bias and
variance over seeds from cells.csv), the error against the conventional
image of the same seed, the reference floor, and the paired comparisons with
the conventional cell (time ratios over the pairs of renders of one seed,
the drift control, the relMSE difference with its Holm-corrected verdict),
and beside the measured time ratio the calibrated cost model's ratio from
the same renders' work counters (experiments/calibrate.py; "no model"
without one), naming the phase and the counter that explain the two
ratios' difference where it exceeds the model's validation error.
Columns of the estimate
"paper" have no suffix, those of another estimate E the suffix _E
(relmse_ref_mean_corrected, ...). The Markdown compares the two methods
paired (stats.compare_family) and ranks other numbers only when their 95%
intervals are disjoint.
"""

import argparse
import math
import os
import sys

import numpy as np
import pandas as pd

from experiments import calibrate
from experiments.analysis import metrics
from experiments.analysis import report
from experiments.analysis import runs as layout
from experiments.analysis import stats
from experiments.analysis.report import fmt, fmt_ci, fmt_pm, fmt_range, isnum

PHASES = ("trace", "build", "precompute", "render")
# the runs.csv column of the error the table reports (metrics.PRIMARY; its
# output columns keep the names relmse_* whatever PRIMARY is)
ERR = metrics.PRIMARY_COLUMN


def suffix(estimate):
    """Column suffix of an estimate: '' for the paper's, '_E' otherwise."""
    return "" if estimate == "paper" else f"_{estimate}"


def read_inputs(runs_csv, cells_csv, paper_csv):
    """The three tables, with the columns this script needs checked by name."""
    frames = []
    for path, need in ((runs_csv, ["method", "estimate", "photons", "nn", "seed", "status", "role", "total_s",
                                   "cpu_s", "trace_s", ERR, "relmse_conv", "message"]),
                       (cells_csv, ["method", "estimate", "photons", "nn", "bias_ref", "variance_ref",
                                    "relmse_ref_floor", "ref", "ref_fast"]),
                       (paper_csv, ["emitted_kphotons", "nn", "conventional_s", "proposed_s", "ratio_percent"])):
        frames.append(report.read_csv(path, need, "table.py", comment="#"))
    runs, cells, paper = frames
    runs["message"] = runs["message"].fillna("")
    return runs, cells, paper


def ok_values(frame, column):
    """The COLUMN values of the ok runs in FRAME, as a float array."""
    return frame.loc[frame["status"] == "ok", column].to_numpy(dtype=np.float64)


def summarize(runs, cells, paper, model=None):
    """One dict per (photons, nn, method) of the grid: the table1.csv row.
    MODEL: (model, validation) of calibrate.load_model, or None."""
    grid = runs[runs["role"] == "grid"]
    conv_all = runs[runs["role"] == "comparison"] if (runs["role"] == "comparison").any() \
        else grid[grid["method"] == "conventional"]
    estimates = list(dict.fromkeys(grid["estimate"]))
    keys = list(dict.fromkeys(zip(grid["photons"], grid["nn"], grid["method"])))
    first = grid.iloc[0]
    rows = []
    for photons, nn, method in keys:
        row = {"photons": photons, "nn": nn, "method": method, "width": first["width"], "height": first["height"],
               "subpixels": first["subpixels"], "tag": first["tag"] if isinstance(first["tag"], str) else ""}
        row["paper_s"] = row["paper_ratio_percent"] = row["paper_conv_s"] = math.nan
        pap = paper[(paper["emitted_kphotons"] * 1000 == photons) & (paper["nn"] == nn)]
        if len(pap):
            p = pap.iloc[0]
            row["paper_conv_s"] = p["conventional_s"]
            row["paper_s"] = p["conventional_s"] if method == "conventional" else p["proposed_s"]
            row["paper_ratio_percent"] = 100.0 if method == "conventional" else p["ratio_percent"]
        for est in estimates:
            sfx = suffix(est)
            sel = grid[(grid["photons"] == photons) & (grid["nn"] == nn) & (grid["method"] == method)
                       & (grid["estimate"] == est)]
            conv = conv_all[(conv_all["photons"] == photons) & (conv_all["nn"] == nn) & (conv_all["estimate"] == est)]
            counts = sel["status"].value_counts()
            row[f"seeds{sfx}"] = int(counts.get("ok", 0))
            row[f"seeds_refused{sfx}"] = int(counts.get("refused", 0))
            row[f"seeds_missing{sfx}"] = int(counts.get("missing", 0))
            refused = sel.loc[sel["status"] == "refused", "message"]
            row[f"refusal{sfx}"] = refused.iloc[0] if len(refused) else ""
            if "threads" in sel and (sel["status"] == "ok").any():
                row["threads"] = int(sel.loc[sel["status"] == "ok", "threads"].iloc[0])
            for col, name in (("total_s", "total"), ("cpu_s", "cpu")):
                med, lo, hi = stats.median_range(ok_values(sel, col))
                row[f"{name}_median_s{sfx}"], row[f"{name}_min_s{sfx}"], row[f"{name}_max_s{sfx}"] = med, lo, hi
            for ph in PHASES:
                row[f"{ph}_median_s{sfx}"] = stats.median_range(ok_values(sel, f"{ph}_s"))[0]
            a, b = paired_values(sel, conv, ("total_s", "cpu_s", "trace_s", ERR))
            row[f"pairs{sfx}"] = len(a["total_s"])
            # every time ratio: the per-seed log ratios of the repeats' minima,
            # t interval over seeds (a percentile bootstrap at 3-5 seeds covers
            # far below 95%)
            for col, name in (("total_s", "ratio"), ("cpu_s", "cpu_ratio")) + PAIRED_RATIOS:
                r, lo, hi, _ = stats.paired_log_ratio(a[col], b[col])
                row[f"{name}_percent{sfx}"] = 100 * r
                row[f"{name}_ci95_lo{sfx}"], row[f"{name}_ci95_hi{sfx}"] = 100 * lo, 100 * hi
            row.update(model_columns(model, sel, conv, sfx, (row[f"paired_ratio_ci95_lo{sfx}"] / 100,
                                                             row[f"paired_ratio_ci95_hi{sfx}"] / 100)))
            d = stats.paired_difference(a[ERR], b[ERR])
            for k in ("mean", "lo", "hi", "p", "delta", "relative"):
                row[f"relmse_diff_{k}{sfx}"] = d[k]
            row[f"relmse_diff_equivalent{sfx}"] = d["equivalent"]
            for col in ("photons_stored", "representatives", "empty_estimates"):
                row[f"{col}{sfx}"] = stats.median_range(ok_values(sel, col))[0]
            for col in dict.fromkeys((ERR, "relmse_ref", "nmse_ref", "psnr_ref", "relmse_conv")):
                if col not in sel:  # a runs.csv from before NMSE
                    continue
                v = ok_values(sel, col)
                v = v[np.isfinite(v)]
                row[f"{col}_mean{sfx}"], row[f"{col}_ci95{sfx}"] = stats.t_interval(v)
            cell = cells[(cells["photons"] == photons) & (cells["nn"] == nn) & (cells["method"] == method)
                         & (cells["estimate"] == est)]
            # the conventional cell this row is compared with (itself for a
            # conventional row of the grid; CONV_RUNROOT's for a variant)
            for col, name in (("total_s", "total"), ("cpu_s", "cpu")):
                med, lo, hi = stats.median_range(ok_values(conv, col))
                row[f"conv_{name}_median_s{sfx}"], row[f"conv_{name}_min_s{sfx}"], row[f"conv_{name}_max_s{sfx}"] = \
                    med, lo, hi
            v = ok_values(conv, ERR)
            row[f"conv_relmse_ref_mean{sfx}"], row[f"conv_relmse_ref_ci95{sfx}"] = stats.t_interval(v[np.isfinite(v)])
            row[f"bias_ref{sfx}"] = cell["bias_ref"].iloc[0] if len(cell) else math.nan
            row[f"variance_ref{sfx}"] = cell["variance_ref"].iloc[0] if len(cell) else math.nan
        row["relmse_ref_floor"] = cells["relmse_ref_floor"].iloc[0] if len(cells) else math.nan
        rows.append(row)
    # the paired error comparisons of a table are one family: Holm over its cells
    for est in estimates:
        sfx = suffix(est)
        fam = [r for r in rows if r["method"] != "conventional"]
        comps = stats.compare_family([{"p": r[f"relmse_diff_p{sfx}"], "mean": r[f"relmse_diff_mean{sfx}"],
                                       "equivalent": r[f"relmse_diff_equivalent{sfx}"]} for r in fam])
        for r in rows:
            r[f"relmse_diff_p_holm{sfx}"], r[f"relmse_diff_verdict{sfx}"] = math.nan, ""
        for r, c in zip(fam, comps):
            r[f"relmse_diff_p_holm{sfx}"] = c["p_holm"]
            r[f"relmse_diff_verdict{sfx}"] = c["verdict"] if r[f"pairs{sfx}"] else ""
    return pd.DataFrame(rows), estimates


# the paired time ratios (precomputed / conventional, the same seed, rendered
# back to back): the renderer's own total, the process CPU (secondary) and
# the drift control, the photon trace (the same code in both methods: 1 when
# the machine did not drift between the two renders of a pair)
PAIRED_RATIOS = (("total_s", "paired_ratio"), ("cpu_s", "paired_cpu_ratio"), ("trace_s", "trace_ratio"))


def model_rows(sel, conv):
    """The pairs of calibrate's rows ({"work", "time"}) of the seeds where
    both SEL and CONV rendered ok: the work counters from each render's
    stats file, the times (the repeats' minima) from runs.csv; None when a
    stats file is not there (a runs.csv without its renders) or has no
    counters."""
    a = sel[sel["status"] == "ok"].drop_duplicates("seed").set_index("seed")
    b = conv[conv["status"] == "ok"].drop_duplicates("seed").set_index("seed")
    out = ([], [])
    for seed in sorted(set(a.index) & set(b.index)):
        for frame, rows in ((a, out[0]), (b, out[1])):
            r = frame.loc[seed]
            if not os.path.isfile(r["run"] + ".stats.json"):
                return None
            stats = layout.load_json(r["run"] + ".stats.json")
            if stats.get("work") is None:
                return None
            rows.append({"work": stats["work"], "time": {**{ph: float(r[f"{ph}_s"]) for ph in PHASES},
                                                         "total": float(r["total_s"])}})
    return out


def model_disagrees(lo, hi, q, err):
    """True when the model's ratio Q, give or take its relative error ERR
    (the band [Q / (1 + ERR), Q (1 + ERR)]), lies wholly outside the
    measured ratio's 95% interval [LO, HI]; False where they overlap or the
    interval is undefined (fewer than two pairs): a disagreement is claimed
    only where neither the measurement's noise nor the model's error covers
    it."""
    if not (isnum(lo) and isnum(hi) and isnum(q)):
        return False
    return q * (1 + err) < lo or q / (1 + err) > hi


def model_columns(model, sel, conv, sfx, measured):
    """The cost model's columns of one cell against its conventional cell:
    model_ratio_percent (the model's paired ratio of the predicted totals),
    model_differs (model_disagrees: the model's ratio, give or take its
    validation error, the held-out median relative error of the total, lies
    outside MEASURED, the measured paired ratio's 95% interval (lo, hi) as
    fractions), model_phase and model_counter (calibrate.explain, where they
    differ); nan / False / "" without a model or counters."""
    out = {f"model_ratio_percent{sfx}": math.nan, f"model_differs{sfx}": False, f"model_phase{sfx}": "",
           f"model_counter{sfx}": ""}
    if model is None:
        return out
    pairs = model_rows(sel, conv)
    if not pairs or not pairs[0]:
        return out
    coef, validation = model
    q = calibrate.model_ratio(coef, *pairs)
    out[f"model_ratio_percent{sfx}"] = 100 * q
    if model_disagrees(*measured, q, validation["median"]):
        phase, name = calibrate.explain(coef, *pairs)
        out.update({f"model_differs{sfx}": True, f"model_phase{sfx}": phase, f"model_counter{sfx}": name})
    return out


def model_text(row, model, sfx=""):
    """The model's ratio as the Markdown shows it: "no model" without one."""
    if model is None:
        return "no model"
    return fmt(row.get(f"model_ratio_percent{sfx}", math.nan)) if len(row) else "n/a"


def model_lines(table, model, estimates, problem=""):
    """Markdown lines: the model's validation error and, per estimate, the
    cells where the measured and the model's ratio differ by more, with the
    phase and the counter that explain it; without a model, why (PROBLEM:
    the model file that could not be used, and the reason)."""
    if model is None:
        why = f" ({problem})" if problem else ""
        return ["", f"Model ratio: no model{why} (`make calibrate` writes `{calibrate.DEFAULT_MODEL}`, this machine's "
                "cost model; the table then gives its predicted ratio beside the measured one)."]
    err = model[1]["median"]
    out = ["", f"Model ratio: the calibrated cost model's (`{calibrate.DEFAULT_MODEL}`, validation error: median "
           f"{100 * err:.1f}%, largest {100 * model[1]['largest']:.1f}% of a held-out render's total) paired "
           "ratio of the predicted totals, from the same renders' work counters."]
    for est in estimates:
        sfx = suffix(est)
        col = f"model_differs{sfx}"
        if col not in table:
            continue
        rows = [r for _, r in table.iterrows() if bool(r[col])]
        if not rows:
            out.append(f"- {est} estimate: in every cell the model's ratio, give or take its error, overlaps the "
                       "measured ratio's 95% interval (no disagreement shown; overlap is not a test of agreement).")
            continue
        out.append(f"- {est} estimate: the model's ratio, give or take its error, lies outside the measured ratio's "
                   "95% interval in "
                   + "; ".join(f"{cell_label(r)} (measured {fmt(r.get(f'paired_ratio_percent{sfx}'))}% "
                               f"[{fmt(r.get(f'paired_ratio_ci95_lo{sfx}'))}, "
                               f"{fmt(r.get(f'paired_ratio_ci95_hi{sfx}'))}], model "
                               f"{fmt(r.get(f'model_ratio_percent{sfx}'))}%: phase {r[f'model_phase{sfx}']}, counter "
                               f"{r[f'model_counter{sfx}']})" for r in rows) + ".")
    return out


def paired_values(sel, conv, columns):
    """({column: values}, {column: values}) of the seeds where both SEL
    (one cell) and CONV (its conventional cell) rendered ok, in the same
    seed order: the pairs of a paired comparison."""
    a = sel[sel["status"] == "ok"].drop_duplicates("seed").set_index("seed")
    b = conv[conv["status"] == "ok"].drop_duplicates("seed").set_index("seed")
    seeds = sorted(set(a.index) & set(b.index))
    return ({c: a.loc[seeds, c].to_numpy(np.float64) for c in columns},
            {c: b.loc[seeds, c].to_numpy(np.float64) for c in columns})


def interval(row, col, sfx=""):
    """The 95% t-interval (lo, hi) of column COL's mean in ROW."""
    m, h = row.get(f"{col}_mean{sfx}", math.nan), row.get(f"{col}_ci95{sfx}", math.nan)
    return (m - h, m + h) if isnum(m) and isnum(h) else (math.nan, math.nan)


def cell_label(row):
    """'(50k, 10)' for a table row: (P_e, n)."""
    p = row["photons"]
    return f"({p // 1000}k, {row['nn']})" if p % 1000 == 0 else f"({p}, {row['nn']})"


def cell_list(labels):
    """'cells (P_e, n) = (50k, 10), (100k, 20)' for a list of cell labels."""
    return "cell (P_e, n) = " + labels[0] if len(labels) == 1 else "cells (P_e, n) = " + ", ".join(labels)


def ranked_clauses(pairs):
    """'TEXT in CELLS' for each (text, cell labels) pair with any labels,
    joined by '; '."""
    return "; ".join(f"{text} in {cell_list(labels)}" for text, labels in pairs if labels)


def estimate_comparisons(runs, est, method):
    """(cell labels, paired_difference dicts with compare_family's
    verdicts) of one METHOD's error (ERR) with estimate EST against the
    paper estimate's, per cell, paired per seed (the same photon map and
    render but for the estimate), Holm over the cells; the conventional
    renders are the comparison ones where there are any."""
    ok = runs[(runs["status"] == "ok") & (runs["method"] == method)]
    role = "comparison" if method == "conventional" and (ok["role"] == "comparison").any() else "grid"
    ok = ok[ok["role"] == role]
    m = ok[ok["estimate"] == est].merge(ok[ok["estimate"] == "paper"], on=["photons", "nn", "seed"],
                                        suffixes=("", "_paper"))
    return stats.paired_family((cell_label({"photons": int(p), "nn": int(n)}), g[ERR].astype(float),
                                g[f"{ERR}_paper"].astype(float)) for (p, n), g in m.groupby(["photons", "nn"], sort=True))


def rank_sentences(table, estimates, runs=None):
    """Markdown lines that rank numbers only where the 95% intervals are
    disjoint, and name the cells where they overlap; the estimates' errors
    against each other are compared paired per seed (RUNS, the grid's
    renders), Holm over the cells."""
    lines = []
    prec = [r for _, r in table.iterrows() if r["method"] != "conventional"]
    if "paper" in estimates and prec:
        below, above, other = [], [], []
        for p in prec:
            lo, hi = p.get("paired_ratio_ci95_lo", math.nan), p.get("paired_ratio_ci95_hi", math.nan)
            if isnum(hi) and hi < 100:
                below.append(cell_label(p))
            elif isnum(lo) and lo > 100:
                above.append(cell_label(p))
            else:
                other.append(cell_label(p))
        parts = [f"lies below 100% (precomputed faster) in {len(below)} of {len(prec)} cells",
                 ranked_clauses([("above 100% (precomputed slower)", above),
                                 ("contains 100% or is unknown (no ranking)", other)])]
        lines.append("- **Time** (paper estimate, the renderer's own timer, paired over seeds): the "
                     "precomputed/conventional ratio's 95% interval "
                     + "; ".join(p for p in parts if p) + ".")
    if prec:
        lines.append("- **Error, precomputed vs conventional**: the paired comparison above (same seed, Holm over "
                     "the cells; \"equivalent\" only within its margin delta).")
    if "paper" in estimates and len(estimates) > 1 and runs is not None:
        m = f"{100 * stats.EQUIVALENCE_MARGIN:g}%"
        for est in [e for e in estimates if e != "paper"]:
            for method in ("conventional", "precomputed"):
                labels, comps = estimate_comparisons(runs, est, method)
                by = {"higher": [], "lower": [], "equivalent": [], "undetermined": []}
                for lab, c in zip(labels, comps):
                    by[c["verdict"]].append(lab)
                if labels:
                    parts = ranked_clauses([(f"{est} lower", by["lower"]), (f"{est} higher", by["higher"]),
                                            (f"equivalent within {m}", by["equivalent"]),
                                            ("undetermined (neither ranked nor within the margin)",
                                             by["undetermined"])])
                    lines.append(f"- **{est} vs paper estimate, {method}** (relMSE against the reference, paired "
                                 f"per seed, Holm over the {len(labels)} cells; equivalent: the 95% interval of the "
                                 f"difference inside +-{m} of the paper estimate's): " + parts + ".")
    floor = table["relmse_ref_floor"].iloc[0] if len(table) else math.nan
    if isnum(floor):
        for est in estimates:
            sfx = suffix(est)
            if not table[f"bias_ref{sfx}"].notna().any():
                continue
            low = [f"{cell_label(r)} {r['method']}" for _, r in table.iterrows()
                   if isnum(r.get(f"bias_ref{sfx}")) and r[f"bias_ref{sfx}"] <= floor]
            if low:
                lines.append(f"- **Reference-limited** ({est} estimate): the bias term is at or below the reference "
                             f"floor ({fmt(floor)}) in (P_e, n) = {', '.join(low)}: there the reference, not the method, limits "
                             f"what the bias column can show.")
            else:
                lines.append(f"- **Reference floor** ({est} estimate): every bias term is above the floor "
                             f"({fmt(floor)}).")
    return lines


VERDICT_TEXT = {"higher": "precomputed higher", "lower": "precomputed lower",
                "equivalent": "equivalent within ±delta", "undetermined": "undetermined"}


def paired_section(table, estimates):
    """Markdown lines of the paired comparisons: per precomputed cell and
    estimate the paired time ratios (with the drift control) and the paired
    relMSE difference with its Holm-corrected verdict (stats.compare_family)."""
    out = []
    for est in estimates:
        sfx = suffix(est)
        prec = [r for _, r in table.iterrows() if r["method"] != "conventional" and r.get(f"pairs{sfx}", 0) > 0]
        if not prec:
            continue
        out += ["", f"## Paired: precomputed against conventional, the same seed ({est} estimate)", "",
                "Per seed the two renders share the photon map and ran back to back (rule `pair` of "
                "`experiments/rules/render.smk`: the order alternates with the seed). "
                "Time ratios: exp of the mean over seeds of log(precomputed / "
                "conventional), with the exponentiated 95% t-interval of that mean; s: the renderer's own total "
                "(`time_s.total`: no start-up, no image writing), CPU: the process (`/usr/bin/time`, secondary); "
                "trace: the photon-trace phase, the same code in both methods, the **drift control** (100% when the "
                "machine did not change between the two renders of a pair). relMSE difference: mean over seeds of "
                "precomputed − conventional relMSE against the reference, 95% t-interval, two-sided paired t-test "
                f"with Holm's correction over the {len(prec)} cells of this table (p Holm); \"equivalent\" only when "
                f"the 95% interval lies inside ±delta, delta = {100 * stats.EQUIVALENCE_MARGIN:g}% of the "
                "conventional mean relMSE (`stats.EQUIVALENCE_MARGIN`); otherwise \"undetermined\" "
                "(`stats.compare_family`).", ""]
        rows = []
        for r in prec:
            g = (lambda k: r.get(f"{k}{sfx}", math.nan))
            rows.append([r["photons"], r["nn"], int(g("pairs")),
                         fmt_ci(g("paired_ratio_percent"), g("paired_ratio_ci95_lo"), g("paired_ratio_ci95_hi"), 1),
                         fmt_ci(g("paired_cpu_ratio_percent"), g("paired_cpu_ratio_ci95_lo"),
                                g("paired_cpu_ratio_ci95_hi"), 1),
                         fmt_ci(g("trace_ratio_percent"), g("trace_ratio_ci95_lo"), g("trace_ratio_ci95_hi"), 1),
                         f"{fmt(g('relmse_diff_mean'))} {report.fmt_interval(g('relmse_diff_lo'), g('relmse_diff_hi'))}",
                         fmt(100 * g("relmse_diff_relative")), fmt(g("relmse_diff_delta")), fmt(g("relmse_diff_p_holm")),
                         VERDICT_TEXT.get(g("relmse_diff_verdict"), "")])
        out += report.md_table(["P_e", "n", "pairs", "time ratio % [95% CI]", "CPU ratio % [95% CI]",
                                "trace ratio % (drift) [95% CI]", "relMSE prec. − conv. [95% CI]", "diff. %",
                                "delta", "p Holm", "verdict"], rows, ["r"] * 10 + ["l"])
        by = {}
        for r in prec:
            by.setdefault(r.get(f"relmse_diff_verdict{sfx}", ""), []).append(cell_label(r))
        parts = ranked_clauses([(VERDICT_TEXT[v], by.get(v, [])) for v in ("higher", "lower", "equivalent",
                                                                             "undetermined")])
        out += ["", f"- **Error, paired** ({est} estimate, Holm over {len(prec)} cells): {parts}."]
    return out


def markdown(table, runs, estimates, args):
    """The Markdown text of the table."""
    grid = runs[runs["role"] == "grid"]
    n_ok, n_ref = int((grid["status"] == "ok").sum()), int((grid["status"] == "refused").sum())
    n_miss = int((grid["status"] == "missing").sum())
    first = grid.iloc[0]
    seeds = " ".join(str(s) for s in sorted(set(grid["seed"])))
    stem = os.path.basename(args.out)
    cells_ref, cells_fast = args.ref, args.ref_fast
    floor = table["relmse_ref_floor"].iloc[0]
    load = grid.loc[grid["status"] != "missing", "loadavg_1min"].to_numpy(dtype=np.float64)
    load_med, load_lo, load_hi = stats.median_range(load)
    threads = table["threads"].dropna().iloc[0] if "threads" in table and table["threads"].notna().any() else "n/a"
    out = [
        "# Table 1, reproduced, over seeds",
        "",
        f"Generated by `make reproduce-table` on {report.today()} from `{args.runroot}`: {len(grid)} renders "
        f"({n_ok} ok, {n_ref} not applicable, {n_miss} missing). Data: [`{stem}.csv`]({stem}.csv) (this table), "
        f"[`{os.path.basename(args.runs_csv)}`]({os.path.relpath(args.runs_csv, os.path.dirname(args.out) or '.')}) "
        f"(one row per render), [`{os.path.basename(args.cells_csv)}`]"
        f"({os.path.relpath(args.cells_csv, os.path.dirname(args.out) or '.')}) (one row per cell and estimate). "
        f"The speed-up at equal error: [`{os.path.basename(args.equal_error)}`]"
        f"({os.path.relpath(args.equal_error, os.path.dirname(args.out) or '.')}).",
        "",
        f"- Machine: {report.machine()}, threads per render: {threads}. Load average when this table was written: "
        f"{report.loadavg_now()}; 1-minute load average at the start of the renders: median {fmt(load_med)}, "
        f"range {fmt(load_lo)}-{fmt(load_hi)} (with {os.cpu_count()} cores, a load above {os.cpu_count()} means "
        "work waited for a core: wall times then suffer more than CPU times).",
        f"- Commit: {report.commit()} when the table was written; renderer: {report.renderer_note(args.pm)}.",
        f"- Settings: {first['width']}x{first['height']}, {first['subpixels']}x{first['subpixels']} subpixel samples, "
        f"scene `{first['scene']}`" + (f", extra options `{args.pm_args}`" if args.pm_args.strip() else "")
        + f", renderer defaults otherwise (`build/photonmap render --help`). Seeds: {seeds} (`--seed`: the photon "
        "paths; the eye pass is deterministic). Every cell was rendered once per seed; the same renders give the "
        f"times and the errors. Estimates: {', '.join(estimates)} (paper: the paper's estimator, the renderer's "
        "default; corrected: `--bias-correction`).",
        f"- Reference for the error columns: `{cells_ref}` (reference/README.md says how it was rendered)."
        if cells_ref else
        "- Reference: none of this size in `reference/` (REF unset): the columns against the reference are n/a.",
    ]
    if cells_ref:
        out.append(f"- Reference floor: relMSE of `{cells_fast}` (POV-Ray's fast preset, the same pixels) against "
                   f"the reference = {fmt(floor)}. Two POV-Ray settings disagree by this much; a bias term at or "
                   "below it cannot be told apart from the reference's own error." if cells_fast and isnum(floor)
                   else "- Reference floor: n/a (no fast POV-Ray render of this size beside the reference).")
    out += ["- Paper: Intel Core2 Duo 2.93 GHz, g++ 4.6.3, 1024x768 with 2x2 samples; its times are total "
            "rendering times of one run.", ""]

    pairs = {}
    for _, r in table.iterrows():
        pairs.setdefault((r["photons"], r["nn"]), {})[r["method"]] = r
    if "paper" in estimates:
        out += ["## Times: the paper beside ours (paper estimate)", "",
                "Ours: median over seeds (min-max). ratio = precomputed (the paper's \"proposed\") / conventional, "
                "in percent: exp of the mean over seeds of the per-seed log ratio (the two renders of a seed "
                "share its photon map), with the exponentiated 95% t interval of that mean. s: the renderer's "
                "wall clock (`time_s.total`, the minimum over the render's repeats); CPU s: "
                "user+system CPU seconds of the process (`/usr/bin/time`, includes start-up and writing the EXR), "
                "less disturbed by other work on a shared machine."
                + ("" if (first["width"], first["height"], first["subpixels"]) == (1024, 768, 2) else
                   f" The paper's times are for 1024x768 with 2x2 samples, ours for {first['width']}x{first['height']} "
                   f"with {first['subpixels']}x{first['subpixels']}: compare the ratios, not the seconds (the eye "
                   "pass, which the precomputed method speeds up, shrinks with the image, the photon phases do not)."),
                ""]
        rows = []
        for (p, n), m in pairs.items():
            # the precomputed row carries the conventional cell it is compared with
            q = m.get("precomputed", {})
            c = m.get("conventional", {}) if not len(q) else \
                {k[len("conv_"):]: v for k, v in q.items() if k.startswith("conv_")}
            g = (lambda d, k: d.get(k, math.nan) if len(d) else math.nan)
            any_row = q if len(q) else c
            rows.append([p, n, fmt(g(any_row, "paper_conv_s")), fmt(g(q, "paper_s")), fmt(g(q, "paper_ratio_percent")),
                         fmt_range(g(c, "total_median_s"), g(c, "total_min_s"), g(c, "total_max_s")),
                         fmt_range(g(q, "total_median_s"), g(q, "total_min_s"), g(q, "total_max_s")),
                         fmt_ci(g(q, "ratio_percent"), g(q, "ratio_ci95_lo"), g(q, "ratio_ci95_hi"), 1),
                         model_text(q, args.model_state),
                         fmt_range(g(c, "cpu_median_s"), g(c, "cpu_min_s"), g(c, "cpu_max_s")),
                         fmt_range(g(q, "cpu_median_s"), g(q, "cpu_min_s"), g(q, "cpu_max_s")),
                         fmt_ci(g(q, "cpu_ratio_percent"), g(q, "cpu_ratio_ci95_lo"), g(q, "cpu_ratio_ci95_hi"), 1)])
        out += report.md_table(["P_e", "n", "paper conv. s", "paper prop. s", "paper ratio %", "our conv. s",
                                "our prec. s", "our ratio % [95% CI]", "model ratio %", "our conv. CPU s",
                                "our prec. CPU s", "our CPU ratio % [95% CI]"], rows, ["r"] * 12)
        out += model_lines(table, args.model_state, estimates, getattr(args, "model_problem", ""))
        out += ["", "## Our phases (paper estimate, median seconds over seeds)", "",
                "Each phase's own median (so the phases need not add up to the median total). Empty estimates: "
                "eye samples where no photon or representative applied (black), median over seeds.", ""]
        rows = [[r["photons"], r["nn"], r["method"]] + [report.fmt_fixed(r.get(f"{ph}_median_s"), 3) for ph in PHASES]
                + [fmt_range(r.get("total_median_s"), r.get("total_min_s"), r.get("total_max_s"), 3),
                   fmt_range(r.get("cpu_median_s"), r.get("cpu_min_s"), r.get("cpu_max_s"), 2),
                   report.fmt_fixed(r.get("photons_stored"), 0), report.fmt_fixed(r.get("representatives"), 0),
                   report.fmt_fixed(r.get("empty_estimates"), 0)]
                for _, r in table.iterrows()]
        out += report.md_table(["P_e", "n", "method", "trace", "build", "precompute", "render", "total (min-max)",
                                "CPU (min-max)", "stored photons", "representatives", "empty estimates"], rows,
                               ["r", "r", "l"] + ["r"] * 9)
    for est in estimates:
        sfx = suffix(est)
        sel = table[table[f"seeds{sfx}"] > 0]
        out += ["", f"## Error against the reference: {est} estimate", ""]
        if sel.empty:
            msgs = sorted(set(m for m in table[f"refusal{sfx}"] if m))
            out.append("No render of this estimate applied" + (f" (the renderer: `{'`; `'.join(msgs)}`)." if msgs else "."))
            continue
        out += ["Per cell over its seeds: relMSE against the reference, mean ± 95% t half-width; its split into "
                "bias and variance (they add up to the mean); the relMSE of the image against the conventional "
                "image of the same seed and estimate, mean ± 95% t half-width. "
                + (f"Reference floor: {fmt(floor)}; a bias at or below it is marked ≤floor." if isnum(floor) else ""),
                ""]
        rows = []
        for _, r in table.iterrows():
            if r[f"seeds{sfx}"] == 0:
                why = "not applicable" if r[f"seeds_refused{sfx}"] else "not rendered yet"
                rows.append([r["photons"], r["nn"], r["method"], 0, why, "", "", ""])
                continue
            b = r.get(f"bias_ref{sfx}")
            mark = " ≤floor" if isnum(b) and isnum(floor) and b <= floor else ""
            conv = "-" if r["method"] == "conventional" else fmt_pm(r.get(f"relmse_conv_mean{sfx}"),
                                                                    r.get(f"relmse_conv_ci95{sfx}"))
            rows.append([r["photons"], r["nn"], r["method"], r[f"seeds{sfx}"],
                         fmt_pm(r.get(f"relmse_ref_mean{sfx}"), r.get(f"relmse_ref_ci95{sfx}")),
                         fmt(b) + mark, fmt(r.get(f"variance_ref{sfx}")), conv])
        out += report.md_table(["P_e", "n", "method", "seeds", "relMSE vs ref", "bias", "variance",
                                "relMSE vs conv. (same seed)"], rows, ["r", "r", "l", "r", "r", "r", "r", "r"])

    out += paired_section(table, estimates)
    out += ["", "## What the intervals allow us to say", "",
            "Generated from the intervals above; two numbers are ranked only when their 95% intervals are "
            "disjoint (a conservative test: with few seeds, real differences can stay unranked), the estimates' "
            "errors against each other by the paired test per seed (Holm over the cells).", ""]
    out += rank_sentences(table, estimates, runs)

    refused = grid[grid["status"] == "refused"]
    if len(refused):
        out += ["", "## Not applicable", "",
                "Renders the renderer refused (exit 2): the combination does not apply, so the cell has no value "
                "for that estimate. Its message:", ""]
        rows = []
        for (method, est, msg), g in refused.groupby(["method", "estimate", "message"], sort=False):
            cells_txt = ", ".join(dict.fromkeys(f"({p}, {n})" for p, n in zip(g["photons"], g["nn"])))
            rows.append([method, est, cells_txt, f"`{msg}`" if msg else "(no message)"])
        out += report.md_table(["method", "estimate", "cells (P_e, n)", "renderer's message"], rows, ["l"] * 4)
        if refused["message"].str.contains("unknown option").any():
            out += ["", "**An \"unknown option\" above is not a refusal of the combination**: the renderer that ran "
                    "(`" + args.pm + "`) predates that option, so those renders say nothing about the estimate. "
                    "Re-run with a renderer that has it."]
    if n_miss:
        out += ["", f"{n_miss} render(s) missing: run `make reproduce-table` again (with the same variables) to "
                "finish them."]

    out += ["", "## How each column was computed", "",
            "- Per render (`runs.csv`): times from the renderer's `--stats` JSON (`time_s`, monotonic wall clock "
            "per phase); `cpu_s` = user + system seconds of the process from `/usr/bin/time -f \"%U %S\"`; "
            "`relmse_ref` = mean over pixels and RGB channels of (x-r)^2/(r^2+0.01), x our image, r the "
            "reference; `rmse_ref`, `psnr_ref` = 10 log10(1/MSE) dB (peak 1, linear radiance); `relmse_conv`: "
            "relMSE with the conventional image of the same seed and estimate in the place of r. One "
            "implementation: `experiments/analysis/metrics.py`.",
            "- `*_median_s`, `*_min_s`, `*_max_s`: median, minimum, maximum over the seeds that rendered.",
            "- `ratio_percent`, `cpu_ratio_percent` (`_ci95_lo`, `_ci95_hi`): the same numbers as "
            "`paired_ratio_percent` and `paired_cpu_ratio_percent` below (every time ratio of the table is the "
            "paired per-seed log ratio of the repeats' minima with a t interval over seeds; a percentile "
            "bootstrap of a ratio of medians covers far below 95% at 3-5 seeds).",
            "- `paired_ratio_percent`, `paired_cpu_ratio_percent`, `trace_ratio_percent` (`_ci95_lo`, `_ci95_hi`): "
            "100 x exp(mean over the seeds both cells rendered of log(precomputed / conventional)) of `total_s`, "
            "`cpu_s` and `trace_s`, with the exponentiated 95% t-interval of that mean (`stats.paired_log_ratio`); "
            "the two renders of a seed ran back to back (`pair_pos` in `runs.csv`). `relmse_diff_*`: the paired "
            "difference precomputed − conventional of `relmse_ref` (`stats.paired_difference`), `_p_holm` Holm's "
            "adjustment over the precomputed cells, `_verdict` from `stats.compare_family`.",
            "- `model_ratio_percent`: the cost model's (`make calibrate`; empty without one) paired ratio of the "
            "predicted totals, 100 x exp(mean over the paired seeds of log(predicted precomputed / predicted "
            "conventional)), each prediction from the render's work counters (its `--stats` JSON's `work`); "
            "`model_differs`: the model's ratio, give or take the model's validation error (the median "
            "relative error of a held-out render's total), lies wholly outside the measured ratio's 95% "
            "interval; `model_phase`, "
            "`model_counter` (where they differ): the phase whose measured times, put in the place of its "
            "predicted ones, bring the model's ratio closest to the measured one, and that phase's counter with "
            "the most predicted seconds in the method where the phase is furthest from its prediction "
            "(`calibrate.explain`).",
            "- `nmse_ref_mean`, `nmse_ref_ci95`: the same for NMSE = mean((x-r)^2) / mean(r^2), the error that "
            "stays relative in dark pixels (`metrics.py` says why relMSE stays the primary one).",
            "- `relmse_ref_mean`, `relmse_ref_ci95`: mean over seeds and the half-width of its 95% Student-t "
            "interval (t_{0.975, S-1} sd / sqrt(S), S seeds); the same for `psnr_ref` and `relmse_conv`.",
            "- `bias_ref`, `variance_ref` (from `cells.csv`): with xbar the per-pixel mean image over the S seeds, "
            "s^2 the per-pixel sample variance over seeds (ddof 1) and w = 1/(r^2+0.01): variance_ref = "
            "mean(w s^2), bias_ref = mean(w ((xbar-r)^2 - s^2/S)). Both are unbiased; bias_ref + variance_ref = "
            "relmse_ref_mean exactly, and bias_ref can be slightly negative when the bias is small. No "
            "interval is given for them: the t-interval of relmse_ref_mean carries the seed uncertainty.",
            "- Columns ending in `_corrected` (or another estimate's name): the same for that estimate.",
            "- `relmse_ref_floor`: relMSE of the fast POV-Ray render against the reference, the same pixels and "
            "samples (reference/README.md says how each was rendered).",
            "- `paper_s`, `paper_ratio_percent`: the paper's Table 1 (`experiments/paper-table1.csv`)."]
    return "\n".join(out) + "\n"


def main():
    """Command line: see the module docstring and experiments/rules/grid.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs-csv", required=True)
    ap.add_argument("--cells-csv", required=True)
    ap.add_argument("--paper", required=True)
    ap.add_argument("--out", required=True, help="output stem: STEM.csv and STEM.md")
    ap.add_argument("--equal-error", required=True, help="the equal-error Markdown (linked)")
    ap.add_argument("--pm", default="build/photonmap")
    ap.add_argument("--pm-args", default="")
    ap.add_argument("--runroot", required=True)
    ap.add_argument("--model", default=calibrate.DEFAULT_MODEL,
                    help="this machine's cost model (make calibrate); absent: the model columns say no model")
    ap.add_argument("--bootstrap", type=int, default=2000, help="accepted, unused: the time ratios' intervals are t intervals")
    ap.add_argument("--bootstrap-seed", type=int, default=1, help="accepted, unused")
    args = ap.parse_args()
    runs, cells, paper = read_inputs(args.runs_csv, args.cells_csv, args.paper)
    if (runs["role"] == "grid").sum() == 0:
        report.die("table.py", f"{args.runs_csv}: no render of the grid")
    args.ref = cells["ref"].dropna().iloc[0] if cells["ref"].notna().any() else ""
    args.ref_fast = cells["ref_fast"].dropna().iloc[0] if cells["ref_fast"].notna().any() else ""
    args.model_problem = ""
    try:
        args.model_state = calibrate.load_model(args.model)
    except calibrate.ModelError as e:  # a model of other counters: the table without its model column, and why
        args.model_state, args.model_problem = None, str(e)
        print(f"table.py: {e}; the table has no model ratios", file=sys.stderr)
    try:
        table, estimates = summarize(runs, cells, paper, args.model_state)
    except layout.RunError as e:
        report.die("table.py", str(e))
    report.write_csv_atomic(table, args.out + ".csv", "%.6g")
    report.write_atomic(args.out + ".md", markdown(table, runs, estimates, args))
    print(f"wrote {args.out}.csv and {args.out}.md ({len(table)} rows)")


if __name__ == "__main__":
    main()
