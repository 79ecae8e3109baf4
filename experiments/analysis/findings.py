#!/usr/bin/python3
"""findings.py: the results files -> FINDINGS.md, the findings written by the data.

Owns the wording of the project's findings: every number in FINDINGS.md is
read from a results file by this script, and every comparison is worded
from its test, never from a reading of the numbers:
  - two methods' paired values (the same seed): table.py's Holm-corrected
    verdict (stats.compare_family): "ranked higher/lower", "equivalent within
    delta" (delta = stats.EQUIVALENCE_MARGIN of the conventional value), or
    "undetermined";
  - two numbers that are not paired: ranked only when their 95% intervals
    are disjoint (stats.rank), else "undetermined"; never "equal";
  - a number against the paper's single measurement: whether our interval
    contains it (the paper's value carries no interval of its own).
A speed-up at equal error is quoted only at a target where at least 95% of
the bootstrap resamples reach both fronts (equal_error.headline); the
tightest target both fronts reach is named as where the curve starts.
One estimate is primary (PRIMARY_ESTIMATE, the paper's: every claim under
test was made with it); every summary bullet quotes it, and gives the other
beside it only where the verdict words differ. The equal-error curve's
dependence on the target is worded by one function (trend_text) for both
texts. A finding whose input file or column is missing says so, with the
target that makes it, instead of a number. The findings are numbered as the
hand-written ones of results/README.md that they replace (1-9), each with
the question the review asked of it, and lettered beyond them. FINDINGS.md
opens with README's summary bullets, each linked to its section, and each
section shows its figures (FIGURES) that exist under the results directory.

Three layers, one concern each: a record function per finding (record_*)
loads its results files once and returns a plain dict with every number and
verdict the finding quotes; md_* words a record as a FINDINGS.md section and
readme_* as a bullet of README's summary block. Both writers of a finding
read the same record and compute nothing of their own.

  python3 -m experiments.analysis.findings --results results --out results/FINDINGS.md
"""

import argparse
import glob
import math
import os

import numpy as np
import pandas as pd
from scipy import stats as sps

from experiments.analysis import coverage
from experiments.analysis import equal_error as ee
from experiments.analysis import metrics
from experiments.analysis import report
from experiments.analysis import stats
from experiments.analysis.report import fmt, isnum
from experiments.bench import report as bench_report
from experiments.bench import threads

WHERE = "findings.py"
# the smallest number of seeds whose percentile-bootstrap interval a finding
# quotes (below it such an interval covers well under 95%: coverage.py
# simulates how much, and the text quotes the simulation)
MIN_SEEDS_QUOTED = 5
# the estimate every summary bullet quotes; the other one is given beside it
# only where its verdict words differ (PRIMARY_ESTIMATE_REASON says why)
PRIMARY_ESTIMATE = "paper"
OTHER_ESTIMATE = {"paper": "corrected", "corrected": "paper"}[PRIMARY_ESTIMATE]
PRIMARY_ESTIMATE_REASON = (
    "The paper's estimate (its eq. 1 and eq. 2 as the paper uses them) is the primary one, because every claim "
    "under test, Table 1's times and Figure 3's images, was made with it; the corrected estimate (the n/(n-1) bias "
    "removed) is ours; the summary in numbers gives it beside the primary one wherever its verdict differs, the short "
    "sentences the primary one only.")
# the equivalence margin of the estimator-bias intervals around 1 (the exact
# radiance): 1%, below the law's bias n/(n-1) - 1 at every n the paper uses
# (1.01% at its largest, n = 100), so an interval inside 1 +- BIAS_MARGIN
# rules out the uncorrected bias at every such n
BIAS_MARGIN = 0.01
BIAS_MARGIN_REASON = "below the law's bias n/(n-1) - 1 at every n the paper uses (1.01% at n = 100)"
# the paper's Figure 3 statements: the cell (P_e, n) and what the paper says
# of the two methods' images there
FIGURE3 = ((50000, 10, "differ"), (100000, 100, "alike"), (500000, 100, "alike"))


def sfx(est):
    """The column suffix of estimate EST in a table1.csv ('' for the paper's)."""
    return "" if est == "paper" else f"_{est}"


class Missing(Exception):
    """A finding's input is not there: the message says which and what makes it."""


def load(path, need, make):
    """The CSV at PATH with the columns NEED, or Missing naming MAKE."""
    if not os.path.isfile(path):
        raise Missing(f"`{path}` is missing (`{make}` writes it)")
    try:
        frame = pd.read_csv(path, comment="#")
    except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError) as e:
        raise Missing(f"`{path}` cannot be read ({e})") from e
    lack = [c for c in need if c not in frame.columns]
    if lack:
        raise Missing(f"`{path}` has no column {', '.join(lack)} (written before this analysis: rerun `{make}`)")
    return frame


def pct(x):
    """A percentage with one decimal."""
    return report.fmt_fixed(x, 1)


def ci(m, lo, hi, f=fmt):
    """'m [lo, hi]'."""
    return f"{f(m)} [{f(lo)}, {f(hi)}]"


def cell(p, n):
    """'(50k, 10)'."""
    p = int(p)
    return f"({p // 1000}k, {int(n)})" if p % 1000 == 0 else f"({p}, {int(n)})"


def prec_rows(table):
    """The precomputed rows of a table1.csv."""
    return table[table["method"] != "conventional"]


# ---- records: one per finding. Each loads its results files once and
# returns a plain dict holding every number and verdict that FINDINGS.md and
# README's summary quote of it (or raises Missing); the writers below only
# word and format a record, they compute nothing.

EQUAL_ERROR_COLUMNS = ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction"]


def row_dict(r):
    """A results row (a pandas Series) as a plain dict."""
    return {k: r[k] for k in r.index}


def span_of(rows):
    """(smallest, largest) of an integer column's values."""
    return int(rows.min()), int(rows.max())


def excess_and_bias(q, c):
    """(relMSE excess, bias excess) of the precomputed rows Q of a cells.csv
    over the conventional rows C of the same cell (the first row of each)."""
    return (q["relmse_ref_mean"].iloc[0] - c["relmse_ref_mean"].iloc[0],
            q["bias_ref"].iloc[0] - c["bias_ref"].iloc[0])


def corrected_coverage(b):
    """Of an estimator-bias CSV's corrected intervals (both methods, every
    n): (how many contain 1, how many there are, [(mean, half-width)])."""
    k_in = k_all = 0
    vals = []
    for m in ("conventional", "precomputed"):
        mean, half = b[f"{m}_corrected_mean"], b[f"{m}_corrected_ci95"]
        ok = np.isfinite(mean) & np.isfinite(half)
        k_in += int(((mean[ok] - half[ok] <= 1) & (1 <= mean[ok] + half[ok])).sum())
        k_all += int(ok.sum())
        vals += list(zip(mean[ok], half[ok]))
    return k_in, k_all, vals


def equivalence_to_one(b, margin):
    """Per corrected interval of an estimator-bias CSV (both methods, every
    n): {method, n, mean, half, equivalent}, equivalent when the whole 95%
    interval lies inside [1 - MARGIN, 1 + MARGIN] (two one-sided tests at
    2.5% each: conservative)."""
    out = []
    for m in ("conventional", "precomputed"):
        for _, r in b.iterrows():
            mean, half = r[f"{m}_corrected_mean"], r[f"{m}_corrected_ci95"]
            if np.isfinite(mean) and np.isfinite(half):
                out.append({"method": m, "n": int(r["n"]), "mean": mean, "half": half,
                            "equivalent": bool(1 - margin <= mean - half and mean + half <= 1 + margin)})
    return out


def resolution_files(d):
    """The resolution study's equal-error-WxH.csv files, smallest width first."""
    return sorted(glob.glob(os.path.join(d["resolution"], "equal-error-*.csv")),
                  key=lambda f: int(os.path.basename(f)[len("equal-error-"):-4].split("x")[0]))


def headline_of(e, est):
    """The headline row of estimate EST in an equal-error CSV (the tightest
    curve target at least equal_error.DEFINED_MIN of the resamples reach on
    both fronts), or None."""
    g = e[(e["estimate"] == est) & (e["kind"] == "curve")]
    return ee.headline([r for _, r in g.iterrows()])


def tightest_and_curve(e, est):
    """(tightest row, (lowest, highest) curve rows where 95% of the resamples
    reach both fronts, or None) of estimate EST in an equal-error CSV; Missing
    when the fronts share no error."""
    g = e[e["estimate"] == est]
    t = g[g["kind"] == "tightest"]
    if len(t) == 0:
        raise Missing(f"the {est} estimate's fronts reach no common {metrics.PRIMARY}")
    c = g[(g["kind"] == "curve") & (g["defined_fraction"] >= ee.DEFINED_MIN)]
    span = (c.loc[c["speedup"].idxmin()], c.loc[c["speedup"].idxmax()]) if len(c) else None
    return t.iloc[0], span


REGION_WORDS = {"above": "it pays (the interval lies wholly above 1)",
                "below": "it does not pay (wholly below 1)",
                "contains": "undetermined (the interval contains 1)"}


def curve_regions(c):
    """Runs of the curve rows C (one estimate, kind `curve`) by target, at
    the targets where at least equal_error.DEFINED_MIN of the resamples
    reach both fronts: [{class, first, last, count}] with class `above`
    (the interval wholly above 1: the precomputation pays), `below` (wholly
    below 1) or `contains` (it contains 1, or an end is nan)."""
    c = c[c["defined_fraction"] >= ee.DEFINED_MIN].sort_values("target")
    runs = []
    for _, r in c.iterrows():
        k = {"higher": "above", "lower": "below"}.get(stats.rank((r["lo"], r["hi"]), (1.0, 1.0)), "contains")
        if runs and runs[-1]["class"] == k:
            runs[-1].update(last=r["target"], count=runs[-1]["count"] + 1)
        else:
            runs.append({"class": k, "first": r["target"], "last": r["target"], "count": 1})
    return runs


def crossing_of(runs):
    """Where a curve_regions list crosses 1: (direction, a, b), the curve
    wholly below 1 up to target a and wholly above it from b on
    ('up'), or the reverse ('down'); None without both kinds of target, or
    when they interleave."""
    below = [x for x in runs if x["class"] == "below"]
    above = [x for x in runs if x["class"] == "above"]
    if not below or not above:
        return None
    if max(x["last"] for x in below) < min(x["first"] for x in above):
        return ("up", max(x["last"] for x in below), min(x["first"] for x in above))
    if max(x["last"] for x in above) < min(x["first"] for x in below):
        return ("down", max(x["last"] for x in above), min(x["first"] for x in below))
    return None


def regions_text(runs):
    """Where on the curve the precomputation pays and where not, from a
    curve_regions list: 'at relMSE a-b (k targets) it pays ...; ...'."""
    if not runs:
        return f"at no target of the curve do {100 * ee.DEFINED_MIN:.0f}% of the resamples reach both fronts"
    parts = []
    for k in ("above", "below", "contains"):
        rs = [x for x in runs if x["class"] == k]
        if rs:
            where = ", ".join(f"{fmt(x['first'])}" if x["count"] == 1 else f"{fmt(x['first'])} to {fmt(x['last'])}"
                              for x in rs)
            count = sum(x["count"] for x in rs)
            parts.append(f"{REGION_WORDS[k]} at {primary_name()} {where} ({count} target{'' if count == 1 else 's'})")
    out = "; ".join(parts)
    cr = crossing_of(runs)
    if cr is not None:
        d, a, b = cr
        out += (f"; it crosses 1 between {fmt(a)} and {fmt(b)}, slower at the tighter targets"
                if d == "up" else f"; it crosses 1 between {fmt(a)} and {fmt(b)}, faster at the tighter targets")
    return out


def trend_text(r):
    """The one wording of the equal-error curve's dependence on the target
    (README's summary and FINDINGS.md both use it), from the test of its
    two extremes: the smallest and the largest speed-up where 95% of the
    resamples reach both fronts, ranked only when their 95% intervals are
    disjoint (record key span_rank); the loosest such target's speed-up
    beside them when it is neither (the largest is not the curve's end)."""
    span = r["span"]
    if span is None:
        return (f"at no target of the curve do {100 * ee.DEFINED_MIN:.0f}% of the resamples reach both fronts, so "
                "no trend with the target is tested")
    a, b = span
    ends = (f"from its smallest, {ci(a['speedup'], a['lo'], a['hi'])}x at {fmt(a['target'])}, to its largest, "
            f"{ci(b['speedup'], b['lo'], b['hi'])}x at {fmt(b['target'])}")
    z = r.get("loosest")
    if z is not None and z["target"] not in (a["target"], b["target"]):
        ends += f" (at the loosest such target, {fmt(z['target'])}, {ci(z['speedup'], z['lo'], z['hi'])}x)"
    if r["span_rank"] in ("lower", "higher"):
        return (f"where 95% of the resamples reach both fronts the speed-up runs {ends}, and these two 95% intervals "
                "are disjoint: the speed-up depends on the target, and no single target stands for the curve")
    return (f"where 95% of the resamples reach both fronts the speed-up runs {ends}; these two 95% intervals "
            "overlap, so no trend with the target is claimed")


def equal_error_record(e):
    """Per estimate of an equal-error frame E (equal_error.py's kinds
    `tightest` and `curve`), in file order: the tightest row (None when the
    fronts share no error), the span of the curve where 95% of the resamples
    reach both fronts and the rank of its two ends, the headline row and
    its interval against 1, and the curve's extent."""
    out = []
    for est, g in e.groupby("estimate", sort=False):
        c = g[g["kind"] == "curve"]
        r = {"estimate": est, "curve_targets": len(c), "curve_min": c["target"].min(),
             "curve_max": c["target"].max(), "tightest": None, "span": None, "span_rank": None,
             "headline": None, "headline_vs_one": None, "regions": curve_regions(c)}
        try:
            t, span = tightest_and_curve(g, est)
        except Missing:
            out.append(r)
            continue
        r["tightest"] = row_dict(t)
        if span is not None:
            r["span"] = (row_dict(span[0]), row_dict(span[1]))
            defined = c[c["defined_fraction"] >= ee.DEFINED_MIN]
            r["loosest"] = row_dict(defined.loc[defined["target"].idxmax()])
            r["span_rank"] = stats.rank((span[0]["lo"], span[0]["hi"]), (span[1]["lo"], span[1]["hi"]))
        h = headline_of(g, est)
        if h is not None:
            r["headline"] = row_dict(h)
            r["headline_vs_one"] = stats.rank((h["lo"], h["hi"]), (1.0, 1.0))
        out.append(r)
    return out


def estimate_of(records, est):
    """The record of estimate EST in an equal_error_record list; Missing when
    its fronts share no error (or it is absent)."""
    for r in records:
        if r["estimate"] == est and r["tightest"] is not None:
            return r
    raise Missing(f"the {est} estimate's fronts reach no common {metrics.PRIMARY}")


def record_table(d):
    """Table 1's paired time ratios: the grid, the rank over n at each P_e
    and over P_e at each n (first against last, unpaired intervals), and
    where the paper's single value lies against our interval."""
    t = load(d["table"], ["photons", "nn", "method", "paper_ratio_percent", "paired_ratio_percent",
                          "paired_ratio_ci95_lo", "paired_ratio_ci95_hi", "pairs"], "make reproduce-table")
    p = prec_rows(t)
    nns = sorted(p["nn"].unique())
    phs = sorted(p["photons"].unique())

    def val(s):
        return {"photons": s["photons"], "nn": s["nn"], "ratio": s["paired_ratio_percent"],
                "lo": s["paired_ratio_ci95_lo"], "hi": s["paired_ratio_ci95_hi"], "paper": s["paper_ratio_percent"]}

    def iv(s):
        return (s["paired_ratio_ci95_lo"], s["paired_ratio_ci95_hi"])

    def ends(s):
        lo, hi = s.iloc[0], s.iloc[-1]
        return {"count": len(s), "first": val(lo), "last": val(hi), "rank": stats.rank(iv(hi), iv(lo))}
    grid = {}
    for n in nns:
        for ph in phs:
            s = p[(p["photons"] == ph) & (p["nn"] == n)]
            grid[(n, ph)] = val(s.iloc[0]) if len(s) else None
    over_n = {ph: ends(p[p["photons"] == ph].sort_values("nn")) for ph in phs}
    over_p = {n: ends(p[p["nn"] == n].sort_values("photons")) for n in nns}
    # the cells with the paper's value and an interval (one pair gives none)
    known = p[np.isfinite(p["paper_ratio_percent"]) & np.isfinite(p["paired_ratio_ci95_lo"].astype(float))
              & np.isfinite(p["paired_ratio_ci95_hi"].astype(float))]
    inside = (known["paired_ratio_ci95_lo"] <= known["paper_ratio_percent"]) & \
             (known["paper_ratio_percent"] <= known["paired_ratio_ci95_hi"])
    out = known[~inside]
    # where the paper's method is slower (its ratio above 100%) and ours is
    # faster (our whole interval below 100%)
    rev = known[(known["paper_ratio_percent"] > 100) & (known["paired_ratio_ci95_hi"] < 100)]
    # where the paper's method is slower and our interval contains 100%
    und = known[(known["paper_ratio_percent"] > 100) & (known["paired_ratio_ci95_lo"] <= 100)
                & (known["paired_ratio_ci95_hi"] >= 100)]
    slower = known[known["paper_ratio_percent"] > 100]
    # the other estimate's intervals against the paper's values (the paper
    # used its own estimate; ours is given beside it where the count differs)
    ox = sfx(OTHER_ESTIMATE)
    inside_other = None
    if f"paired_ratio_ci95_lo{ox}" in known.columns:
        lo, hi = known[f"paired_ratio_ci95_lo{ox}"].astype(float), known[f"paired_ratio_ci95_hi{ox}"].astype(float)
        ok = np.isfinite(lo) & np.isfinite(hi)
        inside_other = (int(((lo <= known["paper_ratio_percent"]) & (known["paper_ratio_percent"] <= hi))[ok].sum()),
                        int(ok.sum()))
    return {"pairs": span_of(p["pairs"]), "nns": nns, "photons": phs, "grid": grid, "over_n": over_n,
            "inside_other": inside_other, "rerun": table_rerun(d.get("table_rerun")),
            "reversed": [val(r) for _, r in rev.sort_values(["photons", "nn"]).iterrows()],
            "undetermined_vs_slower": [val(r) for _, r in und.sort_values(["photons", "nn"]).iterrows()],
            "paper_slower": len(slower), "ours_faster": int((p["paired_ratio_ci95_hi"] < 100).sum()),
            "cells": len(p),
            "over_p": over_p, "falls": sum(over_n[ph]["rank"] == "lower" for ph in phs),
            "inside": {ph: (int(inside[known["photons"] == ph].sum()), int((known["photons"] == ph).sum()))
                       for ph in phs},
            "inside_all": bool(inside.all()), "inside_any": bool(inside.any()), "outside": len(out),
            "outside_lower": int((out["paired_ratio_ci95_hi"] < out["paper_ratio_percent"]).sum())}


def table_rerun(path):
    """Table 1's counts in its rerun (reproducibility's run b, PATH, the
    same table1.csv columns): {cells, ours_faster (intervals wholly below
    100%), inside (intervals holding the paper's value), inside_other (the
    other estimate's, or None)}; None when PATH is not given or absent."""
    if not path or not os.path.exists(path):
        return None
    t = prec_rows(load(path, ["photons", "nn", "method", "paper_ratio_percent", "paired_ratio_ci95_lo",
                              "paired_ratio_ci95_hi"], "make reproducibility"))
    known = t[np.isfinite(t["paper_ratio_percent"].astype(float))]

    def holds(lo, hi):
        lo, hi = known[lo].astype(float), known[hi].astype(float)
        return int(((lo <= known["paper_ratio_percent"]) & (known["paper_ratio_percent"] <= hi)).sum())
    ox = sfx(OTHER_ESTIMATE)
    return {"cells": len(t), "ours_faster": int((t["paired_ratio_ci95_hi"].astype(float) < 100).sum()),
            "inside": holds("paired_ratio_ci95_lo", "paired_ratio_ci95_hi"),
            "inside_other": holds(f"paired_ratio_ci95_lo{ox}", f"paired_ratio_ci95_hi{ox}")
            if f"paired_ratio_ci95_lo{ox}" in known.columns else None}


def rerun_text(rec):
    """'; in its rerun (...), 11 of 12 intervals lie below 100% and 4 hold
    the paper's value (the corrected estimate's: 2)': Table 1's counts in
    the rerun where they differ from the first run's, '' where they do not
    or there is no rerun."""
    r = rec.get("rerun")
    if r is None:
        return ""
    first_inside = sum(k for k, _ in rec["inside"].values())
    first_other = rec["inside_other"][0] if rec.get("inside_other") else None
    if (r["ours_faster"], r["inside"], r["inside_other"]) == (rec["ours_faster"], first_inside, first_other):
        return "; its rerun (`make reproducibility`, run b) gives the same counts"
    return (f"; in its rerun (`make reproducibility`, run b) {r['ours_faster']} of {r['cells']} intervals lie below "
            f"100% and {r['inside']} hold the paper's value"
            + (f" (the {OTHER_ESTIMATE} estimate's: {r['inside_other']})" if r["inside_other"] is not None else "")
            + ", so these counts are not stable between runs")


