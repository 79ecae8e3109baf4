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
A finding whose input file or column is missing says so, with the target
that makes it, instead of a number. The findings are numbered as the
hand-written ones of results/README.md that they replace (1-9), each with
the question the review asked of it.

  python3 -m experiments.analysis.findings --results results --out results/FINDINGS.md
"""

import argparse
import glob
import os

import numpy as np
import pandas as pd
from scipy import stats as sps

from experiments.analysis import equal_error as ee
from experiments.analysis import metrics
from experiments.analysis import report
from experiments.analysis import stats
from experiments.analysis.report import fmt
from experiments.bench import report as bench_report
from experiments.bench import threads

WHERE = "findings.py"
# the smallest number of seeds whose percentile-bootstrap interval a finding
# quotes (with 3 seeds such an interval covers about 90%, not 95%)
MIN_SEEDS_QUOTED = 5


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


def word_rank(a, b, what_a, what_b):
    """A sentence part comparing two unpaired intervals by stats.rank."""
    r = stats.rank(a, b)
    if r == "higher":
        return f"{what_a} is ranked above {what_b} (disjoint 95% intervals)"
    if r == "lower":
        return f"{what_a} is ranked below {what_b} (disjoint 95% intervals)"
    return f"{what_a} against {what_b}: undetermined (the 95% intervals overlap)"


def prec_rows(table):
    """The precomputed rows of a table1.csv."""
    return table[table["method"] != "conventional"]


# ---- the findings: each returns (title, [lines]) or raises Missing

def pairs_text(pairs):
    """'5 pairs', or '3-5 pairs' where the cells differ."""
    lo, hi = int(pairs.min()), int(pairs.max())
    return f"{lo} pairs" if lo == hi else f"{lo}-{hi} pairs"


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


def resolution_files(d):
    """The resolution study's equal-error-WxH.csv files, smallest width first."""
    return sorted(glob.glob(os.path.join(d["resolution"], "equal-error-*.csv")),
                  key=lambda f: int(os.path.basename(f)[len("equal-error-"):-4].split("x")[0]))


def finding1(d):
    """The table's shape: the paired time ratio over n and P_e, and the paper's values."""
    t = load(d["table"], ["photons", "nn", "method", "paper_ratio_percent", "paired_ratio_percent",
                          "paired_ratio_ci95_lo", "paired_ratio_ci95_hi", "pairs"], "make reproduce-table")
    p = prec_rows(t)
    lines = [f"Paired time ratio precomputed / conventional (per-seed log ratios of the renderer's own time, "
             f"95% t interval over {pairs_text(p['pairs'])}), % "
             "(the paper's single measurement in brackets):", ""]
    nns = sorted(p["nn"].unique())
    phs = sorted(p["photons"].unique())
    rows = []
    for n in nns:
        r = [str(int(n))]
        for ph in phs:
            s = p[(p["photons"] == ph) & (p["nn"] == n)]
            if len(s) == 0:
                r.append("n/a")
                continue
            s = s.iloc[0]
            r.append(f"{ci(s['paired_ratio_percent'], s['paired_ratio_ci95_lo'], s['paired_ratio_ci95_hi'], pct)}"
                     f" ({pct(s['paper_ratio_percent'])})")
        rows.append(r)
    lines += report.md_table(["n"] + [f"P_e = {cell(ph, 0)[1:-4]}" for ph in phs], rows)
    lines.append("")

    def iv(s):
        return (s["paired_ratio_ci95_lo"], s["paired_ratio_ci95_hi"])
    for ph in phs:
        s = p[p["photons"] == ph].sort_values("nn")
        if len(s) >= 2:
            lo, hi = s.iloc[0], s.iloc[-1]
            lines.append(f"- Over n at P_e = {int(ph)}: " + word_rank(iv(hi), iv(lo), f"the ratio at n = {int(hi['nn'])}",
                                                                        f"the one at n = {int(lo['nn'])}") + ".")
    for n in nns:
        s = p[p["nn"] == n].sort_values("photons")
        if len(s) >= 2:
            lo, hi = s.iloc[0], s.iloc[-1]
            lines.append(f"- Over P_e at n = {int(n)}: " + word_rank(iv(hi), iv(lo), f"the ratio at P_e = {int(hi['photons'])}",
                                                                       f"the one at P_e = {int(lo['photons'])}") + ".")
    inside = {}
    for ph in phs:
        s = p[(p["photons"] == ph) & np.isfinite(p["paper_ratio_percent"])]
        k = int(((s["paired_ratio_ci95_lo"] <= s["paper_ratio_percent"])
                 & (s["paper_ratio_percent"] <= s["paired_ratio_ci95_hi"])).sum())
        inside[ph] = (k, len(s))
    lines.append("- The paper's value lies inside our interval in " + ", ".join(
        f"{k} of {m} cells at P_e = {int(ph)}" for ph, (k, m) in inside.items()) +
        " (the paper's values are one run each, with no interval: a value outside ours is a difference "
        "only if the paper's own run-to-run spread is smaller than our interval).")
    return "The time ratio over n and P_e, against the paper's", lines


EQUAL_ERROR_COLUMNS = ["estimate", "kind", "target", "speedup", "lo", "hi", "defined_fraction"]


def finding2(d):
    """Equal error: the tightest target both fronts reach, and the curve."""
    e = load(d["equal_error"], EQUAL_ERROR_COLUMNS, "make reproduce-table")
    return "The speed-up at equal error", equal_error_lines(e)