def record_precompute(d):
    """Why Table 1's largest photon count differs from the paper's: our
    precompute cost per representative (runs.csv precompute_s /
    representatives, median per P_e over the primary estimate's precomputed
    grid renders) and, per cell, the precompute share of the precomputed
    method's time, ours (precompute_median_s / total_median_s) against the
    paper's implied by one model: the paper's precomputed time less what its
    conventional time would spend outside the precompute if the paper's
    phases scaled like ours,
      paper_precompute = paper_s - paper_conv_s x (ours_total - ours_precompute) / ours_conv_total,
    per representative with our representative count (the same rule, every
    4th stored photon, on the same scene)."""
    x = sfx(PRIMARY_ESTIMATE)
    t = load(d["table"], ["photons", "nn", "method", "paper_s", "paper_conv_s", f"total_median_s{x}",
                          f"precompute_median_s{x}", f"conv_total_median_s{x}", f"representatives{x}"],
             "make reproduce-table")
    r = load(d["runs"], ["role", "status", "method", "estimate", "photons", "precompute_s", "representatives"],
             "make reproduce-table")
    r = r[(r["role"] == "grid") & (r["status"] == "ok") & (r["method"] == "precomputed") &
          (r["estimate"] == PRIMARY_ESTIMATE) & (r["representatives"] > 0)]
    per_rep = {ph: float(np.median(g["precompute_s"] / g["representatives"])) for ph, g in r.groupby("photons")}
    cells = []
    for _, c in prec_rows(t).sort_values(["photons", "nn"]).iterrows():
        ours_total, ours_pre = c[f"total_median_s{x}"], c[f"precompute_median_s{x}"]
        conv = c[f"conv_total_median_s{x}"]
        if not (np.isfinite(c["paper_s"]) and np.isfinite(c["paper_conv_s"]) and conv > 0 and ours_total > 0):
            continue
        rest = (ours_total - ours_pre) / conv
        paper_pre = c["paper_s"] - c["paper_conv_s"] * rest
        reps = c[f"representatives{x}"]
        cells.append({"photons": c["photons"], "nn": c["nn"], "paper_s": c["paper_s"],
                      "paper_conv_s": c["paper_conv_s"],
                      "rest": rest, "paper_pre": paper_pre, "paper_share": paper_pre / c["paper_s"],
                      "ours_share": ours_pre / ours_total, "paper_per_rep": paper_pre / reps if reps > 0 else np.nan,
                      "ours_pre": ours_pre, "machine": c["paper_conv_s"] / conv})
    if not cells:
        raise Missing("`table1.csv` has no precomputed cell with the paper's times (`make reproduce-table`)")
    top = max(c["photons"] for c in cells)
    at = [c for c in cells if c["photons"] == top]
    return {"per_rep": per_rep, "cells": cells, "top": top,
            "paper_share": (min(c["paper_share"] for c in at), max(c["paper_share"] for c in at)),
            "ours_share": (min(c["ours_share"] for c in at), max(c["ours_share"] for c in at)),
            "paper_per_rep": float(np.median([c["paper_per_rep"] for c in at])),
            # the paper's cost per representative on our machine: divided by
            # the ratio of the two conventional times of the same cell
            "paper_per_rep_here": float(np.median([c["paper_per_rep"] / c["machine"] for c in at])),
            "machine": float(np.median([c["machine"] for c in at])),
            "ours_per_rep": per_rep.get(top, np.nan),
            "negative": [(c["photons"], c["nn"]) for c in cells if c["paper_pre"] < 0]}


def verdict_at_margin(lo, hi, m):
    """The verdict of a paired difference's interval [LO, HI] against a
    margin M: "higher" / "lower" when it lies wholly beyond +M / -M,
    "equivalent" when wholly inside [-M, M], else "undetermined"."""
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return "undetermined"
    if lo > m:
        return "higher"
    if hi < -m:
        return "lower"
    if -m <= lo and hi <= m:
        return "equivalent"
    return "undetermined"


def record_reference_error(d):
    """Table 1's reference's own error: its only measured proxy (the fast
    POV-Ray preset's relMSE against the reference preset, table1.csv
    relmse_ref_floor) against each cell's equivalence margin delta, and per
    estimate the cells whose verdict changes when the margin is widened to
    the proxy (verdict_at_margin with max(delta, proxy), on the paired 95%
    intervals, not Holm-adjusted)."""
    t = load(d["table"], ["photons", "nn", "method", "relmse_ref_floor", "relmse_diff_lo", "relmse_diff_hi",
                          "relmse_diff_delta", "relmse_diff_verdict"], "make reproduce-table")
    f = t["relmse_ref_floor"].astype(float)
    f = f[np.isfinite(f)]
    if not len(f):
        raise Missing(f"`{d['table']}` has no relmse_ref_floor value (the fast reference is missing: "
                      "`make reference`)")
    floor = float(f.iloc[0])
    p = prec_rows(t).sort_values(["photons", "nn"])
    out = {}
    for est in (PRIMARY_ESTIMATE, OTHER_ESTIMATE):
        x = sfx(est)
        if f"relmse_diff_verdict{x}" not in p.columns:
            continue
        rows = []
        for _, r in p.iterrows():
            lo, hi, delta = r[f"relmse_diff_lo{x}"], r[f"relmse_diff_hi{x}"], r[f"relmse_diff_delta{x}"]
            v = r[f"relmse_diff_verdict{x}"] if isinstance(r[f"relmse_diff_verdict{x}"], str) else "undetermined"
            rows.append({"photons": r["photons"], "nn": r["nn"], "lo": lo, "hi": hi, "delta": delta, "verdict": v,
                         "widened": verdict_at_margin(lo, hi, max(delta, floor)), "times": floor / delta})
        judged = [r for r in rows if r["verdict"] in ("equivalent", "lower")]
        out[est] = {"rows": rows, "judged": len(judged),
                    "times": (min(r["times"] for r in judged), max(r["times"] for r in judged)) if judged else None,
                    "changed": [r for r in rows if r["widened"] != r["verdict"]]}
    tightest = None
    try:
        e = load(d["equal_error"], EQUAL_ERROR_COLUMNS, "make reproduce-table")
        g = e[(e["estimate"] == PRIMARY_ESTIMATE) & (e["kind"] == "tightest")]
        tightest = float(g["target"].iloc[0]) if len(g) else None
    except Missing:
        pass
    return {"floor": floor, "tightest": tightest, "estimates": out}


def inside_margin(lo, hi, delta):
    """True when the paired interval [LO, HI] lies wholly inside [-DELTA,
    DELTA] (verdict_at_margin's "equivalent"): any difference is smaller
    than the margin, ranked by the test or not."""
    return bool(np.isfinite(delta)) and verdict_at_margin(lo, hi, delta) == "equivalent"


def figure3_word(v, inside=False):
    """'differ', 'alike' or 'undetermined' of a paired verdict V: a visual
    claim, so an interval INSIDE the margin is 'alike' even where the test
    ranks the two (a difference smaller than the margin); 'differ' only for
    a ranked difference the margin does not hold."""
    if inside:
        return "alike"
    return {"higher": "differ", "lower": "differ", "equivalent": "alike"}.get(v, "undetermined")


def record_figure3(d):
    """The paper's Figure 3 statements (FIGURE3) against the paired relMSE
    difference precomputed - conventional at their cells: "differ" when
    the Holm-corrected test ranks the two and the interval is not inside
    +-delta, "alike" when the interval lies inside +-delta (equivalent, or
    ranked by less than delta: "ranked_within"), per estimate, and at the
    reference's own error as the margin (verdict_at_margin) when table1.csv
    has it."""
    t = load(d["table"], ["photons", "nn", "method", "relmse_diff_mean", "relmse_diff_lo", "relmse_diff_hi",
                          "relmse_diff_delta", "relmse_diff_verdict"], "make reproduce-table")
    p = prec_rows(t)
    floor = None
    if "relmse_ref_floor" in t.columns:
        f = t["relmse_ref_floor"].astype(float)
        floor = float(f[np.isfinite(f)].iloc[0]) if np.isfinite(f).any() else None
    rows = []
    for ph, n, said in FIGURE3:
        r = p[(p["photons"] == ph) & (p["nn"] == n)]
        row = {"photons": ph, "nn": n, "said": said, "present": bool(len(r))}
        if len(r):
            r = r.iloc[0]
            for est in (PRIMARY_ESTIMATE, OTHER_ESTIMATE):
                x = sfx(est)
                if f"relmse_diff_verdict{x}" not in p.columns:
                    continue
                v = r[f"relmse_diff_verdict{x}"] if isinstance(r[f"relmse_diff_verdict{x}"], str) else "undetermined"
                wide = (figure3_word(verdict_at_margin(r[f"relmse_diff_lo{x}"], r[f"relmse_diff_hi{x}"],
                                                       max(r[f"relmse_diff_delta{x}"], floor)))
                        if floor is not None else None)
                inside = inside_margin(r[f"relmse_diff_lo{x}"], r[f"relmse_diff_hi{x}"], r[f"relmse_diff_delta{x}"])
                row[est] = {"mean": r[f"relmse_diff_mean{x}"], "lo": r[f"relmse_diff_lo{x}"],
                            "hi": r[f"relmse_diff_hi{x}"], "delta": r[f"relmse_diff_delta{x}"], "verdict": v,
                            "word": figure3_word(v, inside), "wide": wide,
                            "ranked_within": inside and v in ("higher", "lower")}
        rows.append(row)
    return {"rows": rows, "floor": floor}


# per study that judges images: (name, the make target, its cells files
# under results/, each naming its reference in the column `ref`)
STUDY_REFERENCES = (
    ("Table 1", "make reproduce-table", "table1/cells.csv",
     "the claims under test are the paper's, on its scene at its size, which reference/ holds: an independent "
     "renderer judges them"),
    ("representative rules", "make rep-study", "rep-study/cells-rep-*.csv",
     "Table 1's grid with other rules, so Table 1's reference"),
    ("caustic window", "make caustic", "caustic/caustic-cells.csv",
     "the caustic scene at a size reference/ holds (128x96); POV-Ray's photons carry the caustic's paths (finding A)"),
    ("scenes", "make scenes", "scenes/cells-*.csv",
     "reference/ holds these scenes at 128x96 only, and POV-Ray is off in tworooms (finding A): every scene "
     "against its own converged render, judged alike"),
    ("resolution", "make resolution", "resolution/cells-*.csv",
     "one kind of reference at every size (RES_REF=ours): POV-Ray's exist at two of its sizes only"),
    ("reproducibility", "make reproducibility", "reproducibility/cells-*.csv",
     "Table 1's grid rendered again, so Table 1's reference"),
    ("beyond", "make beyond", "beyond/studies/cells-*.csv",
     "the scenes' and sizes' grids of make scenes and make resolution, against the same converged references"),
    ("final gathering", "make gather", "gather/cells-*.csv",
     "every scene and cornell at three sizes, against the converged references make scenes renders"))
# the studies that judge no image against a reference image, and what judges them
NO_REFERENCE_IMAGE = (("estimator bias", "make estimator-bias",
                       "the exact radiance of the analytic scene (1), known in closed form"),
                      ("bench, scaling, threads", "make bench",
                       "none: they time the code and check the neighbour sets, not images"),
                      ("stability", "make stability", "the image mean's expected value, no reference image"))
# why a study is judged by each kind of reference
REFERENCE_WHY = {
    "POV-Ray": "an independent renderer, as the paper judges its images, at the sizes reference/ holds, with "
               "its own noise and bias unmeasured (finding E)",
    "converged photonmap": "our conventional method with the corrected estimate at many times the grid's photon "
                           "count (reference.py): made at whatever scene and size the study renders, with its "
                           "noise and kernel bias measured, but by the method family it judges",
    "pbrt-v3": "an independent path tracer", "unknown": "a reference this script does not recognise"}


def reference_kind(path):
    """The kind of a reference image by its path: 'POV-Ray' (reference/...),
    'converged photonmap' (a convref or refhigh render), 'pbrt-v3', or
    'unknown'."""
    b = str(path).lower()
    if "pbrt" in b:
        return "pbrt-v3"
    if "convref" in b or "refhigh" in b:
        return "converged photonmap"
    if b.startswith("reference/"):
        return "POV-Ray"
    return "unknown"


def beyond_case(path):
    """'cornell-512x384' of a beyond/studies file name '...-cornell-512x384-variant.csv'."""
    stem = os.path.basename(path)[:-4]
    parts = stem.split("-")
    return "-".join(parts[-3:-1]) if len(parts) >= 4 else stem


def quoted_reference_error(root, ref):
    """(noise, bias, file) of the reference REF as a study's Markdown under
    ROOT quotes it (reference.describe's sentence 'Reference `REF`: ... Its
    own error in relmse: noise X ..., kernel bias Y'), or None when no file
    quotes it."""
    import re
    pat = re.compile(re.escape(f"Reference `{ref}`") + r"[^\n]*?Its own error in \w+: noise ([0-9.eE+-]+)"
                     r"[^\n]*?kernel bias ([0-9.eE+-]+)")
    for dirpath, _, files in sorted(os.walk(root)):
        for f in sorted(files):
            if f.endswith(".md") and f != "FINDINGS.md":
                path = os.path.join(dirpath, f)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    m = pat.search(fh.read())
                if m:
                    return float(m.group(1)), float(m.group(2)), os.path.relpath(path, root)
    return None


def runs_reference_error(root, cases):
    """(noise, bias, file) of a converged reference as the runs files of
    beyond/ CASES carry it (collect.py's ref_noise and ref_bias, copied from
    the reference's JSON when the study ran: committed, unlike the JSON), or
    None when no such file has them."""
    for case in sorted(cases):
        for f in sorted(glob.glob(os.path.join(root, "beyond", "studies", f"runs-{case}-*.csv"))):
            try:
                c = pd.read_csv(f, comment="#")
            except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError):
                continue
            if "ref_noise" not in c.columns or "ref_bias" not in c.columns:
                continue
            n, b = c["ref_noise"].astype(float), c["ref_bias"].astype(float)
            ok = np.isfinite(n) & np.isfinite(b)
            if ok.any():
                return float(n[ok].iloc[0]), float(b[ok].iloc[0]), os.path.relpath(f, root)
    return None


def record_judges(d):
    """Per study, the kinds of reference its cells files name (column ref)
    and why; the studies that judge no image; and for every converged
    reference beyond/ uses, its noise and bias from beyond's runs files
    (runs_reference_error), else the JSON beside it (reference.py), else a
    study's Markdown that quotes it (None when none has them), with the
    tightest target it judges there."""
    from experiments.analysis import reference
    root = d["root"]
    repo = os.path.dirname(os.path.abspath(root))
    studies = []
    for name, make, pattern, why in STUDY_REFERENCES:
        files = sorted(glob.glob(os.path.join(root, pattern)))
        refs = set()
        for f in files:
            try:
                c = pd.read_csv(f, comment="#")
            except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError):
                continue
            if "ref" in c.columns:
                refs |= {str(x) for x in c["ref"].dropna()}
        studies.append({"study": name, "make": make, "files": len(files), "pattern": pattern, "why": why,
                        "kinds": sorted({reference_kind(r) for r in refs})})
    beyond = {}
    for f in sorted(glob.glob(os.path.join(root, "beyond", "studies", "cells-*.csv"))):
        try:
            c = pd.read_csv(f, comment="#")
        except (OSError, pd.errors.ParserError, pd.errors.EmptyDataError):
            continue
        for r in set(c["ref"].dropna()) if "ref" in c.columns else ():
            beyond.setdefault(str(r), set()).add(beyond_case(f))
    refs = []
    for r, cases in sorted(beyond.items()):
        info = reference.load(os.path.join(repo, r))
        ts = [reference.tightest_of(e) for case in cases
              for e in glob.glob(os.path.join(root, "beyond", "studies", f"equal-error-{case}-*.csv"))]
        ts = [t for t in ts if t is not None]
        noise = bias = src = None
        q = runs_reference_error(root, cases)
        if q is not None:
            noise, bias, src = q
        elif info is not None:
            noise, bias, src = info.get("noise"), info.get("bias"), reference.sidecar(r)
        else:
            q = quoted_reference_error(root, r)
            if q is not None:
                noise, bias, src = q
        refs.append({"ref": r, "cases": sorted(cases), "kind": reference_kind(r), "noise": noise, "bias": bias,
                     "source": src, "tightest": min(ts) if ts else None})
    return {"studies": studies, "none": [{"study": a, "make": b, "by": c} for a, b, c in NO_REFERENCE_IMAGE],
            "beyond": refs}


# the verdicts reference/pbrt/agreement.py writes in its column holds, by
# what they say: which reference holds in a region (its verdict() words them)
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
AGREEMENT_CSV = os.path.join(REPO, "reference", "pbrt", "agreement.csv")
AGREEMENT_COLUMNS = ["scene", "size", "region", "material_kind", "pixels", "pm_ratio", "pm_ci", "pm_bias",
                     "pov_ratio", "holds"]
# why POV-Ray's reference is off in a scene, where reference/README.md has
# measured it
POV_OFF_WHY = {"tworooms": "That room is lit only by light that bounced many times, and POV-Ray's irradiance cache "
                           "stops adding light after a few bounces (reference/README.md measures it bounce by bounce)."}
HOLDS_CLASS = (("all three agree", "all"), ("POV-Ray off", "pov_off"), ("photonmap (BDPT", "pm_specular"),
               ("undetermined", "undetermined"), ("pbrt and photonmap agree", "pm_pbrt"))


def holds_class(text):
    """The class of an agreement.csv verdict: 'all' (all three agree),
    'pov_off' (pbrt and photonmap agree, POV-Ray off), 'pm_specular'
    (photonmap holds on a mirror or glass region BDPT cannot sample),
    'undetermined', 'pm_pbrt' (pbrt and photonmap agree on a specular
    region), or 'other'."""
    for key, name in HOLDS_CLASS:
        if key in str(text):
            return name
    return "other"


def span(values):
    """(smallest, largest) of VALUES, or None when there are none."""
    v = [float(x) for x in values if isnum(x)]
    return (min(v), max(v)) if v else None


def record_references(d):
    """The three references region by region (reference/pbrt/agreement.csv,
    written by reference/measure-pbrt.sh): its settings line, every region
    row, and per scene the regions of each verdict class with the spans of
    photonmap / pbrt and POV-Ray / pbrt in each."""
    a = load(d["agreement"], AGREEMENT_COLUMNS, "bash reference/measure-pbrt.sh")
    with open(d["agreement"], encoding="utf-8") as f:
        first = f.readline().strip()
    settings = first[1:].strip() if first.startswith("#") else ""
    a["cls"] = [holds_class(h) for h in a["holds"]]
    a["diffuse"] = ~a["material_kind"].isin(["mirror", "glass"])
    scenes = []
    for (scene, size), g in a.groupby(["scene", "size"], sort=False):
        regions = g[g["material_kind"].notna()]
        by = {}
        for cls, h in regions.groupby("cls"):
            by[cls] = {"n": len(h), "pm": span(h["pm_ratio"]), "pov": span(h["pov_ratio"]),
                       "names": list(h["region"])}
        agree = regions[regions["cls"].isin(["all", "pov_off"]) & regions["diffuse"]]
        scenes.append({"scene": scene, "size": size, "regions": len(regions), "by": by,
                       "agree_pm": span(agree["pm_ratio"]), "agree_pov": span(agree["pov_ratio"]),
                       "agree_n": len(agree), "diffuse_n": int(regions["diffuse"].sum()),
                       "agree_ci": float(agree["pm_ci"].astype(float).max()) if len(agree) else math.nan})
    path = os.path.abspath(d["agreement"])
    return {"settings": settings, "scenes": scenes, "rows": [row_dict(r) for _, r in a.iterrows()],
            "path": os.path.relpath(path, REPO) if path.startswith(REPO + os.sep) else d["agreement"]}


def record_gather(d):
    """Final gathering (results/gather/gather.csv, make gather): per grid
    (scene, size) the equal-error speed-up over the targets that at least
    gather.DEFINED_MIN of the resamples reach on both fronts (how many lie
    wholly above 1, wholly below, the span of the speed-ups and of the
    targets), the gather phase's own speed-up with its interval, the
    precompute's share of the time saved (median and range), the memory
    increase and the work counters' bound; over all grids, those whose
    interval lies above 1 at every counted target (every) and the span of
    every counted speed-up (speedup)."""
    from experiments.analysis import gather as study
    g = load(d["gather"], ["scene", "size", "kind", "target", "speedup", "lo", "hi", "defined"], "make gather")
    grids = []
    for (scene, size), x in g.groupby(["scene", "size"], sort=False):
        ee = x[(x["kind"] == "equal_error") & (x["defined"] >= study.DEFINED_MIN)]

        def one(kind):
            r = x[x["kind"] == kind]
            return (float(r["speedup"].iloc[0]), float(r["lo"].iloc[0]), float(r["hi"].iloc[0])) if len(r) \
                else (math.nan,) * 3
        grids.append({"scene": os.path.splitext(os.path.basename(str(scene)))[0], "size": size, "targets": len(ee),
                      "above": int((ee["lo"] > 1).sum()), "below": int((ee["hi"] < 1).sum()),
                      "speedup": span(ee["speedup"]), "target": span(ee["target"]),
                      "lo": float(ee["lo"].min()) if len(ee) else math.nan,
                      "gather": one("gather_phase"), "share": one("precompute_share"),
                      "memory": one("memory_increase")[0], "bound": one("work_bound")[0]})
    if not grids:
        raise Missing(f"`{d['gather']}` has no grid (`make gather`)")
    return {"grids": grids, "published": study.PUBLISHED, "defined_min": study.DEFINED_MIN,
            "every": [x for x in grids if x["targets"] and x["above"] == x["targets"]],
            "speedup": span([v for x in grids for v in (x["speedup"] or ())])}


def record_equal_error(d):
    """The table's equal-error curve, per estimate (equal_error_record)."""
    return {"estimates": equal_error_record(load(d["equal_error"], EQUAL_ERROR_COLUMNS, "make reproduce-table"))}


VERDICTS = ("higher", "lower", "equivalent", "undetermined")


def changed_verdicts(primary, other):
    """[(key, primary's verdict, other's verdict)] of the keys of two
    {key: verdict} maps whose verdict words differ (keys in both only)."""
    return [(k, v, other[k]) for k, v in sorted(primary.items()) if k in other and other[k] != v]


def share_interval(bias, excess, lo, hi):
    """(share, share_lo, share_hi, defined) of the bias term BIAS in an
    excess EXCESS with the paired interval [LO, HI]: the share BIAS / EXCESS
    and its interval BIAS / [HI, LO], holding BIAS fixed (a cell's bias has
    one value, from its mean image). Not defined (nan ends) when the share
    is negative (the bias term falls while the error rises: the split of
    the excess into bias and variance says nothing there) or when the
    excess's interval reaches 0."""
    share = bias / excess if excess > 0 else np.nan
    if not (excess > 0 and bias >= 0 and lo > 0):
        return share, np.nan, np.nan, False
    return share, bias / hi, bias / lo, True