def headline_text(h):
    """'the speed-up is S [lo, hi]x at relMSE T, the tightest target ...' of
    a headline row, or the sentence that there is none."""
    if h is None:
        return f"at no target of the curve do {100 * ee.DEFINED_MIN:.0f}% of the resamples reach both fronts, " \
            "so no speed-up is quoted"
    return f"at {fmt(h['target'])}, the tightest target that at least {100 * ee.DEFINED_MIN:.0f}% of the " \
        f"resamples reach on both fronts, the speed-up is {ci(h['speedup'], h['lo'], h['hi'])}x"


def equal_error_lines(e):
    """One line per estimate of an equal-error CSV (equal_error.py's kinds
    `tightest` and `curve`): where the curve starts, the speed-up at the
    headline target (equal_error.headline) and the range of the curve where
    it is defined."""
    lines = []
    for est, g in e.groupby("estimate", sort=False):
        c = g[g["kind"] == "curve"]
        try:
            t, span = tightest_and_curve(g, est)
        except Missing:
            lines.append(f"- {est} estimate: the two fronts reach no common {metrics.PRIMARY}: no speed-up at equal "
                         "error is defined.")
            continue
        s = f"- {est} estimate: the curve starts at {metrics.PRIMARY} {fmt(t['target'])}, the tightest both fronts " \
            "reach (the larger of the two fronts' smallest errors" \
            + ("; fewer than 95% of the bootstrap resamples reach it on both fronts, so no speed-up is quoted there"
               if t["defined_fraction"] < ee.DEFINED_MIN else "") + f"); {headline_text(headline_of(g, est))}"
        if span is not None:
            a, b = span
            s += f". Over the {len(c)} targets of the curve ({fmt(c['target'].min())} to {fmt(c['target'].max())}), " \
                 f"where at least 95% of the resamples reach the target the speed-up runs from " \
                 f"{ci(a['speedup'], a['lo'], a['hi'])} (at {fmt(a['target'])}) to " \
                 f"{ci(b['speedup'], b['lo'], b['hi'])} (at {fmt(b['target'])}): it depends on the target, " \
                 "and no single target stands for the curve"
        else:
            s += "; at no target of the curve do 95% of the resamples reach it on both fronts, so every interval " \
                 "of the curve is conditional"
        lines.append(s + ".")
    return lines


def finding3(d):
    """What the speed costs in accuracy: paired verdicts, the bias share, n against P_e."""
    t = load(d["table"], ["photons", "nn", "method", "relmse_diff_mean", "relmse_diff_lo", "relmse_diff_hi",
                          "relmse_diff_verdict", "relmse_conv_mean", "relmse_conv_ci95", "pairs"],
             "make reproduce-table")
    cells = load(d["cells"], ["method", "estimate", "photons", "nn", "relmse_ref_mean", "bias_ref"],
                 "make reproduce-table")
    p = prec_rows(t)
    lines = []
    for est in ("paper", "corrected"):
        sfx = "" if est == "paper" else f"_{est}"
        col = f"relmse_diff_verdict{sfx}"
        if col not in p.columns:
            continue
        groups = {}
        for _, r in p.iterrows():
            groups.setdefault(str(r[col]) if isinstance(r[col], str) else "undetermined", []).append(r)
        words = {"higher": "the precomputed method ranked worse (higher error, Holm-corrected p < 0.05)",
                 "lower": "ranked better", "equivalent":
                 f"equivalent within delta = {fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional error",
                 "undetermined": "undetermined"}
        parts = []
        for v in ("higher", "lower", "equivalent", "undetermined"):
            if v in groups:
                parts.append(f"{words[v]} in " + ", ".join(
                    f"{cell(r['photons'], r['nn'])} ({fmt(r[f'relmse_diff_mean{sfx}'])} "
                    f"[{fmt(r[f'relmse_diff_lo{sfx}'])}, {fmt(r[f'relmse_diff_hi{sfx}'])}])" for r in groups[v]))
        lines.append(f"- {est} estimate, paired {metrics.PRIMARY} difference precomputed - conventional per seed "
                     f"({int(p[f'pairs{sfx}'].min())} pairs per cell): " + "; ".join(parts) + ".")
    # bias share of the excess, per cell where the paired test ranks the
    # precomputed method worse (a share of a difference that may be zero is
    # no number)
    worse = set()
    for est in ("paper", "corrected"):
        col = "relmse_diff_verdict" + ("" if est == "paper" else f"_{est}")
        if col in p.columns:
            worse |= {(est, r["photons"], r["nn"]) for _, r in p.iterrows() if r[col] == "higher"}
    shares = []
    for est, g in cells.groupby("estimate", sort=False):
        for (ph, n), h in g.groupby(["photons", "nn"]):
            c = h[h["method"] == "conventional"]
            q = h[h["method"] == "precomputed"]
            if len(c) and len(q) and (est, ph, n) in worse:
                ex, bx = excess_and_bias(q, c)
                if ex > 0:
                    shares.append((est, ph, n, ex, bx, bx / ex))
    if shares:
        for est in dict.fromkeys(s[0] for s in shares):
            sh = [s for s in shares if s[0] == est]
            k = max(sh, key=lambda s: s[3])
            lines.append(f"- {est} estimate: where the paired test ranks the precomputed method's error above the "
                         f"conventional one ({len(sh)} cells), the bias term's share of the excess runs from "
                         f"{pct(100 * min(s[5] for s in sh))}% to {pct(100 * max(s[5] for s in sh))}% (cells.csv "
                         f"bias_ref); at {cell(k[1], k[2])}, the largest excess, {fmt(k[3])} of which {fmt(k[4])} "
                         f"({pct(100 * k[5])}%) is bias.")
    # the difference from the conventional image of the same seed: n against P_e
    conv = p[["photons", "nn", "relmse_conv_mean", "relmse_conv_ci95"]]
    phs = sorted(conv["photons"].unique())
    if len(phs) >= 2:
        parts = []
        for n, g in conv.groupby("nn"):
            a = g[g["photons"] == phs[0]]
            b = g[g["photons"] == phs[-1]]
            if len(a) and len(b):
                a, b = a.iloc[0], b.iloc[0]
                removed = 1 - b["relmse_conv_mean"] / a["relmse_conv_mean"]
                r = stats.rank((b["relmse_conv_mean"] - b["relmse_conv_ci95"], b["relmse_conv_mean"] + b["relmse_conv_ci95"]),
                               (a["relmse_conv_mean"] - a["relmse_conv_ci95"], a["relmse_conv_mean"] + a["relmse_conv_ci95"]))
                parts.append(f"n = {int(n)}: {pct(100 * removed)}% " +
                             ("(disjoint intervals)" if r in ("lower", "higher") else "(intervals overlap: undetermined)"))
        lines.append(f"- The precomputed image's {metrics.PRIMARY} against the conventional image of the same seed: "
                     f"{int(phs[-1] / phs[0])} times the photons ({int(phs[0])} to {int(phs[-1])}) removes "
                     + ", ".join(parts) + " of it: the photon count matters as well as n.")
    return "What the speed costs in accuracy", lines