def record_cost(d):
    """What the speed costs in accuracy: the paired relMSE verdicts per
    estimate and cell (and the cells where the two estimates' verdicts
    differ), the bias share of the excess with its interval where the
    precomputed method ranks worse, and what more photons remove of the
    difference from the conventional image at each n."""
    t = load(d["table"], ["photons", "nn", "method", "relmse_diff_mean", "relmse_diff_lo", "relmse_diff_hi",
                          "relmse_diff_verdict", "relmse_conv_mean", "relmse_conv_ci95", "pairs"],
             "make reproduce-table")
    cells = load(d["cells"], ["method", "estimate", "photons", "nn", "relmse_ref_mean", "bias_ref"],
                 "make reproduce-table")
    p = prec_rows(t)
    verdicts = {}
    for est in ("paper", "corrected"):
        x = sfx(est)
        col = f"relmse_diff_verdict{x}"
        if col not in p.columns:
            continue
        groups = {}
        for _, r in p.iterrows():
            groups.setdefault(str(r[col]) if isinstance(r[col], str) else "undetermined", []).append(
                {"photons": r["photons"], "nn": r["nn"], "mean": r[f"relmse_diff_mean{x}"],
                 "lo": r[f"relmse_diff_lo{x}"], "hi": r[f"relmse_diff_hi{x}"],
                 "inside": inside_margin(r[f"relmse_diff_lo{x}"], r[f"relmse_diff_hi{x}"],
                                         r.get(f"relmse_diff_delta{x}", np.nan))})
        verdicts[est] = {"pairs": span_of(p[f"pairs{x}"]), "groups": groups}
    by_cell = {est: {(c["photons"], c["nn"]): k for k, cs in v["groups"].items() for c in cs}
               for est, v in verdicts.items()}
    changed = changed_verdicts(by_cell.get(PRIMARY_ESTIMATE, {}), by_cell.get(OTHER_ESTIMATE, {}))

    def paired(est, ph, n):
        r = p[(p["photons"] == ph) & (p["nn"] == n)]
        x = sfx(est)
        return (r.iloc[0][f"relmse_diff_lo{x}"], r.iloc[0][f"relmse_diff_hi{x}"]) if len(r) else (np.nan, np.nan)
    # bias share of the excess, per cell where the paired test ranks the
    # precomputed method worse (a share of a difference that may be zero is
    # no number)
    worse = {(est, c["photons"], c["nn"]) for est, v in verdicts.items() for c in v["groups"].get("higher", [])}
    shares = {}
    for est, g in cells.groupby("estimate", sort=False):
        for (ph, n), h in g.groupby(["photons", "nn"]):
            c = h[h["method"] == "conventional"]
            q = h[h["method"] == "precomputed"]
            if len(c) and len(q) and (est, ph, n) in worse:
                ex, bx = excess_and_bias(q, c)
                if ex > 0:
                    share, lo, hi, ok = share_interval(bx, ex, *paired(est, ph, n))
                    shares.setdefault(est, []).append({"photons": ph, "nn": n, "excess": ex, "bias": bx,
                                                       "share": share, "lo": lo, "hi": hi, "defined": ok})
    bias_share = [{"estimate": est, "cells": len(sh), "min": min(s["share"] for s in sh),
                   "max": max(s["share"] for s in sh), "largest": max(sh, key=lambda s: s["excess"]),
                   "rows": sorted(sh, key=lambda s: (s["photons"], s["nn"]))}
                  for est, sh in shares.items()]
    # the largest excess of the primary estimate where it ranks worse, with its bias share and
    # the other "higher" cells whose intervals overlap it (then no cell is ranked largest)
    worst = None
    x = sfx(PRIMARY_ESTIMATE)
    hi = p[p[f"relmse_diff_verdict{x}"] == "higher"] if f"relmse_diff_verdict{x}" in p.columns else p.iloc[:0]
    if len(hi):
        r = hi.loc[hi[f"relmse_diff_mean{x}"].idxmax()]
        c = cells[(cells["estimate"] == PRIMARY_ESTIMATE) & (cells["photons"] == r["photons"]) &
                  (cells["nn"] == r["nn"])]
        q, v = c[c["method"] == "precomputed"], c[c["method"] == "conventional"]
        share = share_lo = share_hi = None
        if len(q) and len(v):
            ex, bx = excess_and_bias(q, v)
            if ex > 0:
                sh, lo, up, ok = share_interval(bx, ex, r[f"relmse_diff_lo{x}"], r[f"relmse_diff_hi{x}"])
                share = sh
                if ok:
                    share_lo, share_hi = lo, up
        worst = {"photons": r["photons"], "nn": r["nn"], "mean": r[f"relmse_diff_mean{x}"],
                 "lo": r[f"relmse_diff_lo{x}"], "hi": r[f"relmse_diff_hi{x}"], "share": share,
                 "share_lo": share_lo, "share_hi": share_hi,
                 "overlaps": [(o["photons"], o["nn"]) for _, o in hi.iterrows()
                              if (o["photons"], o["nn"]) != (r["photons"], r["nn"])
                              and o[f"relmse_diff_hi{x}"] >= r[f"relmse_diff_lo{x}"]]}
    # the difference from the conventional image of the same seed: n against P_e
    conv = p[["photons", "nn", "relmse_conv_mean", "relmse_conv_ci95"]]
    phs = sorted(conv["photons"].unique())
    more = None
    if len(phs) >= 2:
        more = {"from": phs[0], "to": phs[-1], "factor": phs[-1] / phs[0], "per_n": []}
        for n, g in conv.groupby("nn"):
            a = g[g["photons"] == phs[0]]
            b = g[g["photons"] == phs[-1]]
            if len(a) and len(b):
                a, b = a.iloc[0], b.iloc[0]
                r = stats.rank((b["relmse_conv_mean"] - b["relmse_conv_ci95"], b["relmse_conv_mean"] + b["relmse_conv_ci95"]),
                               (a["relmse_conv_mean"] - a["relmse_conv_ci95"], a["relmse_conv_mean"] + a["relmse_conv_ci95"]))
                more["per_n"].append({"nn": n, "removed": 1 - b["relmse_conv_mean"] / a["relmse_conv_mean"],
                                      "disjoint": r in ("lower", "higher")})
    return {"pairs": span_of(p["pairs"]), "cells": len(p), "verdicts": verdicts, "bias_share": bias_share,
            "worst": worst, "more_photons": more, "changed": changed}


def record_bias(d):
    """The estimator's bias in the analytic scene: the paper estimate at
    n = 10 (else the smallest n) against the law n/(n-1), the precomputed
    method's paper estimate there beside n/(n-2) (None when the file has
    none), and the corrected intervals' coverage of 1."""
    b = load(d["bias"], ["n", "law_n_over_n_minus_1", "conventional_paper_mean", "conventional_paper_ci95",
                         "conventional_corrected_mean", "conventional_corrected_ci95", "precomputed_corrected_mean",
                         "precomputed_corrected_ci95", "conventional_paper_seeds"], "make estimator-bias")

    def on_law(r):
        """(lo, hi, equivalent) of the paper estimate's 95% interval over the
        law n/(n-1): equivalent when it lies inside 1 +- BIAS_MARGIN."""
        m, h, law = r["conventional_paper_mean"], r["conventional_paper_ci95"], r["law_n_over_n_minus_1"]
        lo, hi = (m - h) / law, (m + h) / law
        return lo, hi, bool(np.isfinite(lo) and np.isfinite(hi) and 1 - BIAS_MARGIN <= lo and hi <= 1 + BIAS_MARGIN)

    def at(s):
        r = s.iloc[0]
        lo, hi, eq = on_law(r)
        pre = None
        if {"precomputed_paper_mean", "precomputed_paper_ci95", "law_n_over_n_minus_2"} <= set(r.index) \
                and np.isfinite(r["precomputed_paper_mean"]):
            pre = {"mean": r["precomputed_paper_mean"], "ci95": r["precomputed_paper_ci95"],
                   "law": r["law_n_over_n_minus_2"]}
        return {"n": r["n"], "mean": r["conventional_paper_mean"], "ci95": r["conventional_paper_ci95"],
                "seeds": r["conventional_paper_seeds"], "law": r["law_n_over_n_minus_1"],
                "law_lo": lo, "law_hi": hi, "on_law": eq, "precomputed": pre}
    k_in, k_all, vals = corrected_coverage(b)
    eq = equivalence_to_one(b, BIAS_MARGIN)
    # the n where the law can be told from no bias at all: its margin and
    # 1's margin do not touch (n/(n-1) - 1 > 2 BIAS_MARGIN)
    laws = [on_law(r)[2] for _, r in b.iterrows() if np.isfinite(r["conventional_paper_mean"])
            and r["law_n_over_n_minus_1"] - 1 > 2 * BIAS_MARGIN]
    return {"equivalence": eq, "margin": BIAS_MARGIN, "equivalent": sum(e["equivalent"] for e in eq),
            "law_equivalent": sum(laws), "law_rows": len(laws),
            "at10": at(b[b["n"] == 10]) if (b["n"] == 10).any() else None,
            "quoted": at(b[b["n"] == 10] if (b["n"] == 10).any() else b[b["n"] == b["n"].min()]),
            "covered": k_in, "intervals": k_all,
            "lowest": min(vals, key=lambda v: v[0]) if vals else None,
            "highest": max(vals, key=lambda v: v[0]) if vals else None}


def record_caustic(d):
    """The caustic window's excess against the whole image's, per
    precomputed cell, ranked only by disjoint intervals."""
    c = load(d["caustic"], ["estimate", "photons", "nn", "method", "win_excess_mean", "win_excess_ci95",
                            "img_excess_mean", "img_excess_ci95", "seeds"], "make caustic")
    rows = []
    for _, r in c[c["method"] == "precomputed"].iterrows():
        w = (r["win_excess_mean"] - r["win_excess_ci95"], r["win_excess_mean"] + r["win_excess_ci95"])
        i = (r["img_excess_mean"] - r["img_excess_ci95"], r["img_excess_mean"] + r["img_excess_ci95"])
        rows.append({"estimate": r["estimate"], "photons": r["photons"], "nn": r["nn"], "win": r["win_excess_mean"],
                     "win_ci95": r["win_excess_ci95"], "img": r["img_excess_mean"], "img_ci95": r["img_excess_ci95"],
                     "seeds": r["seeds"], "rank": stats.rank(w, i)})
    return {"rows": rows}


def record_scenes(d):
    """The scenes' equal-error cells as scenes.csv words them, with their seeds."""
    s = load(d["scenes"], ["scene", "diff_seeds", "ee_paper", "ee_corrected"], "make scenes")
    return {"rows": [{"scene": r["scene"], "seeds": int(r["diff_seeds"]), "paper": r["ee_paper"],
                      "corrected": r["ee_corrected"]} for _, r in s.iterrows()],
            "coverage": few_seed_coverage(s["diff_seeds"])}


def record_resolution(d):
    """Per output size, smallest first: its equal-error record."""
    files = resolution_files(d)
    return {"dir": os.path.relpath(d["resolution"], d["root"]) if "root" in d else d["resolution"],
            "sizes": [{"size": os.path.basename(f)[len("equal-error-"):-4],
                       "file": os.path.relpath(f, d["root"]) if "root" in d else f,
                       "estimates": equal_error_record(load(f, EQUAL_ERROR_COLUMNS, "make resolution"))}
                      for f in files]}


def record_baseline(d):
    """The drift control: the photon-trace phase's paired ratio over the cells."""
    t = load(d["table"], ["method", "photons", "nn", "trace_ratio_percent", "trace_ratio_ci95_lo",
                          "trace_ratio_ci95_hi"], "make reproduce-table")
    p = prec_rows(t)
    off = p[(p["trace_ratio_ci95_hi"] < 100) | (p["trace_ratio_ci95_lo"] > 100)]
    return {"median": p["trace_ratio_percent"].median(), "min": p["trace_ratio_percent"].min(),
            "max": p["trace_ratio_percent"].max(), "off": len(off), "cells": len(p)}


def scaling_repeats(*rows):
    """The smallest repeats count of scaling.csv ROWS (1 where the file has
    no repeats column: one render, timed once)."""
    reps = [int(r["repeats"]) for r in rows if "repeats" in r and isnum(r["repeats"])]
    return min(reps) if reps else 1


def timed_text(repeats, each=True):
    """'one render each' or 'one process each, the minimum of its 3
    repeats' for a scaling comparison timed with REPEATS."""
    if repeats <= 1:
        return "one render each" if each else "one render"
    return f"one process{' each' if each else ''}, the minimum of its {repeats} repeats"


def record_scale(d):
    """Performance at scale: the largest map of each method in the scaling
    table, the two-thread speed-ups per map size, and for the conventional
    method's largest map its two-thread total."""
    sc = load(d["scaling"], ["method", "photons_emitted", "photons_stored", "threads", "trace_s", "build_s",
                             "precompute_s", "eye_s", "total_s", "bytes_per_stored"], "make bench-scaling")
    th = load(d["threads"], ["photons_emitted", "pair", "threads", "trace_s", "build_s", "total_s"],
              "make bench-threads")
    largest = [(m, row_dict(g.loc[g["photons_emitted"].idxmax()])) for m, g in sc.groupby("method", sort=False)]
    two = [{"photons": ph, **{col: threads.speedup(g, col) for col in ("trace_s", "build_s", "total_s")}}
           for ph, g in th.groupby("photons_emitted")]
    conv = None
    c = sc[sc["method"] == "conventional"]
    if len(c):
        r = c.loc[c["photons_emitted"].idxmax()]
        g = th[th["photons_emitted"] == r["photons_emitted"]]
        t2 = g[g["threads"] == 2]["total_s"]
        conv = {**row_dict(r), "two_total_median": np.median(t2) if len(t2) else None, "two_total_pairs": len(t2),
                "trace": threads.speedup(g, "trace_s"), "build": threads.speedup(g, "build_s")}
    # both methods at the largest map they share: the totals and each phase's difference
    both = None
    c, q = sc[sc["method"] == "conventional"], sc[sc["method"] == "precomputed"]
    common = sorted(set(c["photons_emitted"]) & set(q["photons_emitted"]))
    if common:
        a = c[c["photons_emitted"] == common[-1]].iloc[0]
        b = q[q["photons_emitted"] == common[-1]].iloc[0]
        phases = {k: float(b[f"{k}_s"] - a[f"{k}_s"]) for k in ("trace", "build", "precompute", "eye")}
        both = {"photons_emitted": common[-1], "photons_stored": a["photons_stored"], "threads": a["threads"],
                "repeats": scaling_repeats(a, b),
                "conventional": float(a["total_s"]), "precomputed": float(b["total_s"]),
                "precompute_s": float(b["precompute_s"]), "phases": phases,
                "largest_phase": max(phases, key=lambda k: abs(phases[k]))}
    return {"largest": largest, "two_threads": two, "conventional": conv, "both": both}


def record_stability(d):
    """Where the stability check's extremes are."""
    path = d["stability"]
    if not os.path.isfile(path):
        raise Missing(f"`{path}` is missing (`make stability`)")
    return {"file": os.path.relpath(path, d["root"])}


def record_beyond(d):
    """Beyond the paper's rule, the primary estimate (PRIMARY_ESTIMATE): per case the paper rule's
    and the best variant's speed-ups and what the goal's tests say, the
    count of cases that meet it, and each case's variants against the paper's rule (beyond_vs_paper)."""
    b = load(d["beyond"], ["case", "variant", "estimate", "target", "speedup", "lo", "hi", "defined_fraction",
                           "fallback_rate", "evaluated_share", "seeds", "best", "above_one", "vs_paper", "goal_met",
                           "image_group", "vs_paper_ratio", "vs_paper_ratio_lo", "vs_paper_ratio_hi"],
             "make beyond")
    b = b[b["estimate"] == PRIMARY_ESTIMATE]
    margin = stats.EQUIVALENCE_MARGIN
    cases = []
    for case, g in b.groupby("case", sort=False):
        seeds = int(g["seeds"].min())
        paper = g[g["variant"] == "paper"]
        best = g[g["best"].astype(bool)]
        c = {"case": case, "seeds": seeds, "variants": len(g) - 1, "vs": beyond_vs_paper(g)}
        if paper.empty or best.empty:
            c["status"] = "no best"
        elif seeds < MIN_SEEDS_QUOTED:
            c["status"] = "few seeds"
        elif min(float(paper.iloc[0]["defined_fraction"]), float(best.iloc[0]["defined_fraction"])) < ee.DEFINED_MIN:
            c["status"] = "undefined"
        else:
            r = best.iloc[0]
            c.update(status="quoted", paper=row_dict(paper.iloc[0]), best=row_dict(r), above=bool(r["above_one"]),
                     fragile=bool(r["above_one"]) and float(r["lo"]) < 1.0 + margin, met=bool(r["goal_met"]))
        cases.append(c)
    quoted = [c for c in cases if c["status"] == "quoted"]
    return {"cases": cases, "quoted": len(quoted), "met": sum(c["met"] for c in quoted),
            "decided": sum(c["status"] in ("quoted", "no best") for c in cases),
            "no_best": sum(c["status"] == "no best" for c in cases),
            "coverage": few_seed_coverage([c["seeds"] for c in cases]),
            "thin": sum(c["met"] and c["fragile"] for c in quoted)}


def beyond_vs_paper(g):
    """One case's variants against the paper's rule, paired per seed (Holm
    over the case's variants), from beyond.csv's rows G: {"faster",
    "slower", "unranked"}, each a list of (variant, others with the same
    images, ratio, lo, hi), the ratio the paper rule's time over the
    variant's (above 1: the variant is faster); a variant whose images are
    bit-identical to another's is reported in that one's row."""
    out = {"faster": [], "slower": [], "unranked": []}
    word = {"higher": "faster", "lower": "slower", "undetermined": "unranked"}
    for _, r in g.iterrows():
        v = str(r["variant"])
        if v == "paper" or str(r["image_group"]) != v or str(r["vs_paper"]) not in word:
            continue
        same = int((g["image_group"].astype(str) == v).sum()) - 1
        out[word[str(r["vs_paper"])]].append((v, same, float(r["vs_paper_ratio"]), float(r["vs_paper_ratio_lo"]),
                                              float(r["vs_paper_ratio_hi"])))
    return out


def beyond_vs_classes(cases):
    """The cases of record_beyond by their variants against the paper's
    rule: (faster: some variant faster; slower: every variant slower;
    neither: none faster, some not ranked), each a list of cases; cases
    without a paired test are in none."""
    faster = [c for c in cases if c["vs"]["faster"]]
    slower = [c for c in cases if not c["vs"]["faster"] and not c["vs"]["unranked"] and c["vs"]["slower"]]
    neither = [c for c in cases if not c["vs"]["faster"] and c["vs"]["unranked"]]
    return faster, slower, neither


def vs_variants_text(c, kind, detail, sep, noun=True):
    """The variants of case C in class KIND of beyond_vs_paper, joined by
    SEP: 'lazy', 'gated0.05 (and 2 settings with the same images)' ('and 2
    with' without NOUN), with DETAIL the paper rule's time over each one's
    and its interval."""
    f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731
    return sep.join(v + (f" (and {k}{(' setting' + ('s' if k > 1 else '')) if noun else ''} with the same images)"
                         if k else "")
                    + (f" {ci(r, lo, hi, f3)}" if detail else "") for v, k, r, lo, hi in c["vs"][kind])


VS_LABEL = {"faster": "faster", "slower": "slower", "unranked": "not ranked"}


def beyond_vs_text(rec, detail):
    """What the paired tests against the paper's rule say over the cases of
    REC: the count of cases where a variant is faster (named), where every
    variant is slower and where none is faster; with DETAIL, the paper
    rule's time over each named variant's, with its interval, and the range
    over the slower cases."""
    faster, slower, neither = beyond_vs_classes(rec["cases"])
    n = len(faster) + len(slower) + len(neither)
    f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731

    parts = [f"a variant is faster than the paper's rule in {len(faster)} of {n} scene and size cases"
             + (" (" + "; ".join(f"{c['case']}: {vs_variants_text(c, 'faster', detail, '; ')}" for c in faster)
                + ")" if faster else "")]
    if slower:
        ratios = [r for c in slower for _, _, r, _, _ in c["vs"]["slower"]]
        parts.append(f"in {len(slower)} every variant is slower ("
                     + (f"the paper rule's time over theirs {f3(min(ratios))} to {f3(max(ratios))}; " if detail else "")
                     + "each group of variants with identical images tested once)")
    if neither:
        parts.append(f"in {len(neither)} ({count_list(c['case'] for c in neither)}) none is faster and some are "
                     "not ranked")
    return "; ".join(parts[:-1]) + (", and " if len(parts) > 1 else "") + parts[-1]


def record_repro(d):
    """Reproducibility between two runs: reproducibility.csv's summary row
    (the rows of runs `a-b` where the file names its runs), and the busy
    run's against run a (rows `a-busy`) when the file has them."""
    r = load(d["repro"], ["summary_ratio_median_abs_delta_pp", "summary_ratio_max_abs_delta_pp",
                          "summary_ratio_overlap_cells", "summary_cells", "summary_goal_pp", "summary_met"],
             "make reproducibility")

    def summ(s):
        out = {"median_pp": s["summary_ratio_median_abs_delta_pp"], "max_pp": s["summary_ratio_max_abs_delta_pp"],
               "overlap": int(s["summary_ratio_overlap_cells"]), "cells": int(s["summary_cells"]),
               "goal_pp": s["summary_goal_pp"], "met": bool(s["summary_met"]),
               "design": "two runs of `make reproduce-table`, one after the other" if "runs" in r.columns
               else "two interleaved runs of the grid"}
        # the goal's other clauses, where the file has them (the sequential design)
        for k in ("max_pp", "drift_lo", "drift_hi", "drift_inside_cells", "drift_min", "drift_max",
                  "process_change_median", "process_change_p90", "drift_inside_cells_a", "drift_inside_cells_b",
                  "drift_inside_cells_min2", "drift_inside_cells_min3"):
            v = s.get(f"summary_{k}")
            out[f"goal_{k}" if k == "max_pp" else k] = float(v) if isnum(v) else None
        return out
    if "runs" not in r.columns:
        return summ(r.iloc[0])
    ab, busy = r[r["runs"] == "a-b"], r[r["runs"] == "a-busy"]
    if ab.empty:
        raise Missing(f"`{d['repro']}` has no row of runs a-b (`make reproducibility`)")
    out = summ(ab.iloc[0])
    out["busy"] = summ(busy.iloc[0]) if len(busy) else None
    return out


def record_rules(d):
    """The representative rules' tests as repstudy.py made them (chi^2 per
    rule with the degrees of freedom it has left, Holm over the rules), read
    from rep-study-rules.csv."""
    r = load(d["rep"], ["rule", "label", "fitted", "chi2", "dof", "p_value", "p_holm", "verdict"], "make rep-study")
    rows = [row_dict(x) for _, x in r.iterrows()]
    from experiments.analysis import repstudy
    sens = [{"factor": f, "rejected": [x["label"] for _, x in r.iterrows()
                                       if x[repstudy.sensitivity_column(f)] == "incompatible"]}
            for f in repstudy.SENSITIVITY if repstudy.sensitivity_column(f) in r.columns]
    return {"rows": rows, "rejected": [x["label"] for x in rows if x["verdict"] == "incompatible"],
            "sensitivity": sens}


def sensitivity_text(rec):
    """'; at half that noise they reject 2 (A and C), and at twice that
    noise none' from REC's sensitivity list: the rules the paper's times
    reject with their assumed noise scaled ('' when the rules file has no
    such columns)."""
    said = []
    for a in rec.get("sensitivity", []):
        f = {0.5: "half that", 2.0: "twice that"}.get(a["factor"], f"{fmt(a['factor'])} times that")
        bad = a["rejected"]
        verb = "" if said else "they reject "
        said.append(f"at {f} noise {verb}" + (f"{len(bad)} ({count_list(bad)})" if bad else "none"))
    return ("; " + ", and ".join(said)) if said else ""


def record_metric(d):
    """The error metric: per estimate, the Spearman correlation of the
    cells' mean relMSE and NMSE, their ratio's range, and the cells whose
    paired verdict (Holm) differs between the two."""
    r = load(d["runs"], ["role", "status", "method", "estimate", "photons", "nn", "seed", "relmse_ref", "nmse_ref"],
             "make reproduce-table")
    r = r[(r["role"] == "grid") & (r["status"] == "ok")]
    out = []
    for est, g in r.groupby("estimate", sort=False):
        means = g.groupby(["method", "photons", "nn"])[["relmse_ref", "nmse_ref"]].mean()
        verdicts = {}
        for col in ("relmse_ref", "nmse_ref"):
            cells = []
            for (ph, n), h in g.groupby(["photons", "nn"]):
                a = h[h["method"] == "precomputed"].set_index("seed")[col]
                b = h[h["method"] == "conventional"].set_index("seed")[col]
                seeds = sorted(set(a.index) & set(b.index))
                if seeds:
                    cells.append(((ph, n), a.loc[seeds].to_numpy(), b.loc[seeds].to_numpy()))
            keys, comps = stats.paired_family(cells)
            verdicts[col] = dict(zip(keys, (c["verdict"] for c in comps)))
        ratio = (means["nmse_ref"] / means["relmse_ref"]).to_numpy(np.float64)
        out.append({"estimate": est, "cells": len(means),
                    "rho": sps.spearmanr(means["relmse_ref"], means["nmse_ref"]).statistic,
                    "ratio_min": np.min(ratio), "ratio_max": np.max(ratio), "compared": len(verdicts["relmse_ref"]),
                    "changed": [(k, verdicts["relmse_ref"][k], verdicts["nmse_ref"].get(k))
                                for k in verdicts["relmse_ref"]
                                if verdicts["relmse_ref"][k] != verdicts["nmse_ref"].get(k)]})
    return {"estimates": out}


def per_run_range(f, k, peer, ours):
    """(smallest, largest) over the timed runs of peers.csv's frame F (tile
    order, k) of PEER's seconds over OURS's in the same run (every answer
    of a run times the same queries one after another), or None."""
    g = f[(f["order"] == "tiles") & (f["k"].astype(int) == k) & f["rep"].astype(str).str.fullmatch(r"\d+")]
    t = g.pivot_table(index="rep", columns="who", values="seconds", aggfunc="first")
    if peer not in t.columns or ours not in t.columns:
        return None
    r = (t[peer] / t[ours]).dropna()
    return (float(r.min()), float(r.max())) if len(r) else None


def record_peers(d):
    """The kd-tree against the peers in tile order, per k: the map size, the
    strongest peer and its and nanoflann's query rate relative to ours."""
    f = load(d["peers"], ["who", "order", "pe", "stored", "k", "queries", "rep", "seconds"], "make bench")
    got = {}
    for order, pe, _, k, _, med in bench_report.peer_medians(f):
        if order == "tiles":
            got[int(k)] = (pe, med)
    rows = []
    for k in sorted(got):
        pe, med = got[k]
        best = bench_report.strongest_peer(med)
        row = {"k": k, "pe": pe, "strongest": best, "strongest_ratio": med[best] / med["ours"],
               "nanoflann_ratio": med["nanoflann"] / med["ours"],
               "strongest_range": per_run_range(f, k, best, "ours")}
        if "ours-stateless" in med:
            row["stateless_ratio"] = med[best] / med["ours-stateless"]
            row["stateless_range"] = per_run_range(f, k, best, "ours-stateless")
        rows.append(row)
    return {"file": d["peers"], "rows": rows}


RECORDS = {"table": record_table, "precompute": record_precompute, "reference_error": record_reference_error,
           "figure3": record_figure3, "judges": record_judges, "references": record_references,
           "equal_error": record_equal_error,
           "cost": record_cost, "bias": record_bias,
           "caustic": record_caustic, "scenes": record_scenes, "resolution": record_resolution,
           "baseline": record_baseline, "scale": record_scale, "stability": record_stability,
           "beyond": record_beyond, "repro": record_repro, "rules": record_rules, "metric": record_metric,
           "peers": record_peers, "gather": record_gather}


# the figures each finding shows, relative to the results directory (a
# pattern may match several; a file that is not there is left out)
FIGURES = {"table": ("figures/ratio-vs-n.png",), "precompute": ("figures/phases.png",),
           "figure3": ("figures/fig3.png", "figures/fig3-errors.png"),
           "equal_error": ("table1/equal-error.png", "figures/tradeoff.png"), "caustic": ("figures/caustic.png",),
           "scenes": ("figures/scenes.png",), "resolution": ("resolution/equal-error-*.png",),
           "scale": ("figures/bench-scaling.png",), "beyond": ("figures/beyond.png",),
           "rules": ("figures/rep-study.png", "figures/fig2.png"), "gather": ("figures/gather.png",),
           "repro": ("reproducibility/equal-error-a.png", "reproducibility/equal-error-b.png")}


def figures_of(d):
    """{finding: [figure paths relative to D's root]} of the FIGURES that exist."""
    root = d["root"]
    out = {}
    for name, pats in FIGURES.items():
        got = []
        for pat in pats:
            got += sorted(os.path.relpath(f, root) for f in glob.glob(os.path.join(root, pat)))
        if got:
            out[name] = got
    return out


def records(d):
    """Every finding's record from the results files D names: name -> the
    record, or the Missing that says why there is none; under "figures",
    figures_of(D)."""
    out = {}
    for name, fn in RECORDS.items():
        try:
            out[name] = fn(d)
        except Missing as e:
            out[name] = e
    out["figures"] = figures_of(d) if "root" in d else {}
    return out


# ---- FINDINGS.md: one section per record; each writer returns (title,
# [lines]) from its record or raises Missing

def pairs_text(pairs):
    """'5 pairs', or '3-5 pairs' where the cells differ, of a (smallest, largest)."""
    lo, hi = pairs
    return f"{lo} pairs" if lo == hi else f"{lo}-{hi} pairs"


def word_rank(r, what_a, what_b):
    """A sentence part wording the stats.rank verdict R of two unpaired intervals."""
    if r == "higher":
        return f"{what_a} is ranked above {what_b} (disjoint 95% intervals)"
    if r == "lower":
        return f"{what_a} is ranked below {what_b} (disjoint 95% intervals)"
    return f"{what_a} against {what_b}: undetermined (the 95% intervals overlap)"


def md_table(rec):
    """Finding 1: the table's shape."""
    lines = [f"Paired time ratio precomputed / conventional (per-seed log ratios of the renderer's own time, "
             f"95% t interval over {pairs_text(rec['pairs'])}), % "
             "(the paper's single measurement in brackets):", ""]
    rows = []
    for n in rec["nns"]:
        r = [str(int(n))]
        for ph in rec["photons"]:
            s = rec["grid"][(n, ph)]
            r.append("n/a" if s is None else f"{ci(s['ratio'], s['lo'], s['hi'], pct)} ({pct(s['paper'])})")
        rows.append(r)
    lines += report.md_table(["n"] + [f"P_e = {cell(ph, 0)[1:-4]}" for ph in rec["photons"]], rows)
    lines.append("")
    for ph, s in rec["over_n"].items():
        if s["count"] >= 2:
            lines.append(f"- Over n at P_e = {int(ph)}: " + word_rank(s["rank"], f"the ratio at n = {int(s['last']['nn'])}",
                                                                        f"the one at n = {int(s['first']['nn'])}") + ".")
    for n, s in rec["over_p"].items():
        if s["count"] >= 2:
            lines.append(f"- Over P_e at n = {int(n)}: " + word_rank(s["rank"], f"the ratio at P_e = {int(s['last']['photons'])}",
                                                                       f"the one at P_e = {int(s['first']['photons'])}") + ".")
    lines.append("- The paper's value lies inside our interval in " + ", ".join(
        f"{k} of {m} cells at P_e = {int(ph)}" for ph, (k, m) in rec["inside"].items()) +
        " (the paper's values are one run each, with no interval: a value outside ours is a difference "
        "only if the paper's own run-to-run spread is smaller than our interval)" + other_inside_text(rec) + ".")
    return "The time ratio over n and P_e, against the paper's", lines


def headline_text(h):
    """'the speed-up is S [lo, hi]x at relMSE T, the tightest target ...' of
    a headline row, or the sentence that there is none."""
    if h is None:
        return f"at no target of the curve do {100 * ee.DEFINED_MIN:.0f}% of the resamples reach both fronts, " \
            "so no speed-up is quoted"
    return f"at {fmt(h['target'])}, the tightest target that at least {100 * ee.DEFINED_MIN:.0f}% of the " \
        f"resamples reach on both fronts, the speed-up is {ci(h['speedup'], h['lo'], h['hi'])}x"


# where an equal-error curve starts, said once before the lines that give it
CURVE_START = ("A curve starts at the tightest error both fronts reach (the larger of the two fronts' smallest "
               f"errors); a speed-up is quoted only at a target that at least {100 * ee.DEFINED_MIN:.0f}% of the "
               "bootstrap resamples reach on both fronts.")


def equal_error_lines(recs):
    """One line per estimate of an equal_error_record list: where the curve
    starts (CURVE_START says what that is), the speed-up at the headline
    target (equal_error.headline) and the range of the curve where it is
    defined."""
    lines = []
    for r in recs:
        est, t, span = r["estimate"], r["tightest"], r["span"]
        if t is None:
            lines.append(f"- {est} estimate: the two fronts reach no common {metrics.PRIMARY}: no speed-up at equal "
                         "error is defined.")
            continue
        s = f"- {est} estimate: the curve starts at {metrics.PRIMARY} {fmt(t['target'])}" \
            + (" (too few resamples reach it for a speed-up there)" if t["defined_fraction"] < ee.DEFINED_MIN
               else "") + f"; {headline_text(r['headline'])}"
        s += f". Over the {r['curve_targets']} targets of the curve ({fmt(r['curve_min'])} to " \
             f"{fmt(r['curve_max'])}), {trend_text(r)}"
        if span is not None:
            s += f". Along the curve, {regions_text(r['regions'])}"
        lines.append(s + ".")
    return lines


def md_equal_error(rec):
    """Finding 2: equal error."""
    return "The speed-up at equal error", [CURVE_START, ""] + equal_error_lines(rec["estimates"])


def md_cost(rec):
    """Finding 3: what the speed costs in accuracy."""
    lines = []
    words = {"higher": "the precomputed method ranked worse (higher error, Holm-corrected p < 0.05)",
             "lower": "ranked better", "equivalent":
             f"equivalent within delta = {fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional error",
             "undetermined": "undetermined"}
    for est, v in rec["verdicts"].items():
        parts = [f"{words[k]} in " + ", ".join(f"{cell(c['photons'], c['nn'])} ({fmt(c['mean'])} "
                                               f"[{fmt(c['lo'])}, {fmt(c['hi'])}]"
                                               + (", inside delta: ranked, by less than the margin"
                                                  if k in ("higher", "lower") and c.get("inside") else "") + ")"
                                               for c in v["groups"][k])
                 for k in VERDICTS if k in v["groups"]]
        lines.append(f"- {est} estimate, paired {metrics.PRIMARY} difference precomputed - conventional per seed "
                     f"({v['pairs'][0]} pairs per cell): " + "; ".join(parts) + ".")
    for s in rec["bias_share"]:
        parts = []
        for k in s["rows"]:
            if k["defined"]:
                parts.append(f"{cell(k['photons'], k['nn'])} {pct(100 * k['share'])}% [{pct(100 * k['lo'])}, "
                             f"{pct(100 * k['hi'])}]")
            elif k["share"] < 0:
                parts.append(f"{cell(k['photons'], k['nn'])} {pct(100 * k['share'])}%: negative, the bias term "
                             "falls where the error rises, so the split into bias and variance is not defined there")
            else:
                parts.append(f"{cell(k['photons'], k['nn'])}: the excess's interval reaches 0, no share")
        lines.append(f"- {s['estimate']} estimate: where the paired test ranks the precomputed method's error above the "
                     f"conventional one ({s['cells']} cells), the bias term's share of the excess (the two methods' "
                     "difference of cells.csv bias_ref, precomputed - conventional, over the paired excess; the interval is the paired excess's 95% interval with the bias term "
                     "held fixed, since a cell's bias has one value, from its mean image): " + "; ".join(parts) + ".")
    m = rec["more_photons"]
    if m is not None:
        lines.append(f"- The precomputed image's {metrics.PRIMARY} against the conventional image of the same seed: "
                     f"{int(m['factor'])} times the photons ({int(m['from'])} to {int(m['to'])}) removes "
                     + ", ".join(f"n = {int(x['nn'])}: {pct(100 * x['removed'])}% " +
                                 ("(disjoint intervals)" if x["disjoint"] else "(intervals overlap: undetermined)")
                                 for x in m["per_n"]) + " of it: the photon count matters as well as n.")
    return "What the speed costs in accuracy", lines


def md_bias(rec):
    """Finding 4: the estimator's bias in the analytic scene."""
    lines = []
    r = rec["at10"]
    if r is not None:
        lines.append(f"- Conventional, paper estimate, at n = 10: {fmt(r['mean'], 5)} ± "
                     f"{fmt(r['ci95'], 2)} ({int(r['seeds'])} seeds); the law "
                     f"n/(n-1) gives {fmt(r['law'], 5)}{law_text(rec)}.")
    lo, hi = rec["lowest"], rec["highest"]
    if lo is None:
        raise Missing("`estimator-bias.csv` has no finite corrected interval (`make estimator-bias`)")
    lines.append("- With `--bias-correction` " + bias_equivalence_text(rec) + f"; the means run from "
                 f"{fmt(lo[0], 5)} ± {fmt(lo[1], 2)} to {fmt(hi[0], 5)} ± {fmt(hi[1], 2)}.")
    wide = [e for e in rec["equivalence"] if not e["equivalent"]]
    if wide:
        lines.append("- Not shown equivalent (the interval reaches beyond the margin): " + "; ".join(
            f"{e['method']} n = {e['n']}: {fmt(e['mean'], 5)} ± {fmt(e['half'], 2)}" for e in wide) + ".")
    if r is not None and r["precomputed"] is not None:
        lines.append(f"- {precomputed_bias_text(r)}.")
    return "The paper's estimator is biased by a law", lines


def precomputed_bias_text(at):
    """'The precomputed method's paper estimate at n = 10 is 1.1696 +- 0.0037:
    ... n/(n-2) (1.25) ...' of a bias record's quoted row AT."""
    p = at["precomputed"]
    return (f"The precomputed method's paper estimate follows another law: {fmt(p['mean'], 5)} ± {fmt(p['ci95'], 2)} "
            f"at n = {int(at['n'])}. At a representative its n nearest photons include itself, so the estimate "
            f"there follows n/(n-2) ({fmt(p['law'], 4)}); the eye pass's nearest-representative lookup weights "
            "representatives by the area they serve, which pulls the image below that")


def md_caustic(rec):
    """Finding 5: the caustic window's excess against the whole image's."""
    lines = [f"- {r['estimate']} {cell(r['photons'], r['nn'])}: excess in the window "
             f"{fmt(r['win'])} ± {fmt(r['win_ci95'])}, over the image "
             f"{fmt(r['img'])} ± {fmt(r['img_ci95'])} ({int(r['seeds'])} seeds): "
             + word_rank(r["rank"], "the window's", "the image's") + "." for r in rec["rows"]]
    lines.append("- Overlap is not equality: the file holds no paired window-minus-image test with a margin, "
                 "so no cell is called equal.")
    return "The caustic window against the whole image", lines


def few_seeds(name, seeds, make, cover=None):
    """The line that names NAME's intervals as too few-seeded to quote
    (fewer than MIN_SEEDS_QUOTED seeds) and the MAKE command that reruns it;
    COVER: the simulated coverage of a nominal 95% interval at that many
    seeds (few_seed_coverage), quoted when given."""
    how = (f" (a nominal 95% percentile-bootstrap interval of a mean of {seeds} normal values covers the truth "
           f"{pct(100 * cover)}% of the time in {coverage.TRIALS} simulated trials, coverage.py)"
           if cover is not None else "")
    return (f"- {name}: {seeds} seeds: its percentile-bootstrap intervals are not quoted{how}; rerun "
            f"`{make} SEEDS={MIN_SEEDS_QUOTED}` or more.")


def few_seed_coverage(seeds):
    """{s: simulated coverage of a 95% percentile-bootstrap interval of a
    mean at s seeds} for each s of SEEDS below MIN_SEEDS_QUOTED (at least 2)."""
    return {int(k): coverage.percentile_coverage(int(k)) for k in sorted(set(seeds))
            if 2 <= int(k) < MIN_SEEDS_QUOTED}


def md_scenes(rec):
    """Finding 6: the scenes' speed-ups, quoted only where enough seeds stand behind an interval."""
    return "Across scenes", [
        few_seeds(r["scene"], r["seeds"], "make scenes", rec.get("coverage", {}).get(r["seeds"]))
        if r["seeds"] < MIN_SEEDS_QUOTED else
        f"- {r['scene']} ({r['seeds']} seeds): paper estimate {r['paper']}; corrected {r['corrected']} "
        "(target: speed-up [95% bootstrap interval])." for r in rec["rows"]]


def md_resolution(rec):
    """Finding 7: the speed-up at equal error per output size."""
    if not rec["sizes"]:
        raise Missing(f"no `{rec['dir']}/equal-error-WxH.csv` (`make resolution`)")
    lines = [CURVE_START, ""]
    for s in rec["sizes"]:
        lines += [f"- {s['size']}:"] + ["  " + x for x in equal_error_lines(s["estimates"])]
    lines.append("- Each size is judged against its own reference (`resolution/resolution.md` gives each one's "
                 "measured noise and kernel bias).")
    return "The speed-up at equal error per output size", lines


def md_precompute(rec):
    """Finding T: where the precomputed method's time goes, ours against the paper's implied."""
    lines = ["Model: the paper's precompute = its precomputed time - its conventional time x (our precomputed "
             "method's time outside the precompute / our conventional time), per cell; it assumes the paper's "
             "photon pass, build and eye pass stand to its conventional time as ours do. Our times: medians over "
             f"seeds ({PRIMARY_ESTIMATE} estimate, `table1/table1.csv`); the paper's: its single runs.", ""]
    lines += report.md_table(
        ["cell", "paper (s)", "paper conv. (s)", "our rest / our conv.", "paper's precompute share (model)",
         "our precompute share", "paper µs per representative (model)"],
        [[cell(c["photons"], c["nn"]), fmt(c["paper_s"]), fmt(c["paper_conv_s"]), fmt(c["rest"]),
          f"{pct(100 * c['paper_share'])}%", f"{pct(100 * c['ours_share'])}%", fmt(1e6 * c["paper_per_rep"])]
         for c in rec["cells"]])
    lines.append("")
    lines.append("- Our precompute per representative (runs.csv precompute_s / representatives, median over the "
                 "grid's precomputed renders): " + ", ".join(f"{fmt(1e6 * v)} µs at P_e = {k_of(ph)}"
                                                           for ph, v in sorted(rec["per_rep"].items())) + ".")
    lines.append(f"- At P_e = {k_of(rec['top'])} the model gives the paper's precompute "
                 f"{pct(100 * rec['paper_share'][0])}-{pct(100 * rec['paper_share'][1])}% of its precomputed time, "
                 f"ours takes {pct(100 * rec['ours_share'][0])}-{pct(100 * rec['ours_share'][1])}%; per "
                 f"representative the paper's is {fmt(1e6 * rec['paper_per_rep'])} µs on its machine, "
                 f"{fmt(1e6 * rec['paper_per_rep_here'])} µs scaled to ours by the ratio of the two conventional "
                 f"times ({fmt(rec['machine'])}x; the median of the cells' scaled values), against our "
                 f"{fmt(1e6 * rec['ours_per_rep'])} µs.")
    if rec["negative"]:
        lines.append(f"- The model gives a negative precompute at {count_list([cell(*k) for k in rec['negative']])}: "
                     "there its assumption fails or the paper's single times are noisier than the difference, and "
                     "the model says nothing.")
    neg = set(rec["negative"])
    kept = [c for c in rec["cells"] if (c["photons"], c["nn"]) not in neg]
    top = [1e6 * c["paper_per_rep"] for c in kept if c["photons"] == rec["top"]]
    rest = [1e6 * c["paper_per_rep"] for c in kept if c["photons"] != rec["top"]]
    if top and rest:
        lines.append(f"- How far to trust it: the model's cost per representative on the paper's machine, which "
                     f"should not depend on the cell, runs from {fmt(min(top))} to {fmt(max(top))} µs over the "
                     f"P_e = {k_of(rec['top'])} cells and from {fmt(min(rest))} to {fmt(max(rest))} µs over the others"
                     + (" (the negative cells left out)" if neg else "") + ". The "
                     f"P_e = {k_of(rec['top'])} shares are an estimate with that spread, from single runs, not a "
                     "measurement; what stands without the model is that the paper's method was slower than its "
                     "baseline there and ours is not.")
    return "Where the precomputed method's time goes, ours against the paper's", lines