def finding4(d):
    """The estimator's bias in the analytic scene."""
    b = load(d["bias"], ["n", "law_n_over_n_minus_1", "conventional_paper_mean", "conventional_paper_ci95",
                         "conventional_corrected_mean", "conventional_corrected_ci95", "precomputed_corrected_mean",
                         "precomputed_corrected_ci95", "conventional_paper_seeds"], "make estimator-bias")
    lines = []
    at = b[b["n"] == 10]
    if len(at):
        r = at.iloc[0]
        lines.append(f"- Conventional, paper estimate, at n = 10: {fmt(r['conventional_paper_mean'], 5)} ± "
                     f"{fmt(r['conventional_paper_ci95'], 2)} ({int(r['conventional_paper_seeds'])} seeds); the law "
                     f"n/(n-1) gives {fmt(r['law_n_over_n_minus_1'], 5)}.")
    k_in, k_all, vals = corrected_coverage(b)
    lo = min(vals, key=lambda v: v[0])
    hi = max(vals, key=lambda v: v[0])
    lines.append(f"- With `--bias-correction`, 1 (the exact radiance) lies inside {k_in} of the {k_all} intervals "
                 f"(both methods, every n); the means run from {fmt(lo[0], 5)} ± {fmt(lo[1], 2)} to "
                 f"{fmt(hi[0], 5)} ± {fmt(hi[1], 2)}.")
    return "The paper's estimator is biased by a law", lines


def finding5(d):
    """The caustic window's excess against the whole image's."""
    c = load(d["caustic"], ["estimate", "photons", "nn", "method", "win_excess_mean", "win_excess_ci95",
                            "img_excess_mean", "img_excess_ci95", "seeds"], "make caustic")
    lines = []
    for _, r in c[c["method"] == "precomputed"].iterrows():
        w = (r["win_excess_mean"] - r["win_excess_ci95"], r["win_excess_mean"] + r["win_excess_ci95"])
        i = (r["img_excess_mean"] - r["img_excess_ci95"], r["img_excess_mean"] + r["img_excess_ci95"])
        lines.append(f"- {r['estimate']} {cell(r['photons'], r['nn'])}: excess in the window "
                     f"{fmt(r['win_excess_mean'])} ± {fmt(r['win_excess_ci95'])}, over the image "
                     f"{fmt(r['img_excess_mean'])} ± {fmt(r['img_excess_ci95'])} ({int(r['seeds'])} seeds): "
                     + word_rank(w, i, "the window's", "the image's") + ".")
    lines.append("- Overlap is not equality: the file holds no paired window-minus-image test with a margin, "
                 "so no cell is called equal.")
    return "The caustic window against the whole image", lines


def few_seeds(name, seeds, make):
    """The line that names NAME's intervals as too few-seeded to quote
    (fewer than MIN_SEEDS_QUOTED seeds) and the MAKE command that reruns it."""
    return (f"- {name}: {seeds} seeds: its percentile-bootstrap intervals (which at 3 seeds cover about 90%, not "
            f"95%) are not quoted; rerun `{make} SEEDS={MIN_SEEDS_QUOTED}` or more.")


def finding6(d):
    """The scenes' speed-ups, quoted only where enough seeds stand behind an interval."""
    s = load(d["scenes"], ["scene", "diff_seeds", "ee_paper", "ee_corrected"], "make scenes")
    lines = []
    for _, r in s.iterrows():
        seeds = int(r["diff_seeds"])
        if seeds < MIN_SEEDS_QUOTED:
            lines.append(few_seeds(r["scene"], seeds, "make scenes"))
        else:
            lines.append(f"- {r['scene']} ({seeds} seeds): paper estimate {r['ee_paper']}; corrected {r['ee_corrected']} "
                         "(target: speed-up [95% bootstrap interval]).")
    return "Across scenes", lines


def finding7(d):
    """Small images: the speed-up at equal error per output size."""
    files = resolution_files(d)
    if not files:
        raise Missing(f"no `{os.path.relpath(d['resolution'], d['root'])}/equal-error-WxH.csv` (`make resolution`)")
    lines = []
    for f in files:
        size = os.path.basename(f)[len("equal-error-"):-4]
        e = load(f, EQUAL_ERROR_COLUMNS, "make resolution")
        lines += [f"- {size}:"] + ["  " + x for x in equal_error_lines(e)]
    lines.append("- Each size is judged against its own reference (`resolution/resolution.md` gives each one's "
                 "measured noise and kernel bias).")
    return "The speed-up at equal error per output size", lines