def md_reference_error(rec):
    """Finding E: Table 1's reference's own error against the cells' margins."""
    fl = rec["floor"]
    lines = [f"- Table 1 is judged against POV-Ray's reference preset, whose own noise and bias are not measured; "
             f"the only proxy is the fast preset's {primary_name()} against it, {fmt(fl)} (table1.csv "
             "relmse_ref_floor)"
             + (f", {pct(100 * fl / rec['tightest'])}% of the tightest equal-error target ({fmt(rec['tightest'])})"
                if rec["tightest"] else "") + "."]
    for est, e in rec["estimates"].items():
        s = f"- {est} estimate: "
        if e["times"] is not None:
            s += (f"the proxy is {fmt(e['times'][0])}-{fmt(e['times'][1])} times the margin delta of the "
                  f"{e['judged']} cells called equivalent or lower. ")
        s += ("Widening each cell's margin to the larger of delta and the proxy (a difference smaller than the "
              "reference's own error is not resolved), and ranking only an interval wholly beyond it (the paired "
              "95% intervals, not Holm-adjusted): ")
        s += ("no verdict changes" if not e["changed"] else "the verdicts change in " + count_list(
            [f"{cell(r['photons'], r['nn'])} ({r['verdict']} -> {r['widened']})" for r in e["changed"]]))
        lines.append(s + ".")
    lines.append(f"- The primary metric is {primary_name()}: every study's targets and every earlier table are in "
                 "it (experiments/analysis/metrics.py says why); NMSE, relative at every brightness, is reported "
                 "beside it, and where it changes the paired verdicts is finding M.")
    return "Table 1's reference and its own error", lines


def md_figure3(rec):
    """Finding F: the paper's Figure 3 statements against the paired data."""
    lines = [f"The paper's Figure 3 says the two methods' images differ or are alike at three cells; the verdict "
             f"here is the paired {primary_name()} difference precomputed - conventional per seed: \"differ\" "
             "when the Holm-corrected test ranks the two and the 95% interval is not inside +-delta "
             f"({fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional error), \"alike\" when the interval lies "
             "inside +-delta (a difference the test detects but smaller than delta is alike: the claim is about "
             "how the images look), else undetermined"
             + (f"; beside it, the verdict with the margin widened to the reference's own error ({fmt(rec['floor'])})"
                if rec["floor"] is not None else "") + ".", ""]
    for r in rec["rows"]:
        if not r["present"] or PRIMARY_ESTIMATE not in r:
            lines.append(f"- {cell(r['photons'], r['nn'])}: not in table1.csv.")
            continue
        a = r[PRIMARY_ESTIMATE]
        agree = ("agree" if a["word"] == r["said"] else "decide nothing" if a["word"] == "undetermined"
                 else "disagree")
        s = (f"- {cell(r['photons'], r['nn'])}: the paper says {r['said']}; {PRIMARY_ESTIMATE} estimate "
             f"{ci(a['mean'], a['lo'], a['hi'])} (delta {fmt(a['delta'])}): {a['word']}"
             + (" (ranked, by less than delta)" if a.get("ranked_within") else "") + f", so the data {agree}")
        if a["wide"] is not None:
            s += f"; at the reference's error: {a['wide']}"
        o = r.get(OTHER_ESTIMATE)
        if o is not None and o["word"] != a["word"]:
            s += f" ({OTHER_ESTIMATE} estimate: {ci(o['mean'], o['lo'], o['hi'])}, {o['word']})"
        lines.append(s + ".")
    return "The paper's Figure 3 claim", lines


def readme_figure3(rec):
    """README's summary bullet on the paper's Figure 3 claim from its record REC: at each of Figure 3's
    cells in table1.csv, what the paper says and the paired data's verdict; raises Missing when table1.csv has
    none of those cells."""
    parts = []
    for r in rec["rows"]:
        if r["present"] and PRIMARY_ESTIMATE in r:
            a = r[PRIMARY_ESTIMATE]
            o = r.get(OTHER_ESTIMATE)
            beside = f", {OTHER_ESTIMATE} estimate {o['word']}" if o is not None and o["word"] != a["word"] else ""
            wide = (f" (within the reference's own error: {a['wide']})"
                    if a["wide"] is not None and a["wide"] != a["word"] else "")
            within = (f" (a difference is detected, by less than {fmt(100 * stats.EQUIVALENCE_MARGIN)}%)"
                      if a.get("ranked_within") else "")
            parts.append(f"at {cell(r['photons'], r['nn'])} the paper says {r['said']}, the paired data say "
                         f"{a['word']}{within}{wide}{beside}")
    if not parts:
        raise Missing("`table1.csv` has none of Figure 3's cells (`make reproduce-table`)")
    return (f"- **The paper's Figure 3 claim, against the paired {primary_name()}** ({PRIMARY_ESTIMATE} estimate; "
            f"differ = ranked by the Holm-corrected test, its interval not inside a "
            f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}% margin; alike = the interval inside that margin): " + "; ".join(parts) + " (`results/table1/table1.csv`).")


def md_judges(rec):
    """Finding J: which reference judges which study, and the converged references' own error."""
    lines = report.md_table(["study", "judged by", "why"], [
        [f"{x['study']} (`{x['make']}`)", ", ".join(x["kinds"]) or f"no cells file (`{x['pattern']}`)",
         x["why"] if x["kinds"] else "not run here"] for x in rec["studies"]]
        + [[f"{x['study']} (`{x['make']}`)", x["by"], "no reference image"] for x in rec["none"]])
    kinds = sorted({k for x in rec["studies"] for k in x["kinds"]})
    lines += [""] + [f"- {k}: {REFERENCE_WHY[k]}." for k in kinds]
    lines.append("")
    lines.append("pbrt-v3 judges no study: it checks the other two (finding A). The converged references beyond/ uses, with their own error in "
                 f"{primary_name()} (as beyond's runs files carry it from the JSON reference.py writes beside "
                 "each, else that JSON, else a study's Markdown that quotes it), and each as a share of the tightest "
                 "target on its equal-error curves (the largest shares: the targets finding B counts are no tighter):")
    lines.append("")
    if not rec["beyond"]:
        lines.append("- beyond/ names no reference (`make beyond`).")
    for r in rec["beyond"]:
        if r["noise"] is None:
            lines.append(f"- {count_list(r['cases'])}: `{r['ref']}`: beyond's runs files carry no ref_noise, its "
                         "JSON is missing here (the references live under results/runs/, which is not committed; "
                         "`make beyond` writes them) and no study's Markdown quotes its error, so its noise and bias "
                         "are not reported.")
            continue
        t = r["tightest"]
        share = (f"; tightest target {fmt(t)}: noise {pct(100 * r['noise'] / t)}%, bias "
                 f"{pct(100 * r['bias'] / t)}% of it" if t else "")
        lines.append(f"- {count_list(r['cases'])}: noise {fmt(r['noise'])}, kernel bias {fmt(r['bias'])} "
                     f"(`{r['source']}`){share}.")
    lines += ["", "Corrected for the reference's own noise: every runs file carries `relmse_ref_less_noise`, a "
              f"render's {primary_name()} less its reference's measured noise (collect.py; equal to {primary_name()} "
              "where the noise is not measured). A reference's noise is independent of the renders it judges, so "
              "to first order it adds the same constant to every render's error against it: the paired differences "
              "and the speed-ups at equal error do not change under the correction; the targets' labels move by that "
              "constant (the list above gives it as a share of each study's tightest target), and the equivalence "
              f"margins, {fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional error, shrink by "
              f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}% of it, so a verdict of equivalence near its margin could turn "
              "undetermined."]
    return "What judges what", lines


def max_bias_term(sp):
    """What a reference r = q t off the truth t by a ratio q in the span SP
    = (lo, hi) adds to an unbiased render's relMSE = mean((x - r)^2 / (r^2 +
    0.01)), at most: (1/q - 1)^2 at the q farthest from 1 (a pixel's term
    is (1 - q)^2 t^2 / (q^2 t^2 + 0.01) <= (1/q - 1)^2)."""
    return max((1 / sp[0] - 1) ** 2, (1 / sp[1] - 1) ** 2)


def span_text(sp, f="{:.3f}"):
    """'0.986-0.996', one value when both ends agree, '-' for None."""
    if sp is None:
        return "-"
    a, b = f.format(sp[0]), f.format(sp[1])
    return a if a == b else f"{a}-{b}"


def md_references(rec):
    """Finding A: the three references side by side, region by region, and
    where each is trusted and why."""
    sc = rec["scenes"]
    lines = [f"Three references of the same scenes, compared region by region (`{rec['path']}`, written by "
             "`bash reference/measure-pbrt.sh`): pbrt-v3 (bidirectional path tracing, then path tracing; unbiased "
             "for every path it can sample), the converged photonmap (ours; its kernel bias measured at half the "
             "photons) and POV-Ray's reference preset (one render: no seed noise known). A region is the set of "
             "pixels whose four subpixel rays all hit one shape first; every ratio is to pbrt's region mean, "
             "photonmap's with its 95% interval. Settings: " + (rec["settings"] or "not recorded") + ".", ""]
    lines += report.md_table(
        ["scene", "size", "regions", "all three agree", "POV-Ray off", "photonmap holds (mirror, glass)",
         "undetermined", "photonmap / pbrt where they agree (diffuse)", "POV-Ray / pbrt there"],
        [[x["scene"], x["size"], x["regions"]] + [x["by"].get(c, {}).get("n", 0)
                                                 for c in ("all", "pov_off", "pm_specular", "undetermined")]
         + [span_text(x["agree_pm"]), span_text(x["agree_pov"])] for x in sc])
    lines.append("")
    agree_n = sum(x["agree_n"] for x in sc)
    diffuse_n = sum(x["diffuse_n"] for x in sc)
    pm_all = span([v for x in sc for v in (x["agree_pm"] or ())])
    spec = [(x, x["by"]["pm_specular"]) for x in sc if "pm_specular" in x["by"]]
    spec_n = sum(b["n"] for _, b in spec)
    spec_pm = span([v for _, b in spec for v in (b["pm"] or ())])
    spec_pov = span([v for _, b in spec for v in (b["pov"] or ())])
    pov_ok = [x["scene"] for x in sc if x["by"].get("all") and not x["by"].get("pov_off")]
    pov_off = [x for x in sc if x["by"].get("pov_off")]
    lines.append("Where each is trusted, and why:")
    lines.append("")
    widest = max((x["agree_ci"] for x in sc if isnum(x["agree_ci"])), default=math.nan)
    lines.append(f"- **pbrt-v3 on directly seen diffuse surfaces**: it is unbiased there, and the converged photonmap "
                 f"is consistent with it (pbrt's value inside photonmap's 95% interval, or within 0.5% of it) in "
                 f"{agree_n} of {diffuse_n} diffuse regions, at {span_text(pm_all)} of pbrt. This is a consistency "
                 f"check, not an equivalence with a fixed margin: the intervals' half-widths reach "
                 f"{pct(100 * widest)}% (the widest are those of the smallest regions).")
    if spec:
        lines.append(f"- **The converged photonmap on mirror and glass surfaces** ({spec_n} regions in "
                     f"{count_list([x['scene'] for x, _ in spec])}): what is seen there includes light that reached a "
                     "diffuse surface off a mirror or through glass, seen again via a mirror or glass (light, "
                     "specular, diffuse, specular, eye), a path BDPT cannot sample from a point light and a pinhole "
                     f"camera. photonmap reads {span_text(spec_pm)} of pbrt there, and POV-Ray, whose photons carry "
                     f"those paths, {span_text(spec_pov)}: it sides with photonmap, and pbrt is too dark there.")
    if pov_ok:
        lines.append(f"- **POV-Ray where few bounces carry the light** ({count_list(pov_ok)}): within 2% plus pbrt's "
                     "interval on every diffuse region where pbrt and photonmap agree.")
    for x in pov_off:
        b = x["by"]["pov_off"]
        lines.append(f"- **Not POV-Ray in {x['scene']}**: {b['n']} diffuse regions where pbrt and photonmap agree "
                     f"read {span_text(b['pov'])} of pbrt in POV-Ray. "
                     + POV_OFF_WHY.get(x["scene"], "Why is not measured here.")
                     + " The studies of that scene are judged against the converged photonmap.")
    und = [r for r in rec["rows"] if holds_class(r["holds"]) == "undetermined"]
    if und:
        lines.append("- **Undetermined** (pbrt and photonmap disagree beyond their noise, so neither is shown right): "
                     + "; ".join(f"{r['scene']} {r['region']}, {int(r['pixels'])} pixels: photonmap "
                                 f"{float(r['pm_ratio']):.4f} ± {float(r['pm_ci']):.4f} of pbrt, kernel bias "
                                 f"{fmt(r['pm_bias'])}"
                                 for r in und) + ".")
    corn = next((x for x in sc if x["scene"] == "cornell"), None)
    if corn is not None and corn["agree_pov"] is not None:
        sp = corn["by"].get("pm_specular", {}).get("pov")
        lines.append(f"- **What this says of Table 1's reference** (POV-Ray, cornell): on the diffuse regions it "
                     f"reads {span_text(corn['agree_pov'])} of pbrt (regions where photonmap agrees with pbrt)"
                     + (f", and {span_text(sp)} of pbrt on mirror and glass, where photonmap holds" if sp else "")
                     + f". A reference at q times the truth adds at most (1/q - 1)^2 per pixel to the {primary_name()} "
                     "of a render without bias of its own; with q the regions' means, on those diffuse regions about "
                     f"{fmt(max_bias_term(corn['agree_pov']))} (a render biased itself gains a cross term of either "
                     "sign); finding E sets the reference's error against the cells' margins.")
    lines += ["", "Every region (kernel bias: photonmap's bias as a share of pbrt's mean):", ""]
    lines += report.md_table(
        ["scene", "region", "pixels", "photonmap / pbrt", "kernel bias", "POV-Ray / pbrt", "holds"],
        [[r["scene"], r["region"], int(r["pixels"]), f"{float(r['pm_ratio']):.4f} ± {float(r['pm_ci']):.4f}",
          fmt(r["pm_bias"]) if isnum(r["pm_bias"]) else "-",
          f"{float(r['pov_ratio']):.4f}" if isnum(r["pov_ratio"]) else "-", r["holds"]]
         for r in rec["rows"] if isinstance(r["material_kind"], str)])
    return "The three references side by side", lines


def gather_grid_word(x):
    """Where one grid's equal-error speed-up pays: 'pays at every one of its
    N targets', 'pays at A of N targets (B below 1, the rest undetermined)',
    or 'no target ...'."""
    n = x["targets"]
    if n == 0:
        return "no target that enough resamples reach on both fronts"
    if x["above"] == n:
        return f"pays (its interval wholly above 1) at every one of its {n} targets"
    rest = n - x["above"] - x["below"]
    return (f"pays at {x['above']} of {n} targets, does not (wholly below 1) at {x['below']}"
            + (f", undetermined at {rest}" if rest else ""))


def md_gather(rec):
    """Finding G: final gathering, where the method was designed to pay."""
    gs = rec["grids"]
    every = rec["every"]
    lines = [f"Both methods with final gathering (`make gather`, `results/gather/gather.md`): at each eye path's "
             "first diffuse hit, direct light by a shadow ray, caustics from a caustic map, and N gather rays whose "
             "first diffuse hits read the global map, by the n-nearest estimate (conventional) or the nearest "
             "precomputed representative (precomputed). The equal-error speed-up counts at targets that at least "
             f"{rec['defined_min']:.0%} of the bootstrap resamples reach on both fronts.", ""]
    lines += report.md_table(
        ["scene", "size", "equal-error speed-up at the counted targets", "where it pays", "gather phase speed-up",
         "precompute / time saved (median)", "memory added", "bound (lookups at y free)"],
        [[x["scene"], x["size"], span_text(x["speedup"], "{:.2f}") + "x" if x["speedup"] else "-",
          gather_grid_word(x), ci(*x["gather"]) + "x", f"{pct(100 * x['share'][0])}%", f"{pct(100 * x['memory'])}%",
          f"{fmt(x['bound'])}x"] for x in gs])
    lines += ["", f"- The interval lies above 1 at every counted target in {len(every)} of {len(gs)} grids"
              + (f" ({count_list([x['scene'] + ' at ' + x['size'] for x in every])})" if every else "") + "."]
    gp = span([x["gather"][0] for x in gs])
    bd = span([x["bound"] for x in gs])
    over = [f"{x['scene']} at {x['size']}" for x in gs if x["speedup"] and isnum(x["bound"]) and x["speedup"][1] > x["bound"]]
    lines.append(f"- The gather phase alone runs {span_text(gp, '{:.2f}')}x faster (the geometric mean of each grid's paired ratios); "
                 f"against {published_gather_text()} (quoted below), "
                 f"{gather_phase_intervals(gs)}. The work counters bound the "
                 f"point estimates: with every lookup at y free, a render would run at most {span_text(bd, '{:.2f}')}x faster than "
                 "the conventional one of the same setting (the bound column: the ray casting, shading and caustic "
                 "estimates both methods share stay). Our k-nearest search costs little beside a ray cast, while "
                 "pbrt-v2's naive gather made three k = 50 searches per gather hit, so there the lookups were most of "
                 "the time.")
    if over:
        lines.append(f"- Where the equal-error speed-up exceeds that bound ({count_list(over)}), it compares "
                     "different settings: a cheap setting of the precomputed method reaches the error of a costlier "
                     "conventional one, which no same-setting bound covers. The bound is a least-squares fit over the "
                     "grid's pairs (`results/gather/gather.md` gives its cost per node), not an exact limit.")
    lines.append(f"- Published: {rec['published']}.")
    return "Final gathering: where the method was designed to pay", lines


def published_gather_text():
    """"Christensen's 5-7x and pbrt-v2's 12.7-18.7x" from gather.PUBLISHED_GATHER."""
    from experiments.analysis import gather as study
    return count_list([f"{who} {fmt(lo)}-{fmt(hi)}x" for who, lo, hi in study.PUBLISHED_GATHER])


def gather_phase_intervals(gs):
    """'its 95% interval lies above 1 in K of G grids (...); it contains 5x,
    Christensen's low end, in M of G (undetermined against it) and lies
    below 12.7x, pbrt-v2's low end, in P of G' of the grids GS' gather-phase
    speed-ups (value, lo, hi), against gather.PUBLISHED_GATHER: an interval
    is ranked against a published low end only when it excludes it."""
    from experiments.analysis import gather as study
    n = len(gs)
    above = sum(1 for x in gs if isnum(x["gather"][1]) and x["gather"][1] > 1)
    parts = [f"its 95% interval lies above 1 in {above} of {n} grids"
             + (" (the others contain 1: undetermined)" if above < n else "")]
    ok = [x["gather"] for x in gs if isnum(x["gather"][1]) and isnum(x["gather"][2])]
    for who, lo, _ in study.PUBLISHED_GATHER:
        counts = [("lies below", sum(1 for g in ok if g[2] < lo), ""),
                  ("contains", sum(1 for g in ok if g[1] <= lo <= g[2]), " (undetermined against it)"),
                  ("lies above", sum(1 for g in ok if g[1] > lo), "")]
        said = [(verb, k, tail) for verb, k, tail in counts if k]
        if said:
            (verb, k, tail), rest = said[0], said[1:]
            parts.append(count_list([f"{verb} {fmt(lo)}x, {who} low end, in {k} of {n}{tail}"]
                                    + [f"{v} it in {j}{t}" for v, j, t in rest]))
    return count_list(parts)


def readme_gather(rec):
    """README's bullet on final gathering."""
    gs = rec["grids"]
    every = rec["every"]
    sp = rec["speedup"]
    gp = span([x["gather"][0] for x in gs])
    return (f"- **Final gathering** (Christensen's setting, `make gather`): the precomputed method's equal-error "
            f"speed-up is {span_text(sp, '{:.2f}')}x over the grids' counted targets, its interval above 1 at every "
            f"one of them in {len(every)} of {len(gs)} grids; the gather phase alone runs {span_text(gp, '{:.2f}')}x "
            f"faster at its point estimates; against {published_gather_text()}, {gather_phase_intervals(gs)} "
            "(`results/gather/gather.md`).")


def md_baseline(rec):
    """Finding 8: the baseline and the drift control."""
    return "The baseline, and drift between runs", [
        f"- Drift control (the photon-trace phase, the same code in both methods, paired ratio per cell): "
        f"median {pct(rec['median'])}%, range {pct(rec['min'])}-{pct(rec['max'])}%; its interval excludes 100% in "
        f"{rec['off']} of {rec['cells']} cells"
        + (": there the machine drifted within a pair, and a ratio change there is not attributed to the code."
           if rec["off"] else "."),
        "- The baseline every time ratio divides by is the conventional method on today's kd-tree. The kd-tree "
        "before the kNN work is compared only by its instructions per query (`bench/bench.md`, `make bench`, "
        "column \"before\"); its timings are not repeated."]