def finding8(d):
    """The baseline and the drift control."""
    t = load(d["table"], ["method", "photons", "nn", "trace_ratio_percent", "trace_ratio_ci95_lo",
                          "trace_ratio_ci95_hi"], "make reproduce-table")
    p = prec_rows(t)
    off = p[(p["trace_ratio_ci95_hi"] < 100) | (p["trace_ratio_ci95_lo"] > 100)]
    lines = [f"- Drift control (the photon-trace phase, the same code in both methods, paired ratio per cell): "
             f"median {pct(p['trace_ratio_percent'].median())}%, range {pct(p['trace_ratio_percent'].min())}-"
             f"{pct(p['trace_ratio_percent'].max())}%; its interval excludes 100% in {len(off)} of {len(p)} cells"
             + (": there the machine drifted within a pair, and a ratio change there is not attributed to the code."
                if len(off) else "."),
             "- The instruction counts and timings of the old finding 8 are in no results file and are not "
             "repeated; `bench/bench.md` (`make bench`) holds what the benchmark measures."]
    return "The baseline, and drift between runs", lines


def finding_scale(d):
    """Performance at scale: the largest map of the scaling table and the two-thread speed-ups."""
    sc = load(d["scaling"], ["method", "photons_emitted", "photons_stored", "threads", "trace_s", "build_s",
                             "precompute_s", "eye_s", "total_s", "bytes_per_stored"], "make bench-scaling")
    lines = []
    for m, g in sc.groupby("method", sort=False):
        r = g.loc[g["photons_emitted"].idxmax()]
        lines.append(f"- {m}, n = 100, 512x384, {int(r['threads'])} threads, {int(r['photons_emitted']):,} emitted "
                     f"photons ({int(r['photons_stored']):,} stored): {fmt(r['total_s'])} s in total (trace "
                     f"{fmt(r['trace_s'])}, build {fmt(r['build_s'])}, precompute {fmt(r['precompute_s'])}, eye pass "
                     f"{fmt(r['eye_s'])} s; one render, `bench/scaling.csv`), peak memory "
                     f"{fmt(r['bytes_per_stored'])} bytes per stored photon.")
    th = load(d["threads"], ["photons_emitted", "pair", "threads", "trace_s", "build_s", "total_s"],
              "make bench-threads")
    for ph, g in th.groupby("photons_emitted"):
        parts = []
        for col, what in (("trace_s", "photon pass"), ("build_s", "kd-tree build"), ("total_s", "total")):
            x = threads.speedups(g, col)
            parts.append(f"{what} {fmt(np.median(x))}x [{fmt(x.min())}, {fmt(x.max())}]" if len(x) else "")
        if not parts[0]:
            continue
        lines.append(f"- Two threads against one at {int(ph):,} emitted photons (median of {len(x)} back-to-back "
                     f"pairs [smallest, largest], `bench/threads.csv`): " + ", ".join(parts) + ".")
    return "Performance at scale", lines


def finding9(d):
    """Stability: what the check compares."""
    path = d["stability"]
    if not os.path.isfile(path):
        raise Missing(f"`{path}` is missing (`make stability`)")
    return "Stability under scale and position", [
        f"- `{os.path.relpath(path, d['root'])}` (written by `make stability`) holds each extreme's expected value and "
        "verdict; what it compares is the image mean (and byte identity where stated), not every pixel, so no "
        "per-pixel agreement is claimed here."]


def finding_beyond(d):
    """Beyond the paper's rule: the representative variants at equal error, per case (make beyond)."""
    b = load(d["beyond"], ["case", "variant", "estimate", "target", "speedup", "lo", "hi", "defined_fraction",
                           "fallback_rate", "evaluated_share", "seeds", "best", "above_one", "vs_paper", "goal_met"],
             "make beyond")
    b = b[b["estimate"] == "paper"]
    lines = []
    met = total = thin = 0
    for case, g in b.groupby("case", sort=False):
        seeds = int(g["seeds"].min())
        paper = g[g["variant"] == "paper"]
        best = g[g["best"].astype(bool)]
        if paper.empty or best.empty:
            lines.append(f"- {case}: no best variant: none is ranked faster than every other by the paired tests "
                         "(per seed against the paper's rule and each other, Holm).")
            continue
        p, r = paper.iloc[0], best.iloc[0]
        if seeds < MIN_SEEDS_QUOTED:
            lines.append(few_seeds(case, seeds, "make beyond"))
            continue
        if min(float(p["defined_fraction"]), float(r["defined_fraction"])) < ee.DEFINED_MIN:
            lines.append(f"- {case}: its speed-ups are taken at a target that fewer than {100 * ee.DEFINED_MIN:.0f}% "
                         "of the bootstrap resamples reach on both fronts: not quoted (`make beyond` again quotes "
                         "each at the tightest target that enough resamples reach).")
            continue
        f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731 (an end at 1.001 must not print as 1)
        margin = stats.EQUIVALENCE_MARGIN
        fragile = bool(r["above_one"]) and float(r["lo"]) < 1.0 + margin
        if fragile:
            above = (f"above 1.0 only by less than the {fmt(100 * margin)}% margin, for the largest of "
                     f"{len(g) - 1} variants' point estimates (a selection that favours it), so not established")
        else:
            above = "above 1.0" if bool(r["above_one"]) else "not above 1.0"
        vs = {"higher": "faster", "undetermined": "not ranked", "lower": "slower"}.get(
            r["vs_paper"], "not compared")
        lines.append(f"- {case} (relMSE {fmt(r['target'])}, {seeds} seeds): the paper's rule "
                     f"{ci(p['speedup'], p['lo'], p['hi'], f3)}x; the best variant, {r['variant']}, "
                     f"{ci(r['speedup'], r['lo'], r['hi'], f3)}x, its interval {above}; against the paper's rule, "
                     f"paired per seed (Holm): {vs}; {fmt(100 * r['fallback_rate'])}% of its eye samples fell back, "
                     f"{pct(100 * r['evaluated_share'])}% of the representatives were evaluated: the goal "
                     + (("holds as worded, by a margin too thin to rely on." if fragile else "holds.")
                        if bool(r["goal_met"]) else "does not hold."))
        total += 1
        met += bool(r["goal_met"])
        thin += bool(r["goal_met"]) and fragile
    if total:
        lines.append(f"- The goal (the best variant's interval above 1.0 and the paired test not ranking it slower "
                     "than the paper's rule) holds in "
                     f"{met} of {total} cases"
                     + (f", {thin} of them with the interval's lower end within the margin of 1.0" if thin else "")
                     + "; `beyond/beyond.md` says for each case that misses it where the time goes "
                     "and where the error lies.")
    return "Beyond the paper's rule", lines