def md_scale(rec):
    """Finding P: the largest map of the scaling table and the two-thread speed-ups."""
    lines = []
    for m, r in rec["largest"]:
        lines.append(f"- {m}, n = 100, 512x384, {int(r['threads'])} threads, {int(r['photons_emitted']):,} emitted "
                     f"photons ({int(r['photons_stored']):,} stored): {fmt(r['total_s'])} s in total (trace "
                     f"{fmt(r['trace_s'])}, build {fmt(r['build_s'])}, precompute {fmt(r['precompute_s'])}, eye pass "
                     f"{fmt(r['eye_s'])} s; {timed_text(scaling_repeats(r), each=False)}, `bench/scaling.csv`), peak memory "
                     f"{fmt(r['bytes_per_stored'])} bytes per stored photon (a process of the same render with "
                     "`--repeats 1`: repeats keep the memory they free for the next).")
    b = rec.get("both")
    if b is not None:
        lines.append(f"- At {int(b['photons_emitted']):,} emitted photons the precomputed method's total minus the "
                     f"conventional one's is {fmt(b['precomputed'] - b['conventional'])} s; per phase (precomputed "
                     "minus conventional): " + ", ".join(f"{k} {fmt(v)} s" for k, v in b["phases"].items())
                     + f"; the largest difference is the {b['largest_phase']}.")
    for t in rec["two_threads"]:
        if t["trace_s"] is None:
            continue
        parts = [f"{what} {fmt(x[0])}x [{fmt(x[1])}, {fmt(x[2])}]" if x is not None else ""
                 for x, what in ((t["trace_s"], "photon pass"), (t["build_s"], "kd-tree build"),
                                 (t["total_s"], "total"))]
        pairs = t["total_s"][3] if t["total_s"] is not None else 0
        lines.append(f"- Two threads against one at {int(t['photons']):,} emitted photons (geometric mean of {pairs} "
                     f"back-to-back pairs [95% t interval over the pairs], `bench/threads.csv`): " + ", ".join(parts) + ".")
    return "Performance at scale", lines


def md_stability(rec):
    """Finding 9: what the stability check compares."""
    return "Stability under scale and position", [
        f"- `{rec['file']}` (written by `make stability`) holds each extreme's expected value and "
        "verdict; what it compares is the image mean (and byte identity where stated), not every pixel, so no "
        "per-pixel agreement is claimed here."]


def md_beyond(rec):
    """Finding B: the representative variants at equal error, per case."""
    lines = []
    f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731 (an end at 1.001 must not print as 1)
    margin = stats.EQUIVALENCE_MARGIN
    undefined = [c["case"] for c in rec["cases"] if c["status"] == "undefined"]
    if undefined:
        lines.append(f"- {count_list(undefined)}: " + ("its" if len(undefined) == 1 else "their")
                     + f" speed-ups are taken at a target that fewer than {100 * ee.DEFINED_MIN:.0f}% of the "
                     "bootstrap resamples reach on both fronts: not quoted (`make beyond` again quotes each at the "
                     "tightest target that enough resamples reach).")
    for c in rec["cases"]:
        case = c["case"]
        if c["status"] == "no best":
            vs = "; ".join(f"{VS_LABEL[kind]}: " + vs_variants_text(c, kind, True, ", ", noun=False)
                           for kind in VS_LABEL if c["vs"][kind])
            lines.append(f"- {case}: no best variant: none is ranked faster than every other by the paired tests "
                         "(per seed against the paper's rule and each other, Holm)"
                         + (f"; against the paper's rule (its time over the variant's): {vs}" if vs else "") + ".")
            continue
        if c["status"] == "few seeds":
            lines.append(few_seeds(case, c["seeds"], "make beyond", rec.get("coverage", {}).get(c["seeds"])))
            continue
        if c["status"] == "undefined":
            continue
        p, r = c["paper"], c["best"]
        if c["fragile"]:
            above = (f"above 1.0 only by less than the {fmt(100 * margin)}% margin, for the largest of "
                     f"{c['variants']} variants' point estimates (a selection that favours it), so not established")
        else:
            above = "above 1.0" if c["above"] else "not above 1.0"
        vs = {"higher": "faster", "undetermined": "not ranked", "lower": "slower"}.get(
            r["vs_paper"], "not compared")
        lines.append(f"- {case} ({c['seeds']} seeds, each at its own tightest target): the paper's rule "
                     f"{ci(p['speedup'], p['lo'], p['hi'], f3)}x at relMSE {fmt(p['target'])}; the best variant, "
                     f"{r['variant']}, {ci(r['speedup'], r['lo'], r['hi'], f3)}x at relMSE {fmt(r['target'])}, its "
                     f"interval {above}; against the paper's rule, "
                     f"paired per seed (Holm): {vs}; {fmt(100 * r['fallback_rate'])}% of its eye samples fell back, "
                     f"{pct(100 * r['evaluated_share'])}% of the representatives were evaluated: the goal "
                     + (("holds as worded, by a margin too thin to rely on." if c["fragile"] else "holds.")
                        if c["met"] else "does not hold."))
    if rec["decided"]:
        lines.append("- Against the paper's rule, paired per seed (Holm over each case's variants): "
                     + beyond_vs_text(rec, False) + ".")
        lines.append(f"- The goal (a best variant, its interval above 1.0 and the paired test not ranking it slower "
                     "than the paper's rule) holds in "
                     f"{rec['met']} of {rec['decided']} cases"
                     + (f", {rec['thin']} of them with the interval's lower end within the margin of 1.0"
                        if rec["thin"] else "")
                     + (f" ({rec['no_best']} without a best variant)" if rec["no_best"] else "")
                     + "; `beyond/beyond.md` says for each case that misses it where the time goes "
                     "and where the error lies.")
    return "Beyond the paper's rule", lines


def noise_bullet(rec):
    """[the bullet of where the time noise arises] from reproducibility.csv's
    process columns, or [] when the file has none."""
    med, p90 = rec.get("process_change_median"), rec.get("process_change_p90")
    if med is None or p90 is None:
        return []
    pooled = [f"in {int(rec[f'drift_inside_cells_min{k}'])} "
              + {2: "timed over runs a's and b's processes", 3: "adding the run beside a busy loop"}[k]
              for k in (2, 3) if rec.get(f"drift_inside_cells_min{k}") is not None]
    one = (rec.get("drift_inside_cells_a"), rec.get("drift_inside_cells_b"))
    return [f"- Where the noise arises: the same render's total (the minimum of its repeats in one process) moves by "
            f"a median {report.fmt_fixed(100 * med, 1)}% between two processes, run a's and run b's "
            f"(90th percentile {report.fmt_fixed(100 * p90, 1)}%), so repeats inside one process do not remove it"
            + (f"; the drift control lies inside its window in {int(one[0])} (run a) and {int(one[1])} (run b) of "
               f"{rec['cells']} cells, and with each render's time the minimum over several runs' processes it "
               "would lie inside " + count_list(pooled)
               if pooled and None not in one else "")
            + " (`reproducibility/reproducibility.md`, \"Where the noise arises\")."]


def repro_verdict(rec):
    """'goal met', or 'goal not met (CLAUSES)' naming each clause of the rerun goal
    that record REC misses: the median or largest shift above its goal, cells whose
    intervals are disjoint, cells whose drift control lies outside its window
    (plain 'goal not met' where the record names none of them)."""
    if rec["met"]:
        return "goal met"
    cells, miss = rec.get("cells"), []
    if isnum(rec.get("median_pp")) and isnum(rec.get("goal_pp")) and rec["median_pp"] > rec["goal_pp"]:
        miss.append(f"the median shift is above {fmt(rec['goal_pp'])} pp")
    if isnum(rec.get("max_pp")) and isnum(rec.get("goal_max_pp")) and rec["max_pp"] > rec["goal_max_pp"]:
        miss.append(f"the largest shift is above {fmt(rec['goal_max_pp'])} pp")
    if cells is not None and rec.get("overlap") is not None and rec["overlap"] < cells:
        miss.append(f"the intervals are disjoint in {cells - rec['overlap']} of {cells} cells")
    if (cells is not None and isnum(rec.get("drift_inside_cells")) and isnum(rec.get("drift_lo"))
            and rec["drift_inside_cells"] < cells):
        miss.append(f"the drift control lies outside [{fmt(rec['drift_lo'])}%, {fmt(rec['drift_hi'])}%] in "
                    f"{cells - int(rec['drift_inside_cells'])} of {cells} cells")
    return "goal not met" + (f" ({', and '.join(miss)})" if miss else "")


def md_repro(rec):
    """Finding R: reproducibility between two runs."""
    return "Reproducibility between two runs", [
        f"- {rec.get('design', 'two runs of the grid').capitalize()}: median |difference| of the paired time ratios "
        f"{report.fmt_fixed(rec['median_pp'], 2)} pp (goal {fmt(rec['goal_pp'])} pp), largest "
        f"{report.fmt_fixed(rec['max_pp'], 2)} pp" + (f" (goal {fmt(rec['goal_max_pp'])} pp)" if rec.get("goal_max_pp")
                                                      is not None and isnum(rec["goal_max_pp"]) and
                                                      math.isfinite(rec["goal_max_pp"]) else "")
        + f"; the two runs' intervals overlap in {rec['overlap']} of {rec['cells']} cells"
        + (f"; the drift control (the photon-trace phase's method ratio, the same code in both methods) lies in "
           f"[{fmt(rec['drift_lo'])}%, {fmt(rec['drift_hi'])}%] in {int(rec['drift_inside_cells'])} of "
           f"{rec['cells']} cells (range {report.fmt_fixed(rec['drift_min'], 1)}-"
           f"{report.fmt_fixed(rec['drift_max'], 1)}%)" if rec.get("drift_inside_cells") is not None
           and rec.get("drift_lo") is not None and math.isfinite(rec["drift_lo"]) else "")
        + "; " + repro_verdict(rec) + "."] + noise_bullet(rec) + (
        [f"- Run a against the run beside a busy loop: median |difference| "
         f"{report.fmt_fixed(rec['busy']['median_pp'], 2)} pp (goal {fmt(rec['busy']['goal_pp'])} pp), largest "
         f"{report.fmt_fixed(rec['busy']['max_pp'], 2)} pp; intervals overlap in {rec['busy']['overlap']} of "
         f"{rec['busy']['cells']} cells; goal " + ("met." if rec["busy"]["met"] else "not met.")]
        if rec.get("busy") else [])


def md_rules(rec):
    """Finding S: which representative rule is compatible with the paper's slopes."""
    words = {"incompatible": "incompatible with the paper's slopes",
             "not rejected": "not rejected (compatibility is not shown equality)", "no test": "no test"}
    lines = ["Slope ratios b_prec / b_conv (the renderer's kNN phase timers, t intervals over seeds) against the "
             "paper's (each of its times one noisy measurement, relative sd as our own runs show; "
             "`rep-study/rep-study.md` states the assumption); chi^2 = sum z^2 with one degree of freedom per P_e, "
             "less one for a rule whose parameter was fitted to the paper; Holm over the rules "
             "(`rep-study/rep-study-rules.csv`):", ""]
    lines += report.md_table(["rule", "chi^2", "dof", "p", "p (Holm)", "verdict"],
                             [[x["label"] + (" (fitted)" if x["fitted"] else ""), fmt(x["chi2"]), str(int(x["dof"])),
                               fmt(x["p_value"]), fmt(x["p_holm"]), words.get(x["verdict"], str(x["verdict"]))]
                              for x in rec["rows"]])
    return "Which photons are representatives", lines


def md_metric(rec):
    """Finding M: what NMSE changes against relMSE on the same renders."""
    lines = []
    for e in rec["estimates"]:
        changed = e["changed"]
        lines.append(f"- {e['estimate']} estimate, {e['cells']} cells x methods: Spearman rank correlation of the cells' mean "
                     f"relMSE and mean NMSE {fmt(e['rho'])}; NMSE / relMSE {fmt(e['ratio_min'])}-{fmt(e['ratio_max'])}; "
                     f"the paired verdicts (Holm) differ in {len(changed)} of {e['compared']} cells"
                     + (": " + ", ".join(f"{cell(*k)} {a} -> {b}" for k, a, b in changed) if changed else "") + ".")
    lines.append(f"- The primary error is {metrics.PRIMARY_DEFINITION}; NMSE (mean squared error over the "
                 "reference's mean square, relative at every brightness) is reported beside it.")
    return "The error metric", lines


def md_peers(rec):
    """Finding K: the k-nearest search against FLANN, cKDTree and nanoflann."""
    body = peers_body(rec)
    return "The k-nearest search against the peers", [
        f"- {body[0].upper()}{body[1:]}",
        "- FLANN and nanoflann run from C++, scipy's cKDTree from Python, on the same points and query streams "
        "(experiments/bench/; `make bench-peers` runs this part alone). Before the timed runs our neighbour sets "
        "are checked against brute force on a sample of the queries, and each peer's against ours "
        "(`results/bench/peers.md`)."]


# (number, record, writer, the title said when the record is missing)
FINDINGS = ((1, "table", md_table, "The table's shape"),
            ("T", "precompute", md_precompute, "Where the precomputed method's time goes"),
            ("E", "reference_error", md_reference_error, "Table 1's reference and its own error"),
            ("F", "figure3", md_figure3, "The paper's Figure 3 claim"),
            ("J", "judges", md_judges, "What judges what"),
            ("A", "references", md_references, "The three references side by side"), (2, "equal_error", md_equal_error, "Equal error"),
            (3, "cost", md_cost, "What the speed costs in accuracy"),
            (4, "bias", md_bias, "The estimator's bias in the analytic scene"),
            (5, "caustic", md_caustic, "The caustic window's excess against the whole image's"),
            (6, "scenes", md_scenes, "The scenes' speed-ups, quoted only where enough seeds stand behind an interval"),
            (7, "resolution", md_resolution, "Small images"), (8, "baseline", md_baseline, "The baseline and the drift control"),
            (9, "stability", md_stability, "Stability"), ("P", "scale", md_scale, "Performance at scale"),
            ("B", "beyond", md_beyond, "Beyond the paper's rule"),
            ("R", "repro", md_repro, "Reproducibility between two runs (make reproducibility)"),
            ("S", "rules", md_rules, "Which representative rule is compatible with the paper's slopes"),
            ("M", "metric", md_metric, "The error metric"),
            ("G", "gather", md_gather, "Final gathering: where the method was designed to pay"),
            ("K", "peers", md_peers, "The k-nearest search against the peers"))


# ---- README's summary: one bullet per record, every number read from it
#
# Written into README.md between SUMMARY_BEGIN and SUMMARY_END by
# `make findings`; --check-readme fails when the block there is not the one
# these functions write from the files now (a stale number included). Each
# returns one Markdown bullet from its record or raises Missing.

SUMMARY_BEGIN = "<!-- findings-summary: written by `make findings` from results/ (experiments/analysis/findings.py); " \
                "edits here are overwritten -->"
SUMMARY_END = "<!-- /findings-summary -->"


def primary_name():
    """The primary error's name as the text writes it: 'relMSE', 'NMSE'."""
    return metrics.PRIMARY_DEFINITION.split(" =")[0]


def pct_ci(m, lo, hi):
    """'65.4% [50.8, 84.2]'."""
    return f"{pct(m)}% [{pct(lo)}, {pct(hi)}]"


def k_of(n):
    """'50k' for 50000, else the number."""
    n = int(n)
    return f"{n // 1000}k" if n % 1000 == 0 else str(n)


def count_list(items):
    """'a', 'a and b', 'a, b and c'."""
    items = list(items)
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def readme_table(rec):
    """README's summary bullet on Table 1 from its record REC: the paired time ratio's course over n at
    the smallest P_e beside the paper's, the cells whose interval holds the paper's value, and where ours is
    faster while the paper's method was slower; raises Missing when table1.csv has no precomputed row."""
    phs = rec["photons"]
    if not phs:
        raise Missing("`table1.csv` has no precomputed row (`make reproduce-table`)")
    first = rec["over_n"][phs[0]]
    a, b = first["first"], first["last"]
    per = [f"{k} of {m} cells at P_e = {k_of(ph)}" for ph, (k, m) in rec["inside"].items()]
    paper_falls = sum(1 for ph in phs if rec["over_n"][ph]["last"]["paper"] < rec["over_n"][ph]["first"]["paper"])
    where = "every P_e" if rec["falls"] == len(phs) else f"{rec['falls']} of {len(phs)} photon counts"
    shape = (f"falls over n at {where}"
             + (", as the paper's does" if paper_falls == len(phs) else f" (the paper's at {paper_falls})"))
    level = ("its level reproduces too" if rec["inside_all"] else
             "its level reproduces in part" if rec["inside_any"] else "its level does not reproduce")
    verb = "falls" if first["rank"] == "lower" else "goes"
    if rec["reversed"]:
        rv = rec["reversed"]
        ns = count_list([f"n = {int(r['nn'])}" for r in rv])
        level += (f", and at P_e = {', '.join(sorted({k_of(r['photons']) for r in rv}))} with {ns}, where the "
                  "paper's method was slower than its baseline, ours is faster")
    return (f"- **Table 1: the time ratio {shape}; {level}.** The paired time ratio precomputed / conventional (the "
            f"renderer's own timer, {pairs_text(rec['pairs'])}, 95% t interval) at P_e = {k_of(phs[0])} {verb} from "
            f"{pct_ci(a['ratio'], a['lo'], a['hi'])} at "
            f"n = {int(a['nn'])} to {pct_ci(b['ratio'], b['lo'], b['hi'])} "
            f"at n = {int(b['nn'])} (the paper's {pct(a['paper'])}% and {pct(b['paper'])}%); "
            f"the paper's value lies inside our interval in {', '.join(per)}" + other_inside_text(rec)
            + f"; outside it, ours is the lower in "
            f"{rec['outside_lower']} of {rec['outside']}" + reversal_text(rec) + " (`results/table1/table1.md`).")


def count_word(k):
    """'none' for 0, else the number: a count said in a sentence."""
    return "none" if k == 0 else str(k)


def other_inside_text(rec):
    """'; the corrected estimate's interval holds it in K of the M cells
    (the paper estimate's: J)' where the other estimate's count of cells
    whose interval holds the paper's value differs from the primary one's,
    else ''."""
    o = rec.get("inside_other")
    if o is None:
        return ""
    k = sum(v[0] for v in rec["inside"].values())
    if o[0] == k:
        return ""
    return (f"; the {OTHER_ESTIMATE} estimate's interval holds it in {count_word(o[0])} of the {o[1]} cells (the "
            f"{PRIMARY_ESTIMATE} estimate's: {k})")


def reversal_text(rec):
    """'. One feature does not reproduce: ...' of a table record: the cells
    where the paper's method is slower (its ratio above 100%) and ours is
    faster (our interval wholly below 100%), then those where ours is
    undetermined there (undetermined_text), or '' when there are none."""
    rv = rec["reversed"]
    if not rv:
        ud = undetermined_text(rec)
        return ". A" + ud[3:] if ud else ""
    where = count_list([f"n = {int(r['nn'])}" for r in rv])
    ph = sorted({k_of(r["photons"]) for r in rv})
    return (f". One feature does not reproduce: at P_e = {', '.join(ph)} with {where} the paper's method is slower "
            f"({count_list([pct(r['paper']) + '%' for r in rv])}), ours is faster "
            f"({count_list([pct_ci(r['ratio'], r['lo'], r['hi']) for r in rv])})"
            + undetermined_text(rec) + f"; our interval lies below 100% in {rec['ours_faster']} of {rec['cells']} cells"
            + rerun_text(rec))


def undetermined_text(rec):
    """'; at P_e = .. with n = .. the paper's method is slower (..) and ours is
    undetermined (..., the interval contains 100%)' of a table record, or ''."""
    ud = rec.get("undetermined_vs_slower") or []
    if not ud:
        return ""
    ns = count_list([f"n = {int(r['nn'])}" for r in ud])
    return (f"; at P_e = {', '.join(sorted({k_of(r['photons']) for r in ud}))} with {ns} the paper's method is slower "
            f"({count_list([pct(r['paper']) + '%' for r in ud])}) and ours is undetermined "
            f"({count_list([pct_ci(r['ratio'], r['lo'], r['hi']) for r in ud])}: the interval contains 100%)")


def readme_precompute(rec):
    """README's summary bullet on what may explain Table 1's largest P_e (finding T) from its record
    REC: our precompute's share of the precomputed method's time there beside the paper's as a model puts
    it, with the model's assumption."""
    return (f"- **What may explain P_e = {k_of(rec['top'])} (a model, not a measurement)**: there our precompute takes "
            f"{pct(100 * rec['ours_share'][0])}-{pct(100 * rec['ours_share'][1])}% of the precomputed method's time "
            f"(median {fmt(1e6 * rec['ours_per_rep'])} µs per representative); if the paper's other phases scaled "
            f"like ours, its precompute took {pct(100 * rec['paper_share'][0])}-{pct(100 * rec['paper_share'][1])}% "
            f"of its time, {fmt(1e6 * rec['paper_per_rep_here'])} µs per representative on our machine (its times "
            f"divided by the ratio of the two conventional times, {fmt(rec['machine'])}x; the median over the cells). "
            "The model assumes the "
            "paper's photon pass, build and eye pass stand to its conventional time as ours do, so it puts the whole "
            "gap between the two time ratios in the precompute by construction; the paper's times "
            "are single runs without an interval (`results/table1/runs.csv` and `experiments/paper-table1.csv`; "
            "the model is finding T of `results/FINDINGS.md`).")


VS_ONE = {"higher": "faster", "lower": "slower"}


def vs_one_word(v):
    """'faster', 'slower' or 'undetermined' of an interval's rank against 1."""
    return VS_ONE.get(v, "undetermined")