def finding_repro(d):
    """Reproducibility between two runs (make reproducibility)."""
    r = load(d["repro"], ["summary_ratio_median_abs_delta_pp", "summary_ratio_overlap_cells", "summary_cells",
                          "summary_goal_pp", "summary_met"], "make reproducibility")
    s = r.iloc[0]
    return "Reproducibility between two runs", [
        f"- Two interleaved runs of the grid: median |difference| of the paired time ratios "
        f"{report.fmt_fixed(s['summary_ratio_median_abs_delta_pp'], 2)} pp (goal {fmt(s['summary_goal_pp'])} pp); the "
        f"two runs' intervals overlap in {int(s['summary_ratio_overlap_cells'])} of {int(s['summary_cells'])} cells; "
        "goal " + ("met." if bool(s["summary_met"]) else "not met.")]


def finding_rules(d):
    """Which representative rule is compatible with the paper's slopes: the
    tests repstudy.py made (chi^2 per rule with the degrees of freedom it
    has left, Holm over the rules), read from rep-study-rules.csv."""
    r = load(d["rep"], ["rule", "label", "fitted", "chi2", "dof", "p_value", "p_holm", "verdict"], "make rep-study")
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
                              for _, x in r.iterrows()])
    return "Which photons are representatives", lines


def finding_metric(d):
    """The error metric: what NMSE changes against relMSE (metrics.PRIMARY)
    on the same renders: the cells' order and the paired verdicts."""
    r = load(d["runs"], ["role", "status", "method", "estimate", "photons", "nn", "seed", "relmse_ref", "nmse_ref"],
             "make reproduce-table")
    r = r[(r["role"] == "grid") & (r["status"] == "ok")]
    lines = []
    for est, g in r.groupby("estimate", sort=False):
        means = g.groupby(["method", "photons", "nn"])[["relmse_ref", "nmse_ref"]].mean()
        rho = sps.spearmanr(means["relmse_ref"], means["nmse_ref"]).statistic
        verdicts = {}
        for col in ("relmse_ref", "nmse_ref"):
            comps, keys = [], []
            for (ph, n), h in g.groupby(["photons", "nn"]):
                a = h[h["method"] == "precomputed"].set_index("seed")[col]
                b = h[h["method"] == "conventional"].set_index("seed")[col]
                seeds = sorted(set(a.index) & set(b.index))
                if seeds:
                    comps.append(stats.paired_difference(a.loc[seeds].to_numpy(), b.loc[seeds].to_numpy()))
                    keys.append(cell(ph, n))
            verdicts[col] = dict(zip(keys, (c["verdict"] for c in stats.compare_family(comps))))
        changed = [k for k in verdicts["relmse_ref"] if verdicts["relmse_ref"][k] != verdicts["nmse_ref"].get(k)]
        ratio = (means["nmse_ref"] / means["relmse_ref"]).to_numpy(np.float64)
        lines.append(f"- {est} estimate, {len(means)} cells x methods: Spearman rank correlation of the cells' mean "
                     f"relMSE and mean NMSE {fmt(rho)}; NMSE / relMSE {fmt(np.min(ratio))}-{fmt(np.max(ratio))}; "
                     f"the paired verdicts (Holm) differ in {len(changed)} of {len(verdicts['relmse_ref'])} cells"
                     + (": " + ", ".join(f"{k} {verdicts['relmse_ref'][k]} -> {verdicts['nmse_ref'][k]}" for k in changed)
                        if changed else "") + ".")
    lines.append(f"- The primary error is {metrics.PRIMARY_DEFINITION}; NMSE (mean squared error over the "
                 "reference's mean square, relative at every brightness) is reported beside it.")
    return "The error metric", lines


FINDINGS = ((1, finding1), (2, finding2), (3, finding3), (4, finding4), (5, finding5), (6, finding6),
            (7, finding7), (8, finding8), (9, finding9), ("P", finding_scale), ("B", finding_beyond), ("R", finding_repro), ("S", finding_rules), ("M", finding_metric))


# ---- README's summary: one bullet per finding, every number read here
#
# Written into README.md between SUMMARY_BEGIN and SUMMARY_END by
# `make findings`; --check-readme fails when the block there is not the one
# these functions write from the files now (a stale number included). Each
# returns one Markdown bullet or raises Missing.

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