def readme_equal_error(rec):
    """README's summary bullet on the speed-up at equal error from its record REC: where the primary
    estimate's curve starts, its headline and trend_text; raises Missing when that estimate's fronts share
    no error."""
    r = estimate_of(rec["estimates"], PRIMARY_ESTIMATE)
    t = r["tightest"]
    head = "**The speed-up at equal error is a curve, not a number**" if r["span_rank"] in ("lower", "higher") \
        else "**The speed-up at equal error**"
    beside = ""
    try:
        o = estimate_of(rec["estimates"], OTHER_ESTIMATE)
        if vs_one_word(o["headline_vs_one"]) != vs_one_word(r["headline_vs_one"]):
            beside = (f" (the {OTHER_ESTIMATE} estimate: {headline_text(o['headline'])}, "
                      f"{vs_one_word(o['headline_vs_one'])})")
    except Missing:
        pass
    return (f"- {head} ({PRIMARY_ESTIMATE} estimate; the curve starts at {primary_name()} {fmt(t['target'])}, the "
            f"tightest both fronts reach): {headline_text(r['headline'])}{beside}; {trend_text(r)} "
            "(`results/table1/equal-error.md`).")


def verdict_changes_text(changed, word=None, cells=None):
    """'; the OTHER estimate's verdict differs in (50k, 10) (higher), ...'
    of a changed_verdicts list of cells (with 'k of CELLS cells' when CELLS
    is given), or '' when none differs."""
    if not changed:
        return ""
    word = word or (lambda v: v)
    of = f" {len(changed)} of {cells} cells:" if cells else ""
    return (f"; the {OTHER_ESTIMATE} estimate's verdict differs in{of} " +
            count_list([f"{cell(*k)} ({word(b)})" for k, _, b in changed]))


def within_margin_text(group):
    """' (by less than the 2% margin ...)' for the ranked cells of GROUP whose
    interval lies inside +-delta, '' when none does."""
    inside = [c for c in group if c.get("inside")]
    if not inside:
        return ""
    m = f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}%"
    if len(inside) == len(group):
        return f" ({'each ' if len(group) > 1 else ''}by less than the {m} margin)"
    return f" (by less than the {m} margin at {count_list([cell(c['photons'], c['nn']) for c in inside])})"


def readme_cost(rec):
    """README's summary bullet on what the speed costs from its record REC: the paired verdict on the
    precomputed method's error per cell (Holm over the cells), the largest excess, and the cells where the
    other estimate's verdict differs; raises Missing when table1.csv has no verdicts of the primary estimate."""
    words = {"higher": "higher", "equivalent": f"equivalent within {fmt(100 * stats.EQUIVALENCE_MARGIN)}%",
             "lower": "lower", "undetermined": "undetermined"}
    if PRIMARY_ESTIMATE not in rec["verdicts"]:
        raise Missing(f"`table1.csv` has no {PRIMARY_ESTIMATE}-estimate verdicts (`make reproduce-table`)")
    groups = rec["verdicts"][PRIMARY_ESTIMATE]["groups"]
    parts = [f"{words[v]} in {count_list([cell(c['photons'], c['nn']) for c in groups[v]])}"
             + within_margin_text(groups[v] if v in ("higher", "lower") else [])
             for v in ("higher", "equivalent", "lower", "undetermined") if v in groups]
    worst = ""
    w = rec["worst"]
    if w is not None:
        share = ""
        if w["share_lo"] is not None:
            share = f", {pct(100 * w['share'])}% [{pct(100 * w['share_lo'])}, {pct(100 * w['share_hi'])}] of it bias"
        elif w["share"] is not None and w["share"] < 0:
            share = ", with a negative bias share (the split into bias and variance is not defined there)"
        if w["overlaps"]:
            worst = (f"; the largest point estimate of the excess is at {cell(w['photons'], w['nn'])}: "
                     f"{ci(w['mean'], w['lo'], w['hi'])}{share}, its interval overlapping those of "
                     f"{count_list([cell(*c) for c in w['overlaps']])} (no cell is ranked largest)")
        else:
            worst = (f"; the largest excess is at {cell(w['photons'], w['nn'])}: "
                     f"{ci(w['mean'], w['lo'], w['hi'])}{share}")
    return (f"- **What the speed costs**: per seed, paired ({pairs_text(rec['pairs'])} per cell), Holm over the "
            f"{rec['cells']} cells, the precomputed method's {primary_name()} ({PRIMARY_ESTIMATE} estimate) is "
            + "; ".join(parts) + worst + verdict_changes_text(rec["changed"], lambda v: words.get(v, v), rec["cells"])
            + " (`results/table1/table1.md`).")


def regions_head(runs):
    """The bullet's head of where on the curve of a small image the
    precomputation pays, from its curve_regions list."""
    kinds = {x["class"] for x in runs}
    cr = crossing_of(runs)
    if kinds == {"above"}:
        return "Small images: the precomputation still pays at every target enough resamples reach"
    if kinds == {"below"}:
        return "Small images: the precomputation stops paying at every target enough resamples reach"
    if cr is not None and cr[0] == "up":
        return "Small images: the precomputation pays at the looser targets, not at the tightest"
    if cr is not None:
        return "Small images: the precomputation pays at the tighter targets, not at the looser"
    order = [x["class"] for x in runs]
    if kinds == {"above", "contains"} and order[0] == "contains" and order.count("contains") == 1:
        return ("Small images: the precomputation pays at the looser targets enough resamples reach and is "
                "undetermined at the tightest")
    if kinds == {"above", "contains"} and order[-1] == "contains" and order.count("contains") == 1:
        return ("Small images: the precomputation pays at the tighter targets enough resamples reach and is "
                "undetermined at the loosest")
    if "above" in kinds or "below" in kinds:
        return ("Small images: the precomputation pays at some targets enough resamples reach and is undetermined "
                "at the rest")
    return "Small images: undetermined at every target"


def readme_resolution(rec):
    """README's summary bullet on small images from its record REC: where on the smallest size's
    equal-error curve the precomputation pays, and the speed-up at the largest size's headline target;
    raises Missing with fewer than two sizes, or when the smallest or the largest has no target that enough
    resamples reach on both fronts."""
    sizes = rec["sizes"]
    if len(sizes) < 2:
        raise Missing(f"fewer than two `{rec['dir']}/equal-error-WxH.csv` (`make resolution`)")
    got = []
    for s in (sizes[0], sizes[-1]):
        r = estimate_of(s["estimates"], PRIMARY_ESTIMATE)
        if r["headline"] is None:
            raise Missing(f"`{s['file']}`: at no target do {100 * ee.DEFINED_MIN:.0f}% of the "
                          "resamples reach both fronts (`make resolution` with more seeds)")
        got.append((s["size"], r))
    (s0, ra), (s1, rb) = got
    b = rb["headline"]
    beside = ""
    try:
        o = estimate_of(sizes[0]["estimates"], OTHER_ESTIMATE)
        if regions_head(o["regions"]) != regions_head(ra["regions"]):
            beside = f". The {OTHER_ESTIMATE} estimate differs there: {regions_text(o['regions'])}"
    except Missing:
        pass
    counted = sum(x["count"] for x in ra["regions"])
    rest = ra["curve_targets"] - counted
    rest = (f"; the curve's other {rest} targets, of {ra['curve_targets']}, are reached by too few resamples"
            if rest > 0 else "")
    return (f"- **{regions_head(ra['regions'])}**: at {s0} ({PRIMARY_ESTIMATE} estimate, at the targets that at least "
            f"{100 * ee.DEFINED_MIN:.0f}% of the resamples reach on both fronts), {regions_text(ra['regions'])}{rest}"
            f"{beside}. At {s1}, at the tightest such target ({fmt(b['target'])}), the speed-up is "
            f"{ci(b['speedup'], b['lo'], b['hi'])}x, {vs_one_word(rb['headline_vs_one'])} "
            f"(`results/resolution/equal-error-{s0}.csv` and `equal-error-{s1}.csv`).")


def bias_equivalence_text(rec):
    """The equivalence statement of the corrected estimate against 1, with
    its margin and why that margin."""
    k, m = rec["equivalent"], len(rec["equivalence"])
    return (f"the corrected estimate is equivalent to the exact radiance within {fmt(100 * rec['margin'])}% "
            f"(its whole 95% interval inside 1 ± {fmt(rec['margin'])}; the margin is {BIAS_MARGIN_REASON}) in "
            f"{k} of {m} intervals (both methods, every n)")


def readme_bias(rec):
    """README's summary bullet on the paper's estimator's bias from its record REC: the paper estimate at
    the quoted n against the law n/(n-1), the corrected estimate's equivalence to the exact radiance, and
    the precomputed method's paper estimate where the file has it."""
    at = rec["quoted"]
    return (f"- **The paper's estimator is biased{' by a law' if at['on_law'] else ''}**: "
            f"{fmt(at['mean'], 5)} ± {fmt(at['ci95'], 2)} at n = {int(at['n'])} "
            f"in the analytic scene (conventional method), where n/(n-1) gives {fmt(at['law'], 5)}{law_text(rec)}; "
            f"with `--bias-correction` {bias_equivalence_text(rec)} (`results/estimator-bias/estimator-bias.md`)."
            + (f" {precomputed_bias_text(at)}." if at["precomputed"] else ""))


def law_text(rec):
    """', equivalent to it within 1% (its 95% interval is LO-HI of the law);
    K of the M n where the law differs from 1 by more than twice the margin
    are' of a bias record (', not shown equivalent to it ...' when the
    quoted n's interval reaches beyond the margin)."""
    at, m = rec["quoted"], fmt(100 * rec["margin"])
    iv = f"(its 95% interval is {report.fmt_fixed(at['law_lo'], 4)}-{report.fmt_fixed(at['law_hi'], 4)} of the law)"
    where = (f"; at the {rec['law_rows']} n where the law lies more than {fmt(200 * rec['margin'])}% from 1 (so that "
             f"equivalence to it rules out no bias), {rec['law_equivalent']} are equivalent to it")
    return (f", equivalent to it within {m}% {iv}" if at["on_law"] else
            f", not shown equivalent to it within {m}% {iv}") + where


def readme_rules(rec):
    """README's summary bullet on the representative rules from its record REC: how many of the rules
    the paper's times reject after Holm, and how that count moves with the noise assumed."""
    bad, n = rec["rejected"], len(rec["rows"])
    head = ("**Which photons are representatives is not settled by the paper's times**: no representative rule "
            f"of the {n} is rejected after Holm" if len(bad) == 0 else
            f"**The paper's times reject {len(bad)} of the {n} representative rules** after Holm "
            f"({count_list(bad)})")
    return (f"- {head}, with the paper's times taken as one measurement each, as noisy as our own single runs"
            f"{sensitivity_text(rec)} (`results/rep-study/rep-study-rules.csv`).")


def readme_beyond(rec):
    """README's summary bullet on the variants beyond the paper's rule from its record REC: the paired
    tests of each case's variants against the paper's rule, and the cases where the goal holds; raises
    Missing when no case is quoted."""
    if not rec["decided"]:
        raise Missing(f"`beyond.csv` quotes no case: each at a target that fewer than {100 * ee.DEFINED_MIN:.0f}% "
                      "of the resamples reach on both fronts, or with too few seeds (`make beyond` again)")
    faster, slower, _ = beyond_vs_classes(rec["cases"])
    n = len(rec["cases"])
    head = ("a variant beats the paper's rule in every case" if len(faster) == n else
            "no variant beats the paper's rule" if not faster else
            f"a variant beats the paper's rule in {len(faster)} of {n} cases")
    f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731
    seeds = min(c["seeds"] for c in rec["cases"])
    met = [c for c in rec["cases"] if c["status"] == "quoted" and c["met"]]
    goal = (f"; the goal (a best variant whose equal-error interval lies above 1.0) holds in {rec['met']} of "
            f"{rec['decided']} cases" + (" (" + "; ".join(
                f"{c['case']}'s {c['best']['variant']} {ci(c['best']['speedup'], c['best']['lo'], c['best']['hi'], f3)}x "
                f"at relMSE {fmt(c['best']['target'])}; the paper's rule's interval, "
                f"{ci(c['paper']['speedup'], c['paper']['lo'], c['paper']['hi'], f3)}x at "
                f"{fmt(c['paper']['target'])}, "
                + ("overlaps it: the paired time ratio above, not these, ranks the two"
                   if stats.intervals_overlap((c["paper"]["lo"], c["paper"]["hi"]), (c["best"]["lo"], c["best"]["hi"]))
                   else "is disjoint from it")
                for c in met) + ")" if met else ""))
    return (f"- **Beyond the paper's rule, {head}**: of lazy evaluation, the plane-gated lookup and both together "
            f"(`make beyond`, {seeds} seeds per case, each render time paired per seed with the paper's rule's, "
            f"Holm over each case's variants; the ratio is the paper rule's time over the variant's), "
            + beyond_vs_text(rec, True) + goal + " (`results/beyond/beyond.csv`).")


def readme_repro(rec):
    """README's summary bullet on a rerun from its record REC: in how many cells the two runs' paired
    ratios' intervals overlap, their median and largest shift against the goal, and the same render's
    change between two processes where the file has it."""
    all_in = rec["overlap"] == rec["cells"]
    head = ("A rerun lands inside the first run's intervals, within the goal" if all_in and rec["met"]
            else "A rerun does not land inside the first run's intervals everywhere" if not all_in
            else "A rerun overlaps the first run, but misses the goal")
    return (f"- **{head}**: in {rec.get('design', 'two runs of the grid')}, the paired ratios' intervals overlap in {rec['overlap']} of "
            f"{rec['cells']} cells, with a median shift of the paired ratios of "
            f"{report.fmt_fixed(rec['median_pp'], 2)} pp against the goal of "
            f"{fmt(rec['goal_pp'])}; the largest shift is {report.fmt_fixed(rec['max_pp'], 2)} pp"
            + ("" if rec["met"] else f"; {repro_verdict(rec)}")
            + (f". The same render's time moves by a median {report.fmt_fixed(100 * rec['process_change_median'], 1)}% "
               "between two processes, which repeats inside one process cannot remove"
               if rec.get("process_change_median") is not None else "")
            + " (`results/reproducibility/reproducibility.md`).")


def readme_peers(rec):
    """README's summary bullet on the kd-tree's k nearest against the peers from its record REC
    (peers_body under its head); raises Missing without a tile-order cell."""
    return f"- **The kd-tree's k nearest against the peers**: {peers_body(rec)}"


def peers_body(rec):
    """The peers finding's sentence (README's bullet without its head):
    ours against the strongest peer and nanoflann per k, and what makes the
    comparison unlike; Missing without a tile-order cell."""
    rows = rec["rows"]
    if not rows:
        raise Missing(f"`{rec['file']}` has no tile-order cell (`make bench`)")
    names = dict(bench_report.PEERS)
    ks = [r["k"] for r in rows]
    who = [names[r["strongest"]] for r in rows]
    peer = f"{who[0]} at every k" if len(set(who)) == 1 else ", ".join(f"{w} at k = {k}" for w, k in zip(who, ks))
    def rng(r, key):
        x = r.get(key)
        return f" ({report.fmt_fixed(x[0], 2)}-{report.fmt_fixed(x[1], 2)})" if x else ""
    return (f"on the {k_of(rows[0]['pe'])} map in tile order ours answers "
            f"{count_list([report.fmt_fixed(r['strongest_ratio'], 2) + 'x' + rng(r, 'strongest_range') for r in rows])} "
            "as many queries per second "
            f"as the strongest peer at k = {count_list([str(k) for k in ks])} "
            f"({peer}; the median of one bench's runs, in brackets their range over those runs; nanoflann: "
            f"{count_list([report.fmt_fixed(r['nanoflann_ratio'], 2) + 'x' for r in rows])}), "
            "every neighbour set checked equal; these ratios "
            "move between bench runs on a shared machine. The comparison is not like for like: our search carries "
            "its state from one coherent query to the next and uses AVX2, the peers get neither"
            + (f"; without the carried state ours answers "
               f"{count_list([report.fmt_fixed(r['stateless_ratio'], 2) + 'x' + rng(r, 'stateless_range') for r in rows])} "
               "as many as the "
               "strongest peer" if all("stateless_ratio" in r for r in rows) else
               " (peers.csv has no stateless run of ours to measure what the state is worth)")
            + " (`results/bench/peers.md`).")


def noise_bound_text(ph):
    """'so the other phases' differences of at most X s are not told from
    noise' of a phase-difference dict PH (precomputed minus conventional, s),
    with the photon pass (trace), identical code in both methods, as the
    noise; the phases beyond it are named instead."""
    rest = {k: v for k, v in ph.items() if k not in ("precompute", "trace")}
    big = [k for k, v in rest.items() if abs(v) > abs(ph["trace"])]
    if not big:
        return (f"so the other phases' differences of at most {fmt(max(abs(v) for v in rest.values()))} s are not "
                "told from noise" if rest else "")
    names = {"eye": "eye pass", "build": "kd-tree build"}
    return "and the " + count_list([f"{names.get(k, k)} by {fmt(rest[k])} s" for k in big]) + ", more than that"


def readme_scale(rec):
    """README's summary bullet on performance at scale from its record REC: the conventional method's
    largest map (its time, memory and two-thread speed-ups) and both methods at the largest map they
    share; raises Missing when scaling.csv has no conventional row."""
    r = rec["conventional"]
    if r is None:
        raise Missing("`scaling.csv` has no conventional row (`make bench-scaling`)")
    pairs = (f"{fmt(r['two_total_median'])} s in total (median of {r['two_total_pairs']} pairs; "
             f"{fmt(r['total_s'])} s in the scaling run)"
             if r["two_total_pairs"] else f"{fmt(r['total_s'])} s in total (the scaling run)")
    speed = (f"; two threads against one (geometric mean over {r['trace'][3]} pairs, 95% t interval): photon pass "
             f"{fmt(r['trace'][0])}x [{fmt(r['trace'][1])}, {fmt(r['trace'][2])}], build {fmt(r['build'][0])}x "
             f"[{fmt(r['build'][1])}, {fmt(r['build'][2])}]"
             if r["trace"] is not None and r["build"] is not None else "")
    b = rec["both"]
    methods = ""
    if b is not None:
        ph = b["phases"]
        methods = (f"; in the scaling run at {int(b['photons_emitted']) // 1000000}M the precomputed method took "
                   f"{fmt(b['precomputed'])} s against the conventional {fmt(b['conventional'])} s ({timed_text(b['repeats'])}): "
                   f"of the difference, {fmt(b['precomputed'] - b['conventional'])} s, its precompute is "
                   f"{fmt(b['precompute_s'])} s; the photon pass, the same code in both, differs by "
                   f"{fmt(ph['trace'])} s, " + noise_bound_text(ph)
                   if b["largest_phase"] == "precompute" and "trace" in ph else
                   f"; in the scaling run at {int(b['photons_emitted']) // 1000000}M the precomputed method took "
                   f"{fmt(b['precomputed'])} s against the conventional {fmt(b['conventional'])} s ({timed_text(b['repeats'])}), "
                   f"the largest phase difference in its {b['largest_phase']} ({fmt(ph[b['largest_phase']])} s)")
    return (f"- **At scale**: {int(r['photons_emitted']) // 1000000}M emitted photons ({int(r['photons_stored']):,} "
            f"stored), conventional, n = 100, 512x384, {int(r['threads'])} threads: {pairs}, peak memory "
            f"{fmt(r['bytes_per_stored'])} bytes per stored photon (one render, `--repeats 1`){speed}{methods} (`results/bench/threads.md`, "
            "`results/bench/scaling.md`).")


# ---- FINDINGS.md's opening: one plain sentence per finding, its key
# numbers only (the intervals and the tests are in the bullets after it and
# in the sections), so that the whole reads in two minutes. Each returns one
# Markdown bullet from its record or raises Missing, like the README writers.

def brief_table(rec):
    """FINDINGS.md's opening bullet on Table 1: the ratio's course over n at
    the smallest P_e, worded from its interval test, beside the paper's."""
    first = rec["over_n"][rec["photons"][0]]
    a, b = first["first"], first["last"]
    rv = rec["reversed"]
    ns = count_list(["n = " + str(int(r["nn"])) for r in rv]) if rv else ""
    tail = (f" One feature does not: at P_e = {count_list(sorted({k_of(r['photons']) for r in rv}))} with "
            f"{ns} the paper's method was slower than its "
            f"baseline ({count_list([pct(r['paper']) + '%' for r in rv])}), ours is faster "
            f"({count_list([pct(r['ratio']) + '%' for r in rv])})." if rv else "")
    verb = {"lower": "falls", "higher": "rises"}.get(first["rank"], "goes")
    papers = f"({pct(a['paper'])}% and {pct(b['paper'])}%)"
    paper_falls = b["paper"] < a["paper"]
    if first["rank"] == "lower":
        beside = f"as in the paper {papers}" if paper_falls else f"where the paper's does not fall {papers}"
    else:
        beside = (f"the paper's {'falls' if paper_falls else 'does not fall'} {papers}"
                  + ("" if first["rank"] == "higher" else "; the two ends' intervals overlap: no change is claimed"))
    return (f"- **Table 1.** As n grows from {int(a['nn'])} to {int(b['nn'])} at P_e = {k_of(a['photons'])}, the "
            f"precomputed method's time {verb} from {pct(a['ratio'])}% to {pct(b['ratio'])}% of the conventional "
            f"one's, {beside}.{tail}")


def brief_precompute(rec):
    """FINDINGS.md's opening bullet on where the precomputed method's time goes: our precompute's
    share of that method's time at the largest P_e beside the paper's as a model puts it."""
    return (f"- **A possible reason (a model, not a measurement).** At P_e = {k_of(rec['top'])} our precompute is {pct(100 * rec['ours_share'][0])}-"
            f"{pct(100 * rec['ours_share'][1])}% of the precomputed method's time; a model from the paper's single-run "
            f"times, without intervals and not consistent across its cells, puts the paper's at "
            f"{pct(100 * rec['paper_share'][0])}-{pct(100 * rec['paper_share'][1])}% of its time, by assuming that "
            "the whole gap between the two time ratios is the precompute's.")


def brief_figure3(rec):
    """FINDINGS.md's opening bullet on Figure 3: at how many of its cells the paired errors agree
    with what the paper says, and the verdict at each; raises Missing when table1.csv has none of them."""
    rows = [r for r in rec["rows"] if r["present"] and PRIMARY_ESTIMATE in r]
    if not rows:
        raise Missing("`table1.csv` has none of Figure 3's cells (`make reproduce-table`)")
    agree = sum(r[PRIMARY_ESTIMATE]["word"] == r["said"] for r in rows)
    m = fmt(100 * stats.EQUIVALENCE_MARGIN)
    return (f"- **Figure 3.** The paired errors agree with the paper's reading of its images at {agree} of "
            f"{len(rows)} cells: " + "; ".join(f"{cell(r['photons'], r['nn'])} {r[PRIMARY_ESTIMATE]['word']}"
                                               + (f" within {m}%" if r[PRIMARY_ESTIMATE]["word"] == "alike" else "")
                                               + f" (the paper: {r['said']})" for r in rows) + ".")


def brief_equal_error(rec):
    """FINDINGS.md's opening bullet on the equal-error curve: its smallest
    and largest speed-up over the targets enough resamples reach."""
    r = estimate_of(rec["estimates"], PRIMARY_ESTIMATE)
    if r["span"] is None:
        raise Missing("the equal-error curve has no target that 95% of the resamples reach (`make reproduce-table`)")
    a, b = r["span"]
    trend = ("it depends on the target" if r["span_rank"] in ("lower", "higher") else
             "no trend with the target is claimed")
    return (f"- **Equal error.** Over the targets at least {100 * ee.DEFINED_MIN:.0f}% of the resamples reach, the "
            f"precomputed method's speed-up at equal error runs from {fmt(a['speedup'], 3)}x ({primary_name()} "
            f"{fmt(a['target'])}) to {fmt(b['speedup'], 3)}x ({fmt(b['target'])}): {trend}.")


def brief_cost(rec):
    """FINDINGS.md's opening bullet on the cost in accuracy: in how many cells the precomputed method's
    error is higher, equivalent, lower or undetermined; raises Missing when table1.csv has no verdicts of
    the primary estimate."""
    if PRIMARY_ESTIMATE not in rec["verdicts"]:
        raise Missing(f"`table1.csv` has no {PRIMARY_ESTIMATE}-estimate verdicts (`make reproduce-table`)")
    g = rec["verdicts"][PRIMARY_ESTIMATE]["groups"]
    m = f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}%"

    def part(k, word):
        cs = g.get(k, [])
        small = sum(1 for c in cs if c.get("inside"))
        return (f"{word} in {len(cs)}" + (f" ({'each' if small == len(cs) else small} by less than {m})"
                                          if small and k in ("higher", "lower") else ""))
    parts = [part(k, w) for k, w in (("higher", "higher"), ("equivalent", f"equivalent within {m}"),
                                     ("lower", "lower"), ("undetermined", "undetermined")) if g.get(k)]
    return (f"- **Its cost in accuracy.** Of the {rec['cells']} cells, the precomputed method's error is "
            f"{count_list(parts)}.")


def brief_resolution(rec):
    """FINDINGS.md's opening bullet on small images: at the smallest size, at how many of the
    targets enough resamples reach the precomputation pays, is slower or is undetermined; raises Missing
    with fewer than two sizes, or when the primary estimate's fronts there share no error."""
    sizes = rec["sizes"]
    if len(sizes) < 2:
        raise Missing(f"fewer than two `{rec['dir']}/equal-error-WxH.csv` (`make resolution`)")
    r = estimate_of(sizes[0]["estimates"], PRIMARY_ESTIMATE)
    cnt = {c: sum(x["count"] for x in r["regions"] if x["class"] == c) for c in ("above", "below", "contains")}
    parts = [f"{w} at {cnt[c]}" for c, w in (("above", "pays"), ("below", "is slower"), ("contains", "is undetermined"))
             if cnt[c]]
    return (f"- **Small images.** At {sizes[0]['size']}, of the {sum(cnt.values())} error targets enough resamples "
            f"reach, the precomputation {count_list(parts)}.")


def brief_bias(rec):
    """FINDINGS.md's opening bullet on the paper's estimator's bias: the paper estimate at the quoted n
    against its law (and the precomputed method's where the file has it), and in how many cases the
    corrected estimate is shown equivalent to the exact value."""
    at = rec["quoted"]
    p = at["precomputed"]
    return (f"- **The paper's estimator is biased{' by n/(n-1)' if at['on_law'] else ''}.** In the analytic scene "
            f"the conventional method gives {report.fmt_fixed(at['mean'], 3)} at n = {int(at['n'])} where the law "
            f"gives {report.fmt_fixed(at['law'], 3)}"
            + (f", and the precomputed method {report.fmt_fixed(p['mean'], 3)} (its representatives follow n/(n-2), "
               f"{report.fmt_fixed(p['law'], 3)})" if p else "") + "; "
            f"corrected, both methods are shown equivalent to the exact value within {fmt(100 * rec['margin'])}% "
            f"(the whole 95% interval) in {rec['equivalent']} of {len(rec['equivalence'])} cases"
            + bias_rest_text(rec) + ".")


def bias_rest_text(rec):
    """'; the other 2 are undetermined (their intervals reach past the
    margin)', with the count of corrected intervals wholly outside 1 +-
    margin said apart ('' when every interval is equivalent)."""
    m = rec["margin"]
    rest = [e for e in rec["equivalence"] if not e["equivalent"]]
    off = [e for e in rest if e["mean"] - e["half"] > 1 + m or e["mean"] + e["half"] < 1 - m]
    if not rest:
        return ""
    und = len(rest) - len(off)
    if not off:
        return f"; the other {und} are undetermined (their intervals reach past the margin)"
    if not und:
        return f"; the other {len(off)} {'lies' if len(off) == 1 else 'lie'} wholly outside the margin"
    return (f"; of the other {len(rest)}, {und} are undetermined (their intervals reach past the margin) and "
            f"{len(off)} {'lies' if len(off) == 1 else 'lie'} wholly outside it")


def brief_rules(rec):
    """FINDINGS.md's opening bullet on the representatives: how many of the rules tried the paper's
    times reject, and how that moves with the noise assumed."""
    bad, n = rec["rejected"], len(rec["rows"])
    return ("- **Representatives.** " + (f"The paper's times reject none of the {n} rules we tried for which "
                                         "photons are representatives" if not bad else
                                         f"The paper's times reject {len(bad)} of the {n} rules we tried "
                                         f"({count_list(bad)})")
            + ", with their noise taken as that of our single runs" + sensitivity_text(rec) + ".")


def brief_beyond(rec):
    """FINDINGS.md's opening bullet on the variants beyond the paper's rule: what the paired tests
    against it say over the cases; raises Missing when no case is quoted."""
    if not rec["decided"]:
        raise Missing("`beyond.csv` quotes no case (`make beyond`)")
    return ("- **Beyond the paper's rule.** Of lazy evaluation, the plane-gated lookup and both together, paired "
            "per seed, " + beyond_vs_text(rec, False) + ".")


def brief_gather(rec):
    """FINDINGS.md's opening bullet on final gathering: the span of the
    equal-error point estimates and the grids where every interval lies
    above 1."""
    gs = rec["grids"]
    every = rec["every"]
    sp = rec["speedup"]
    return (f"- **Final gathering** (Christensen's setting). The precomputed method's speed-up at equal error is "
            f"{span_text(sp, '{:.2f}')}x over the grids' counted targets (point estimates); its interval lies above "
            f"1 at every counted target in {len(every)} of {len(gs)} grids.")


def brief_repro(rec):
    """FINDINGS.md's opening bullet on a rerun: the median (and, where the record has its goal, the
    largest) shift of the time ratios against the goal, the verdict naming the clauses missed
    (repro_verdict), and the same render's change between two processes where the file has it."""
    largest = (f" and by at most {report.fmt_fixed(rec['max_pp'], 2)} pp (goal {fmt(rec['goal_max_pp'])} pp)"
               if isnum(rec.get("max_pp")) and isnum(rec.get("goal_max_pp")) else "")
    return (f"- **A rerun.** A second run of Table 1 moves the time ratios by a median "
            f"{report.fmt_fixed(rec['median_pp'], 2)} pp (goal {fmt(rec['goal_pp'])} pp){largest}; {repro_verdict(rec)}"
            + (f"; the same render's time moves by a median "
               f"{report.fmt_fixed(100 * rec['process_change_median'], 1)}% between two processes"
               if rec.get("process_change_median") is not None else "") + ".")


def brief_peers(rec):
    """FINDINGS.md's opening bullet on the k-nearest search: how many times as many queries ours
    answers as the strongest peer, per k; raises Missing without a tile-order cell."""
    rows = rec["rows"]
    if not rows:
        raise Missing(f"`{rec['file']}` has no tile-order cell (`make bench`)")
    names = dict(bench_report.PEERS)
    who = {names[r["strongest"]] for r in rows}
    peer = (f"the strongest peer ({who.pop()})" if len(who) == 1 else
            "the strongest peer (" + ", ".join(f"{names[r['strongest']]} at k = {r['k']}" for r in rows) + ")")
    return (f"- **The k-nearest search.** Ours answers {count_list([report.fmt_fixed(r['strongest_ratio'], 1) + 'x' for r in rows])} "
            f"as many queries as {peer} at k = {count_list([str(r['k']) for r in rows])}, with advantages the "
            "peers lack (state between queries, AVX2).")


def brief_scale(rec):
    """FINDINGS.md's opening bullet on performance at scale: the conventional method's time and
    memory at its largest map, and both methods' totals at the largest map they share; raises Missing
    when scaling.csv has no conventional row."""
    r, b = rec["conventional"], rec["both"]
    if r is None:
        raise Missing("`scaling.csv` has no conventional row (`make bench-scaling`)")
    took = (f"{fmt(r['two_total_median'])} s (median of {r['two_total_pairs']} runs)" if r["two_total_pairs"]
            else f"{fmt(r['total_s'])} s")
    return (f"- **At scale.** {int(r['photons_emitted']) // 1000000}M photons take {took} conventionally on "
            f"{int(r['threads'])} threads, at {fmt(r['bytes_per_stored'])} bytes per stored photon"
            + (f"; in the scaling run the precomputed method took {fmt(b['precomputed'])} s against the "
               f"conventional {fmt(b['conventional'])} s ({timed_text(b['repeats'])}), {fmt(b['precompute_s'])} s "
               "of it its precompute" if b is not None else "") + ".")


BRIEF = {"table": brief_table, "precompute": brief_precompute, "figure3": brief_figure3,
         "equal_error": brief_equal_error, "cost": brief_cost, "resolution": brief_resolution, "bias": brief_bias,
         "rules": brief_rules, "beyond": brief_beyond, "gather": brief_gather, "repro": brief_repro,
         "peers": brief_peers, "scale": brief_scale}


# (record, writer), in the block's order
SUMMARY = (("table", readme_table), ("precompute", readme_precompute), ("figure3", readme_figure3),
           ("equal_error", readme_equal_error), ("cost", readme_cost),
           ("resolution", readme_resolution), ("bias", readme_bias), ("rules", readme_rules),
           ("beyond", readme_beyond), ("gather", readme_gather), ("repro", readme_repro), ("peers", readme_peers),
           ("scale", readme_scale))


def write(rec, writer):
    """WRITER applied to REC; Missing when the record is a Missing."""
    if isinstance(rec, Missing):
        raise rec
    return writer(rec)


def summary(d, recs=None):
    """README's summary block from the records RECS (read from D when not
    given): SUMMARY_BEGIN, which estimate is primary and why, one bullet per
    SUMMARY writer (a missing input is said as such), SUMMARY_END."""
    recs = records(d) if recs is None else recs
    line = renderers(d["root"], os.path.join(d["root"], "regeneration-log.md"))
    out = [SUMMARY_BEGIN, PRIMARY_ESTIMATE_REASON, ""] + ([line, ""] if line else [])
    for name, writer in SUMMARY:
        try:
            out.append(write(recs[name], writer))
        except Missing as e:
            out.append(f"- Not answered here: {e}.")
    return "\n".join(out + [SUMMARY_END])


def readme_block(text):
    """(start, end) of the summary block in README TEXT, markers included,
    or None when either marker is missing."""
    a = text.find(SUMMARY_BEGIN)
    b = text.find(SUMMARY_END, a + 1) if a >= 0 else -1
    return (a, b + len(SUMMARY_END)) if a >= 0 and b >= 0 else None


def paths(root):
    """The results files the findings read, under ROOT."""
    j = os.path.join
    return {"root": root, "table": j(root, "table1", "table1.csv"), "cells": j(root, "table1", "cells.csv"),
            "equal_error": j(root, "table1", "equal-error.csv"),
            "bias": j(root, "estimator-bias", "estimator-bias.csv"), "caustic": j(root, "caustic", "caustic.csv"),
            "scenes": j(root, "scenes", "scenes.csv"), "resolution": j(root, "resolution"), "runs": j(root, "table1", "runs.csv"), "stability": j(root, "stability", "stability-extremes.md"),
            "repro": j(root, "reproducibility", "reproducibility.csv"),
            "table_rerun": j(root, "reproducibility", "table1-b.csv"), "rep": j(root, "rep-study", "rep-study-rules.csv"),
            "scaling": j(root, "bench", "scaling.csv"), "threads": j(root, "bench", "threads.csv"),
            "beyond": j(root, "beyond", "beyond.csv"), "peers": j(root, "bench", "peers.csv"),
            "agreement": os.path.relpath(AGREEMENT_CSV), "gather": j(root, "gather", "gather.csv")}


def renderers(root, link):
    """The sentence that names the renderer each study's files come from,
    linking the log as LINK:
    per target of ROOT/regeneration-log.csv, the pinned renderer of its last
    attempt that ended ok (a later attempt, killed or failed, wrote no
    results file: they are written at the end, through temporary names);
    '' without a log. Studies regenerated at different times (a regeneration
    goes on across machines, one study at a time) may come from different
    renderers; the sentence says which, and names a target with no finished
    attempt."""
    path = os.path.join(root, "regeneration-log.csv")
    if not os.path.exists(path):
        return ""
    log = pd.read_csv(path, dtype=str, keep_default_na=False)
    log = log[log["target"] != "findings"]  # renders nothing: this file and README's summary are its output
    ok = log[log["status"] == "ok"].groupby("target", sort=False).tail(1).set_index("target")
    by = {}
    for target, row in ok.iterrows():
        by.setdefault(row["renderer"][:7], []).append(f"`{target}`")
    unfinished = [f"`{t}`" for t in dict.fromkeys(log["target"]) if t not in ok.index]
    parts = [f"`{r}` made {', '.join(ts)}" for r, ts in by.items()]
    head = (f"Every study's files come from renderer `{next(iter(by))}`" if len(by) == 1 else
            f"The studies come from {len(by)} renderers (a regeneration on a newer one goes on study by study): "
            + "; ".join(parts)) if by else "No study has finished"
    tail = f"; no attempt of {', '.join(unfinished)} has ended ok" if unfinished else ""
    return f"{head}{tail} ([regeneration-log.md]({link}))."


def markdown(d, recs=None):
    """The text of FINDINGS.md from the records RECS (read from D when not given)."""
    recs = records(d) if recs is None else recs
    out = ["# Findings, written by the data", "",
           f"Generated by `make findings` (experiments/analysis/findings.py) from the files under `{d['root']}/` "
           f"on {report.today()}, commit {report.commit()}. Every number below is read from those files; "
           "paired comparisons are worded from their Holm-corrected test (ranked, equivalent within delta = "
           f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional value, or undetermined), unpaired ones "
           f"rank only disjoint 95% intervals. Error: {metrics.PRIMARY_DEFINITION} (experiments/analysis/metrics.py).", ""]
    line = renderers(d["root"], "regeneration-log.md")  # FINDINGS.md lies in the results directory
    out += ([line, ""] if line else []) + opener(recs) + [""]
    figs = recs.get("figures", {})
    for num, name, writer, missing_title in FINDINGS:
        try:
            title, lines = write(recs[name], writer)
        except Missing as e:
            title, lines = missing_title, [f"Not answered here: {e}."]
        pics = [f"![{os.path.basename(f)}]({f})" for f in figs.get(name, [])]
        out += [f'<a id="{anchor(num)}"></a>', "", f"## {num}. {title}", ""] + lines + [""] \
            + ([" ".join(pics), ""] if pics else [])
    return "\n".join(out)


def anchor(num):
    """The HTML anchor of finding NUM: 'finding-1', 'finding-T'."""
    return f"finding-{num}"


def opener(recs):
    """FINDINGS.md's opening: the estimate that is primary and why, one
    plain sentence per finding (BRIEF), then README's summary bullets (the
    same writers, the same records) with their intervals and tests, each
    linked to its finding's section; a bullet whose record is missing is
    left to its section."""
    num_of = {name: num for num, name, _, _ in FINDINGS}
    out = ["## In short", "", PRIMARY_ESTIMATE_REASON, ""]
    for name, _ in SUMMARY:
        try:
            text = write(recs[name], BRIEF[name])
        except Missing:
            continue
        if name in num_of:
            text += f" [Finding {num_of[name]}](#{anchor(num_of[name])})."
        out.append(text)
    out += ["", "## The summary in numbers", "",
            "The same findings with their intervals and tests (README's summary is this list):", ""]
    for name, writer in SUMMARY:
        try:
            text = write(recs[name], writer)
        except Missing:
            continue
        cut = text.rfind(" (`results/")
        if cut > 0 and text.endswith(").") and name in num_of:
            text = text[:cut] + "."
        if name in num_of:
            text += f" [Finding {num_of[name]}](#{anchor(num_of[name])})."
        out.append(text)
    return out


NUMBER = r"(?<![\w.])[0-9]+(?:[.,][0-9]+)*"


def findings_section(readme_text, heading="## What it found, in short"):
    """The text of README's findings section: from HEADING to the next '## '."""
    start = readme_text.find(heading)
    if start < 0:
        return ""
    rest = readme_text[start + len(heading):]
    end = rest.find("\n## ")
    return rest if end < 0 else rest[:end]


def results_text(root):
    """Every Markdown and CSV file under ROOT, concatenated (the haystack the
    README's numbers must be found in)."""
    out = []
    for d, _, files in os.walk(root):
        for f in sorted(files):
            if f.endswith((".md", ".csv")) and f != "README.md":
                with open(os.path.join(d, f), encoding="utf-8", errors="replace") as fh:
                    out.append(fh.read())
    return "\n".join(out)


def unbacked_numbers(section, haystack):
    """The numbers of SECTION (README's findings) that appear in no results
    file as a whole number token (not a digit run inside a longer number;
    thousands separators dropped for the search, '1,800' is found as '1800'); [] when every number is backed."""
    import re
    have = {m.group(0).rstrip(".,") for m in re.finditer(NUMBER, haystack)}
    have |= {t.replace(",", "") for t in have}
    missing = []
    for m in re.finditer(NUMBER, section):
        tok = m.group(0).rstrip(".,")
        if tok not in have and tok.replace(",", "") not in have:
            missing.append(tok)
    return missing


def read_readme(path):
    """(text, (start, end) of its summary block) of the README at PATH; exits 1
    when it cannot be read or lacks either marker."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        report.die(WHERE, f"{path}: {e}")
    at = readme_block(text)
    if at is None:
        report.die(WHERE, f"{path}: no summary block (the lines {SUMMARY_BEGIN} and {SUMMARY_END})")
    return text, at


def committed_results(results, readme):
    """True when RESULTS is the results/ directory beside README (the
    committed results, which README's findings summary is written from)."""
    mine = os.path.join(os.path.dirname(os.path.abspath(readme)), "results")
    return os.path.realpath(results) == os.path.realpath(mine)


def main(argv=None):
    """Entry point; exits 1 when the output cannot be written."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--results", default="results")
    ap.add_argument("--out", help="write FINDINGS.md here")
    ap.add_argument("--write-readme", metavar="README", help="write the summary block of README's findings "
                    "section from the results files (between its markers)")
    ap.add_argument("--check-readme", metavar="README", help="exit 1 when README's summary block is not the one the "
                    "results files give now, or a number of its findings section appears in no results file")
    ap.add_argument("--readme", metavar="README", help="--write-readme then --check-readme README when --results "
                    "is the committed results/ beside README; other results leave README alone")
    for k in ("runs", "table", "cells", "equal_error", "bias", "caustic", "scenes", "stability", "repro", "rep", "beyond"):
        ap.add_argument("--" + k.replace("_", "-"), default=None, help=f"override the {k} file")
    args = ap.parse_args(argv)
    if args.readme and committed_results(args.results, args.readme):
        args.write_readme = args.check_readme = args.readme
    d = paths(args.results)
    for k in d:
        v = getattr(args, k, None)
        if v:
            d[k] = v
    if args.out:
        try:
            report.write_atomic(args.out, markdown(d))
        except OSError as e:
            report.die(WHERE, f"{args.out}: {e}")
        print(f"wrote {args.out}")
    if args.write_readme:
        text, at = read_readme(args.write_readme)
        new = text[:at[0]] + summary(d) + text[at[1]:]
        if new != text:
            try:
                report.write_atomic(args.write_readme, new)
            except OSError as e:
                report.die(WHERE, f"{args.write_readme}: {e}")
            print(f"wrote the findings summary of {args.write_readme}")
    if args.check_readme:
        text, at = read_readme(args.check_readme)
        section = findings_section(text)
        if not section.strip():
            report.die(WHERE, f"{args.check_readme}: no findings section")
        if text[at[0]:at[1]] != summary(d):
            have = text[at[0]:at[1]].splitlines()
            want = summary(d).splitlines()
            first = next((i for i in range(max(len(have), len(want)))
                          if i >= len(have) or i >= len(want) or have[i] != want[i]), 0)
            line = text[:at[0]].count("\n") + 1 + first
            report.die(WHERE, f"{args.check_readme}:{line}: the findings summary is not the one the files under "
                       f"{args.results}/ give now (run `make findings`)")
        # the block's numbers are written from the files; the check covers the rest
        bad = unbacked_numbers(section.replace(text[at[0]:at[1]], ""), results_text(args.results))
        if bad:
            report.die(WHERE, f"{args.check_readme}: numbers of the findings in no file under {args.results}/: "
                       + ", ".join(bad))
        print(f"{args.check_readme}: the findings summary is the one {args.results}/ gives, and every number of "
              f"the findings appears there")


if __name__ == "__main__":
    main()