def summary_table(d):
    t = load(d["table"], ["photons", "nn", "method", "paper_ratio_percent", "paired_ratio_percent",
                          "paired_ratio_ci95_lo", "paired_ratio_ci95_hi", "pairs"], "make reproduce-table")
    p = prec_rows(t)
    phs = sorted(p["photons"].unique())

    def iv(r):
        return (r["paired_ratio_ci95_lo"], r["paired_ratio_ci95_hi"])
    falls = 0
    for ph in phs:
        s = p[p["photons"] == ph].sort_values("nn")
        falls += stats.rank(iv(s.iloc[-1]), iv(s.iloc[0])) == "lower"
    s = p[p["photons"] == phs[0]].sort_values("nn")
    a, b = s.iloc[0], s.iloc[-1]
    known = p[np.isfinite(p["paper_ratio_percent"])]
    inside = (known["paired_ratio_ci95_lo"] <= known["paper_ratio_percent"]) & \
             (known["paper_ratio_percent"] <= known["paired_ratio_ci95_hi"])
    per = []
    for ph in phs:
        m = known["photons"] == ph
        per.append(f"{int(inside[m].sum())} of {int(m.sum())} cells at P_e = {k_of(ph)}")
    out = known[~inside]
    lower = int((out["paired_ratio_ci95_hi"] < out["paper_ratio_percent"]).sum())
    shape = "reproduces" if falls == len(phs) else f"holds at {falls} of {len(phs)} photon counts"
    level = "its level too" if inside.all() else ("its level in part" if inside.any() else "its level does not")
    verb = "falls" if stats.rank(iv(b), iv(a)) == "lower" else "goes"
    return (f"- **The shape of Table 1 {shape}; {level}.** The paired time ratio precomputed / conventional (the "
            f"renderer's own timer, {pairs_text(p['pairs'])}, 95% t interval) at P_e = {k_of(phs[0])} {verb} from "
            f"{pct_ci(a['paired_ratio_percent'], a['paired_ratio_ci95_lo'], a['paired_ratio_ci95_hi'])} at "
            f"n = {int(a['nn'])} to {pct_ci(b['paired_ratio_percent'], b['paired_ratio_ci95_lo'], b['paired_ratio_ci95_hi'])} "
            f"at n = {int(b['nn'])} (the paper's {pct(a['paper_ratio_percent'])}% and {pct(b['paper_ratio_percent'])}%); "
            f"the paper's value lies inside our interval in {', '.join(per)}; outside it, ours is the lower in "
            f"{lower} of {len(out)} (`results/table1/table1.md`).")


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


def summary_equal_error(d):
    e = load(d["equal_error"], EQUAL_ERROR_COLUMNS, "make reproduce-table")
    t, span = tightest_and_curve(e, "paper")
    curve = span is not None and \
        stats.rank((span[0]["lo"], span[0]["hi"]), (span[1]["lo"], span[1]["hi"])) == "lower"
    head = "**The speed-up at equal error is a curve, not a number**" if curve else \
        "**The speed-up at equal error**"
    rest = (f"; where 95% of the resamples reach both fronts it runs from {fmt(span[0]['speedup'])} to "
            f"{fmt(span[1]['speedup'])} with the target" if span is not None else
            "; at no target do 95% of the resamples reach both fronts")
    if span is not None and not curve:
        rest += " (the two ends' 95% intervals overlap, so no trend with the target is claimed)"
    return (f"- {head} (paper estimate; the curve starts at {primary_name()} {fmt(t['target'])}, the tightest both "
            f"fronts reach): {headline_text(headline_of(e, 'paper'))}{rest} (`results/table1/equal-error.md`).")


def summary_cost(d):
    t = load(d["table"], ["photons", "nn", "method", "relmse_diff_mean", "relmse_diff_lo", "relmse_diff_hi",
                          "relmse_diff_verdict", "pairs"], "make reproduce-table")
    cells = load(d["cells"], ["method", "estimate", "photons", "nn", "relmse_ref_mean", "bias_ref"],
                 "make reproduce-table")
    p = prec_rows(t)
    words = {"higher": "higher", "equivalent": f"equivalent within {fmt(100 * stats.EQUIVALENCE_MARGIN)}%",
             "lower": "lower", "undetermined": "undetermined"}
    parts = []
    for v in ("higher", "equivalent", "lower", "undetermined"):
        g = p[p["relmse_diff_verdict"].fillna("undetermined") == v]
        if len(g):
            parts.append(f"{words[v]} in {count_list([cell(r['photons'], r['nn']) for _, r in g.iterrows()])}")
    worst = ""
    hi = p[p["relmse_diff_verdict"] == "higher"]
    if len(hi):
        r = hi.loc[hi["relmse_diff_mean"].idxmax()]
        c = cells[(cells["estimate"] == "paper") & (cells["photons"] == r["photons"]) & (cells["nn"] == r["nn"])]
        q, v = c[c["method"] == "precomputed"], c[c["method"] == "conventional"]
        share = ""
        if len(q) and len(v):
            ex, bx = excess_and_bias(q, v)
            if ex > 0:
                share = f", {pct(100 * bx / ex)}% of it bias"
        worst = (f"; the largest excess is at {cell(r['photons'], r['nn'])}: "
                 f"{ci(r['relmse_diff_mean'], r['relmse_diff_lo'], r['relmse_diff_hi'])}{share}")
    return (f"- **What the speed costs**: per seed, paired ({pairs_text(p['pairs'])} per cell), Holm over the "
            f"{len(p)} cells, the precomputed method's {primary_name()} (paper estimate) is "
            + "; ".join(parts) + worst + " (`results/table1/table1.md`).")


def summary_resolution(d):
    files = resolution_files(d)
    if len(files) < 2:
        raise Missing(f"fewer than two `{os.path.relpath(d['resolution'], d['root'])}/equal-error-WxH.csv` "
                      "(`make resolution`)")
    est = "corrected"
    got = []
    for f in (files[0], files[-1]):
        e = load(f, EQUAL_ERROR_COLUMNS, "make resolution")
        tightest_and_curve(e, est)
        h = headline_of(e, est)
        if h is None:
            raise Missing(f"`{os.path.relpath(f, d['root'])}`: at no target do {100 * ee.DEFINED_MIN:.0f}% of the "
                          "resamples reach both fronts (`make resolution` with more seeds)")
        got.append((os.path.basename(f)[len("equal-error-"):-4], h))
    (s0, a), (s1, b) = got
    small = stats.rank((a["lo"], a["hi"]), (1.0, 1.0))
    head = {"lower": "Small images: the precomputation stops paying",
            "higher": "Small images: the precomputation still pays"}.get(small, "Small images: undetermined")
    said = {"lower": ", slower", "higher": ", faster"}.get(small, " (its interval contains 1)")
    return (f"- **{head}**: at {s0} and the tightest target that {100 * ee.DEFINED_MIN:.0f}% of the resamples "
            f"reach on both fronts ({primary_name()} {fmt(a['target'])}, {est} estimate) the precomputed method's "
            f"speed-up is {ci(a['speedup'], a['lo'], a['hi'])}x{said}; at {s1} (its own such target, "
            f"{fmt(b['target'])}) it is {ci(b['speedup'], b['lo'], b['hi'])}x (`results/resolution/resolution.md`).")


def summary_bias(d):
    b = load(d["bias"], ["n", "law_n_over_n_minus_1", "conventional_paper_mean", "conventional_paper_ci95",
                         "conventional_corrected_mean", "conventional_corrected_ci95", "precomputed_corrected_mean",
                         "precomputed_corrected_ci95"], "make estimator-bias")
    at = (b[b["n"] == 10] if (b["n"] == 10).any() else b[b["n"] == b["n"].min()]).iloc[0]
    k_in, k_all, _ = corrected_coverage(b)
    law = at["law_n_over_n_minus_1"]
    on_law = abs(at["conventional_paper_mean"] - law) <= at["conventional_paper_ci95"]
    fix = ("removes it for both methods" if k_in == k_all else f"leaves 1 inside {k_in} of {k_all} intervals")
    return (f"- **The paper's estimator is biased{' by a law' if on_law else ''}**: "
            f"{fmt(at['conventional_paper_mean'], 5)} ± {fmt(at['conventional_paper_ci95'], 2)} at n = {int(at['n'])} "
            f"in the analytic scene, where n/(n-1) gives {fmt(law, 5)}, and `--bias-correction` {fix} "
            f"(1 inside {k_in} of {k_all} intervals; `results/estimator-bias/estimator-bias.md`).")


def summary_rules(d):
    r = load(d["rep"], ["rule", "label", "verdict"], "make rep-study")
    bad = r[r["verdict"] == "incompatible"]
    head = ("**Which photons are representatives is not settled by the paper's times**: no representative rule "
            f"of the {len(r)} is rejected after Holm" if len(bad) == 0 else
            f"**The paper's times reject {len(bad)} of the {len(r)} representative rules** after Holm "
            f"({count_list(list(bad['label']))})")
    return (f"- {head}, with the paper's times taken as one measurement each, as noisy as our own single runs "
            "(`results/rep-study/rep-study.md`, which also gives the verdicts at half and twice that noise).")


def summary_beyond(d):
    b = load(d["beyond"], ["case", "variant", "estimate", "speedup", "lo", "hi", "defined_fraction", "seeds", "best",
                           "above_one", "goal_met"], "make beyond")
    b = b[(b["estimate"] == "paper") & b["best"].astype(bool)]
    if len(b) == 0:
        raise Missing("`beyond.csv` has no best variant (`make beyond`)")
    b = b[b["defined_fraction"].astype(float) >= ee.DEFINED_MIN]
    if len(b) == 0:
        raise Missing(f"`beyond.csv` quotes every best variant at a target that fewer than {100 * ee.DEFINED_MIN:.0f}% "
                      "of the resamples reach on both fronts (`make beyond` again)")
    margin = stats.EQUIVALENCE_MARGIN
    met = b[b["goal_met"].astype(bool)]
    thin = met[met["lo"] < 1.0 + margin]
    f3 = lambda x: report.fmt_fixed(x, 3)  # noqa: E731
    hi, lo = b.loc[b["speedup"].idxmax()], b.loc[b["speedup"].idxmin()]
    return (f"- **Beyond the paper's rule the variants {'hold everywhere' if len(met) == len(b) else 'do not yet hold everywhere'}**: "
            f"of lazy evaluation, the plane-gated lookup and both together (`make beyond`, {int(b['seeds'].min())} "
            f"seeds per case, each against the conventional renders of the same seeds), the best variant's interval "
            f"lies above 1.0 in {len(met)} of {len(b)} cases"
            + (f", {len(thin)} of them with its lower end within the {fmt(100 * margin)}% margin of 1.0" if len(thin) else "")
            + f"; the largest is {hi['case']}'s {ci(hi['speedup'], hi['lo'], hi['hi'], f3)}x, the smallest "
            f"{lo['case']}'s {ci(lo['speedup'], lo['lo'], lo['hi'], f3)}x (`results/beyond/beyond.md`).")


def summary_repro(d):
    r = load(d["repro"], ["summary_ratio_median_abs_delta_pp", "summary_ratio_max_abs_delta_pp",
                          "summary_ratio_overlap_cells", "summary_cells", "summary_goal_pp", "summary_met"],
             "make reproducibility")
    s = r.iloc[0]
    all_in = int(s["summary_ratio_overlap_cells"]) == int(s["summary_cells"])
    head = ("A rerun lands inside the first run's intervals, within the goal" if all_in and bool(s["summary_met"])
            else "A rerun does not land inside the first run's intervals everywhere" if not all_in
            else "A rerun overlaps the first run, but beyond the goal")
    return (f"- **{head}**: two interleaved runs of the grid overlap in {int(s['summary_ratio_overlap_cells'])} of "
            f"{int(s['summary_cells'])} cells, with a median shift of the paired ratios of "
            f"{report.fmt_fixed(s['summary_ratio_median_abs_delta_pp'], 2)} pp against the goal of "
            f"{fmt(s['summary_goal_pp'])}; the largest shift is {report.fmt_fixed(s['summary_ratio_max_abs_delta_pp'], 2)} pp "
            "(`results/reproducibility/reproducibility.md`).")


def summary_peers(d):
    f = load(d["peers"], ["who", "order", "pe", "stored", "k", "queries", "rep", "seconds"], "make bench")
    got = {}
    for order, pe, _, k, _, med in bench_report.peer_medians(f):
        if order == "tiles":
            got[int(k)] = (pe, med)
    if not got:
        raise Missing(f"`{d['peers']}` has no tile-order cell (`make bench`)")
    names = dict(bench_report.PEERS)
    ks = sorted(got)
    ratio, nano, who = [], [], []
    for k in ks:
        med = got[k][1]
        best = bench_report.strongest_peer(med)
        ratio.append(f"{report.fmt_fixed(med[best] / med['ours'], 2)}x")
        nano.append(f"{report.fmt_fixed(med['nanoflann'] / med['ours'], 2)}x")
        who.append(names[best])
    peer = f"{who[0]} at every k" if len(set(who)) == 1 else ", ".join(f"{w} at k = {k}" for w, k in zip(who, ks))
    pe = got[ks[0]][0]
    return (f"- **The kd-tree's k nearest against the peers**: on the {k_of(pe)} map in tile order ours answers "
            f"{count_list(ratio)} as many queries per second as the strongest peer at k = {count_list([str(k) for k in ks])} "
            f"({peer}; nanoflann: {count_list(nano)}), every neighbour set checked equal; these ratios "
            "move between bench runs on a shared machine (`results/bench/bench.md`).")


def summary_scale(d):
    sc = load(d["scaling"], ["method", "photons_emitted", "photons_stored", "threads", "total_s", "bytes_per_stored"],
              "make bench-scaling")
    th = load(d["threads"], ["photons_emitted", "pair", "threads", "trace_s", "build_s", "total_s"],
              "make bench-threads")
    c = sc[sc["method"] == "conventional"]
    if len(c) == 0:
        raise Missing("`scaling.csv` has no conventional row (`make bench-scaling`)")
    r = c.loc[c["photons_emitted"].idxmax()]
    g = th[th["photons_emitted"] == r["photons_emitted"]]
    two = g[g["threads"] == 2]["total_s"]
    tr, bu = threads.speedups(g, "trace_s"), threads.speedups(g, "build_s")
    pairs = (f"{fmt(np.median(two))} s in total (median of {len(two)} pairs; {fmt(r['total_s'])} s in the scaling run)"
             if len(two) else f"{fmt(r['total_s'])} s in total (the scaling run)")
    speed = (f"; two threads against one: photon pass {fmt(np.median(tr))}x, build {fmt(np.median(bu))}x"
             if len(tr) and len(bu) else "")
    return (f"- **At scale**: {int(r['photons_emitted']) // 1000000}M emitted photons ({int(r['photons_stored']):,} "
            f"stored), conventional, n = 100, 512x384, {int(r['threads'])} threads: {pairs}, peak memory "
            f"{fmt(r['bytes_per_stored'])} bytes per stored photon{speed} (`results/bench/threads.md`, "
            "`results/bench/scaling.md`).")


SUMMARY = (summary_table, summary_equal_error, summary_cost, summary_resolution, summary_bias, summary_rules,
           summary_beyond, summary_repro, summary_peers, summary_scale)


def summary(d):
    """README's summary block: SUMMARY_BEGIN, one bullet per SUMMARY
    function (a missing input is said as such), SUMMARY_END."""
    out = [SUMMARY_BEGIN]
    for fn in SUMMARY:
        try:
            out.append(fn(d))
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
            "repro": j(root, "reproducibility", "reproducibility.csv"), "rep": j(root, "rep-study", "rep-study-rules.csv"),
            "scaling": j(root, "bench", "scaling.csv"), "threads": j(root, "bench", "threads.csv"),
            "beyond": j(root, "beyond", "beyond.csv"), "peers": j(root, "bench", "bench-peers.csv")}


def markdown(d):
    """The text of FINDINGS.md."""
    out = ["# Findings, written by the data", "",
           f"Generated by `make findings` (experiments/analysis/findings.py) from the files under `{d['root']}/` "
           f"on {report.today()}, commit {report.commit()}. Every number below is read from those files; "
           "paired comparisons are worded from their Holm-corrected test (ranked, equivalent within delta = "
           f"{fmt(100 * stats.EQUIVALENCE_MARGIN)}% of the conventional value, or undetermined), unpaired ones "
           f"rank only disjoint 95% intervals. Error: {metrics.PRIMARY_DEFINITION} (experiments/analysis/metrics.py).", ""]
    for num, fn in FINDINGS:
        try:
            title, lines = fn(d)
        except Missing as e:
            title, lines = fn.__doc__.split(":")[0].split(".")[0], [f"Not answered here: {e}."]
        out += [f"## {num}. {title}", ""] + lines + [""]
    return "\n".join(out)


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
