#!/usr/bin/python3
"""beyond.py: the representative variants at equal error (`make beyond`) ->
STEM.md, STEM.csv and a figure.

Owns the comparison of the paper's representative rule with the variants
beyond it (lazy evaluation, the gated lookup, both) on every case (a scene at
a size): per (case, variant) the equal-error speed-up over the conventional
method at its headline target (equal_error.headline: the tightest relMSE
target of the curve that at least 95% of the bootstrap resamples reach on
both fronts), with its bootstrap interval (equal_error.analyse, one call per
variant's runs.csv), the fallback
rate (rep_fallbacks / eye samples, pooled over the variant's renders), the
share of the representatives evaluated (reps_evaluated / representatives,
pooled), where the time goes (median over renders of the precompute and the
eye pass as shares of the total, and their median seconds) and how much
error the representatives add (the variant's mean relMSE over the
conventional one's, cell by cell at the same seeds) and where it lies (the
share of the per-pixel excess relMSE on the pixels near an edge of the
reference, edge_mask). Variants against each other are paired
(paired_tests): the renders of one (cell, seed) of a case ran back to back
in one group, so per seed each variant's time (summed over the grid's
cells) is compared with the paper's rule's as a log ratio (t interval, t
test) and its relMSE (mean over the cells) as a difference, Holm over the
family of variants of the case; settings whose images are bit-identical
(relMSE and work counters equal on every cell and seed) are one row. A
variant is "best" only
when the paired tests rank it above every other (the paper's rule
included): faster after Holm and its error not ranked higher. Per case the
verdict of the goal: the best variant's equal-error interval lies above 1.0
and the paired test does not rank it below the paper's rule. A variant
whose grid renders are missing is refused (exit 1): a
half-run study never reads as a result. Per case the reference's own
error (reference.py): its noise and kernel bias from the JSON beside its
EXR (ref_noise, ref_bias in STEM.csv, on every row of the case; empty when
it has none, as a POV-Ray reference: not measured, and no number stands in
for it) and reference.describe's sentence in STEM.md's References,
checked against the case's tightest equal-error target (the smallest
`tightest` target of its variants' curves). Every number in STEM.md is
written here from the runs CSVs, the stats JSONs they name and the
references' JSONs.
"""

import argparse
import json
import math
import os
import zlib

import numpy as np
import pandas as pd

from experiments.analysis import equal_error
from experiments.analysis import metrics
from experiments.analysis import plotting
from experiments.analysis import reference
from experiments.analysis import report
from experiments.analysis import stats
from experiments.analysis.plotting import plt
from experiments.analysis.report import fmt

WHERE = "beyond.py"
# where the error lies: a pixel is "near an edge" when it is within
# EDGE_RADIUS pixels (a square) of a pixel whose reference luminance differs
# from a 4-neighbour's by more than EDGE_STEP of (the larger of the two +
# EDGE_OFFSET): the reference's geometric edges and shadow boundaries alike
# (the renderer writes no depth or normal image to tell them apart)
EDGE_RADIUS = 2
EDGE_STEP = 0.25
EDGE_OFFSET = 0.1
NEED = ["role", "status", "estimate", "method", "photons", "nn", "seed", "relmse_ref", "precompute_s",
        "render_s", "total_s", "cpu_s", "run", "size", "loadavg_1min"]
COLUMNS = ["case", "scene", "size", "variant", "args", "estimate", "target", "speedup", "lo", "hi",
           "defined_fraction", "fallback_rate", "evaluated_share", "precompute_share", "render_share",
           "conv_render_share", "photons_med_s", "precompute_med_s", "render_med_s", "error_ratio", "excess_relmse", "edge_pixels",
           "excess_edge_share", "renders", "seeds", "image_group", "pair_seeds", "vs_paper_ratio", "vs_paper_ratio_lo",
           "vs_paper_ratio_hi", "vs_paper_p_holm", "vs_paper_relmse_diff", "vs_paper_relmse_verdict", "best",
           "above_one", "vs_paper", "goal_met", "ref_noise", "ref_bias"]
ALPHA = 0.05  # the family-wise level of the paired tests (Holm)


def read_stats(run):
    """The stats JSON of the render whose path stem is RUN; exits 1 when it
    is missing or not JSON."""
    path = run + ".stats.json"
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        report.die(WHERE, f"{path}: {e}")
    return None


def counters(ok):
    """(fallback rate, evaluated share) pooled over the precomputed renders
    OK (rows of runs.csv): sum rep_fallbacks / sum samples and sum
    reps_evaluated / sum representatives; nan where a key is absent or a
    denominator is 0."""
    sums = {"rep_fallbacks": 0.0, "samples": 0.0, "reps_evaluated": 0.0, "representatives": 0.0}
    for run in ok["run"]:
        js = read_stats(run)
        for k in sums:
            v = js.get(k)
            sums[k] = sums[k] + float(v) if report.isnum(v) and report.isnum(sums[k]) else math.nan
    fb = sums["rep_fallbacks"] / sums["samples"] if sums["samples"] > 0 else math.nan
    ev = sums["reps_evaluated"] / sums["representatives"] if sums["representatives"] > 0 else math.nan
    return fb, ev


def error_ratio(runs, estimate):
    """Mean over the cells of (mean relMSE of the precomputed renders) /
    (mean relMSE of the conventional renders of the same cell and seeds):
    the error the representatives add at equal settings; nan without a
    common cell."""
    sel = runs[(runs["status"] == "ok") & (runs["estimate"] == estimate)]
    pre = sel[(sel["method"] == "precomputed") & (sel["role"] == "grid")]
    conv = sel[sel["method"] == "conventional"]
    m = pre.merge(conv, on=["photons", "nn", "seed"], suffixes=("", "_c"))
    m = m[np.isfinite(m["relmse_ref"].astype(float)) & np.isfinite(m["relmse_ref_c"].astype(float))]
    if m.empty:
        return math.nan
    g = m.groupby(["photons", "nn"])[["relmse_ref", "relmse_ref_c"]].mean()
    return float((g["relmse_ref"] / g["relmse_ref_c"]).mean())


def photon_pass(ok):
    """The photon pass with the kd-tree build of each render: the minimum over
    its repeats of their sum (runs.csv's trace_build_s); a runs.csv without
    it (one timed run each): total minus precompute and eye pass."""
    if "trace_build_s" in ok:
        return ok["trace_build_s"].astype(float)
    return ok["total_s"].astype(float) - ok["precompute_s"].astype(float) - ok["render_s"].astype(float)


def share(frame, col):
    """Median over FRAME's renders of COL / total_s (nan when empty)."""
    t = frame["total_s"].astype(float)
    v = frame[col].astype(float) / t.where(t > 0)
    v = v[np.isfinite(v)]
    return float(np.median(v)) if len(v) else math.nan


def edge_mask(ref, radius=EDGE_RADIUS, step=EDGE_STEP, offset=EDGE_OFFSET):
    """The (H, W) boolean mask of the pixels near an edge of the reference
    REF (H, W, 3): within RADIUS pixels (a square) of a pixel whose
    luminance differs from its right or lower neighbour's by more than STEP
    of (the larger of the two + OFFSET); both pixels of such a step are edge
    pixels."""
    lum = plotting.luminance(ref)
    edge = np.zeros(lum.shape, dtype=bool)
    for a, b in ((lum[:, :-1], lum[:, 1:]), (lum[:-1, :], lum[1:, :])):
        e = np.abs(a - b) > step * (np.maximum(a, b) + offset)
        if a.shape[1] < lum.shape[1]:
            edge[:, :-1] |= e
            edge[:, 1:] |= e
        else:
            edge[:-1, :] |= e
            edge[1:, :] |= e
    near = np.zeros_like(edge)
    h, w = edge.shape
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            near[max(0, dy):h + min(0, dy), max(0, dx):w + min(0, dx)] |= \
                edge[max(0, -dy):h + min(0, -dy), max(0, -dx):w + min(0, -dx)]
    return near


def error_map(img, ref):
    """The per-pixel relMSE terms of IMG against REF, mean over the channels
    (H, W): their mean over the pixels is metrics.relmse."""
    return np.mean(np.square(img - ref) * metrics.rel_weight(ref), axis=2)


def error_location(excess, mask):
    """(mean excess, edge pixel share, edge share of the excess) of the
    per-pixel excess error EXCESS (H, W; the variant's relMSE term minus the
    conventional one's, summed over the pairs and divided by their number)
    and the edge MASK: the mean of EXCESS over all pixels, the fraction of
    pixels in MASK, and sum(EXCESS in MASK) / sum(EXCESS), nan when the
    summed excess is not positive (no excess to place)."""
    total = float(np.sum(excess))
    share = float(np.sum(excess[mask])) / total if total > 0 else math.nan
    return float(np.mean(excess)), float(np.mean(mask)), share


def excess_of(runs, estimate, ref_path):
    """error_location of the variant's renders in RUNS (role grid,
    precomputed, status ok, ESTIMATE) against the conventional renders of
    the same (P_e, n, seed), pooled over every such pair, with the edge mask
    of the reference at REF_PATH; (nan, nan, nan) without a pair or without
    a reference. Exits 1 when an image cannot be read or its size differs
    from the reference."""
    if not ref_path:
        return math.nan, math.nan, math.nan
    sel = runs[(runs["status"] == "ok") & (runs["estimate"] == estimate)]
    pre = sel[(sel["method"] == "precomputed") & (sel["role"] == "grid")]
    conv = sel[sel["method"] == "conventional"]
    m = pre.merge(conv, on=["photons", "nn", "seed"], suffixes=("", "_c"))
    if m.empty:
        return math.nan, math.nan, math.nan
    try:
        ref = metrics.read_exr(ref_path)
        acc = np.zeros(ref.shape[:2])
        for run, run_c in zip(m["run"], m["run_c"]):
            x, c = metrics.read_exr(run + ".exr"), metrics.read_exr(run_c + ".exr")
            if x.shape != ref.shape or c.shape != ref.shape:
                raise ValueError(f"{run}.exr or {run_c}.exr: not the size of {ref_path}")
            acc += error_map(x, ref) - error_map(c, ref)
    except ValueError as e:
        report.die(WHERE, str(e))
    return error_location(acc / len(m), edge_mask(ref))


def median_of(frame, col):
    """Median of FRAME[COL] over its finite values (nan when none)."""
    v = frame[col].astype(float)
    v = v[np.isfinite(v)]
    return float(np.median(v)) if len(v) else math.nan


def measure(case, scene, size, variant, args, runs_csv, time_col, rng, replicates, ref=""):
    """The rows (one per estimate) of one variant of one case (REF: the
    case's reference EXR, for where the error lies). Exits 1 when the CSV
    lacks a column, or when any of the variant's grid renders is missing (a
    study not finished) or none rendered."""
    runs = report.read_csv(runs_csv, NEED, WHERE, hint="make beyond renders and collects it")
    grid = runs[(runs["role"] == "grid") & (runs["method"] == "precomputed")]
    if grid.empty:
        report.die(WHERE, f"{runs_csv}: {case} {variant}: no precomputed render in the grid")
    missing = grid[grid["status"] == "missing"]
    if len(missing):
        report.die(WHERE, f"{runs_csv}: {case} {variant}: {len(missing)} of {len(grid)} renders missing "
                   f"(e.g. {missing['run'].iloc[0]}): run make beyond again")
    conv = runs[(runs["method"] == "conventional") & (runs["status"] == "missing")]
    if len(conv):
        report.die(WHERE, f"{runs_csv}: {case} {variant}: {len(conv)} conventional renders missing")
    out = []
    for est in dict.fromkeys(grid["estimate"]):
        ok = grid[(grid["status"] == "ok") & (grid["estimate"] == est)]
        res = equal_error.analyse(runs, est, time_col, "auto", rng, replicates)
        tight = res.get("headline") or {}
        tightest = (res.get("tightest") or {}).get("target", math.nan)
        fb, ev = counters(ok) if len(ok) else (math.nan, math.nan)
        conv_ok = runs[(runs["method"] == "conventional") & (runs["status"] == "ok") & (runs["estimate"] == est)]
        excess, edge_px, edge_share = excess_of(runs, est, ref)
        out.append({"case": case, "scene": scene, "size": size, "variant": variant, "args": args, "estimate": est,
                    "target": tight.get("target", math.nan), "speedup": tight.get("speedup", math.nan),
                    "lo": tight.get("lo", math.nan), "hi": tight.get("hi", math.nan),
                    "defined_fraction": tight.get("defined_fraction", math.nan),
                    "fallback_rate": fb, "evaluated_share": ev,
                    "precompute_share": share(ok, "precompute_s"), "render_share": share(ok, "render_s"),
                    "conv_render_share": share(conv_ok, "render_s"),
                    "photons_med_s": median_of(ok.assign(rest=photon_pass(ok)), "rest"),
                    "precompute_med_s": median_of(ok, "precompute_s"), "render_med_s": median_of(ok, "render_s"),
                    "error_ratio": error_ratio(runs, est), "excess_relmse": excess, "edge_pixels": edge_px,
                    "excess_edge_share": edge_share, "renders": int(len(ok)), "seeds": int(ok["seed"].nunique()),
                    "load": runs["loadavg_1min"].astype(float).median(), "tightest": tightest})
    return out


def work_of(row):
    """The work counters of the render ROW (its stats JSON's "work", as
    sorted JSON text), or None when the runs.csv names no stats file or the
    stats have none."""
    if "run" not in row or not isinstance(row["run"], str) or not os.path.isfile(row["run"] + ".stats.json"):
        return None
    w = read_stats(row["run"]).get("work")
    return None if w is None else json.dumps(w, sort_keys=True)


def seed_cells(runs, estimate, time_col):
    """{(photons, nn, seed): (time, relMSE, work)} of the ok precomputed grid
    renders of ESTIMATE in RUNS (one variant's runs.csv)."""
    sel = runs[(runs["status"] == "ok") & (runs["estimate"] == estimate) & (runs["method"] == "precomputed")
               & (runs["role"] == "grid")]
    return {(int(r["photons"]), int(r["nn"]), int(r["seed"])): (float(r[time_col]), float(r["relmse_ref"]), work_of(r))
            for _, r in sel.iterrows()}


def identical_images(a, b):
    """True when the cells A and B (seed_cells) hold the same renders, every
    render's relMSE is exactly equal (bit-identical images: the runs record
    no image hash, equal relMSE on every cell and seed stands for it) and so
    are its work counters where the stats have them (the same computation:
    a variant that reaches the same image with other work, e.g. lazy
    evaluation, is not one of them)."""
    return bool(a) and set(a) == set(b) and all(a[k][1:] == b[k][1:] for k in a)


def paired_seeds(a, b):
    """(times A, times B, errors A, errors B): per seed both rendered (in
    seed order), the time summed and the relMSE averaged over the cells
    both rendered ok at that seed."""
    seeds = sorted({k[2] for k in set(a) & set(b)})
    out = ([], [], [], [])
    for s in seeds:
        keys = [k for k in set(a) & set(b) if k[2] == s]
        out[0].append(sum(a[k][0] for k in keys))
        out[1].append(sum(b[k][0] for k in keys))
        out[2].append(float(np.mean([a[k][1] for k in keys])))
        out[3].append(float(np.mean([b[k][1] for k in keys])))
    return tuple(np.array(x, dtype=np.float64) for x in out)


def compare(a, b):
    """The paired comparison of cells A against B (seed_cells): ratio (B's
    time / A's, the speed-up of A over B: exp of the mean per-seed log
    ratio) with its t interval, the t test's p of the mean log ratio, and
    stats.paired_difference of the relMSE (A - B)."""
    ta, tb, ea, eb = paired_seeds(a, b)
    ratio, lo, hi, n = stats.paired_log_ratio(tb, ta)
    ok = (ta > 0) & (tb > 0)
    p = stats.paired_difference(np.log(tb[ok]), np.log(ta[ok]))["p"] if ok.sum() else math.nan
    return {"ratio": ratio, "lo": lo, "hi": hi, "pairs": n, "p": p, "err": stats.paired_difference(ea, eb)}


def time_verdicts(comparisons, alpha=ALPHA):
    """Holm over the time tests of COMPARISONS (compare dicts): adds p_holm
    and verdict "higher" (faster), "lower" (slower), "undetermined" or
    "unknown" (no test) to each."""
    for c, q in zip(comparisons, stats.holm([c["p"] for c in comparisons])):
        c["p_holm"] = float(q)
        c["verdict"] = ("unknown" if not np.isfinite(q) else
                        ("higher" if c["ratio"] > 1 else "lower") if q < alpha else "undetermined")
    stats.compare_family([c["err"] for c in comparisons], alpha)
    return comparisons


def paired_tests(frames, estimate, time_col, alpha=ALPHA):
    """The paired tests of one case and estimate. FRAMES: {variant name:
    its runs.csv} in the order given, the paper's rule's ("paper") among
    them. Returns {name: columns}: image_group (the first variant, in that
    order, whose images are bit-identical to this one's: the row it is
    reported in), pair_seeds, vs_paper_ratio (_lo, _hi: the paper's rule's
    time / this variant's, paired per seed, t interval), vs_paper_p_holm
    and vs_paper (its Holm-corrected verdict over the family of variants:
    higher = faster), vs_paper_relmse_diff and vs_paper_relmse_verdict (the
    paired relMSE difference, stats.compare_family over the family), best
    (the variant with the largest vs_paper_ratio, when the paired tests
    against every other image group, the paper's rule's included, Holm over
    those, rank it faster and none ranks its error higher)."""
    cells = {n: seed_cells(f, estimate, time_col) for n, f in frames.items()}
    group = {}
    for n in cells:
        group[n] = next((r for r in group.values() if r == group.get(r) and identical_images(cells[n], cells[r])), n)
    out = {n: {"image_group": group[n], "pair_seeds": 0, "vs_paper_ratio": math.nan, "vs_paper_ratio_lo": math.nan,
               "vs_paper_ratio_hi": math.nan, "vs_paper_p_holm": math.nan, "vs_paper": "",
               "vs_paper_relmse_diff": math.nan, "vs_paper_relmse_verdict": "", "best": False} for n in cells}
    if "paper" not in cells:
        return out
    reps = [n for n in cells if group[n] == n]
    family = [n for n in reps if n != group["paper"]]
    comps = time_verdicts([compare(cells[n], cells[group["paper"]]) for n in family], alpha)
    for n, c in zip(family, comps):
        out[n].update(pair_seeds=c["pairs"], vs_paper_ratio=c["ratio"], vs_paper_ratio_lo=c["lo"],
                      vs_paper_ratio_hi=c["hi"], vs_paper_p_holm=c["p_holm"], vs_paper=c["verdict"],
                      vs_paper_relmse_diff=c["err"]["mean"], vs_paper_relmse_verdict=c["err"]["verdict"])
    finite = [n for n in family if np.isfinite(out[n]["vs_paper_ratio"])]
    if finite:
        cand = max(finite, key=lambda n: out[n]["vs_paper_ratio"])
        against = time_verdicts([compare(cells[cand], cells[r]) for r in reps if r != cand], alpha)
        out[cand]["best"] = bool(against) and all(c["verdict"] == "higher" and c["err"]["verdict"] != "higher"
                                                  for c in against)
    for n in cells:  # a bit-identical variant is reported in its group's row
        if group[n] != n:
            out[n].update({k: v for k, v in out[group[n]].items() if k != "image_group"}, best=False)
    return out


def add_paired(table, frames, time_col):
    """TABLE with the columns of paired_tests per (case, estimate); FRAMES:
    {case: {variant: runs.csv frame}}."""
    cols = {}
    for (cid, est), _g in table.groupby(["case", "estimate"], sort=False):
        for name, c in paired_tests(frames[cid], est, time_col).items():
            cols[(cid, est, name)] = c
    keys = list(zip(table["case"], table["estimate"], table["variant"]))
    for col in ("image_group", "pair_seeds", "vs_paper_ratio", "vs_paper_ratio_lo", "vs_paper_ratio_hi",
                "vs_paper_p_holm", "vs_paper", "vs_paper_relmse_diff", "vs_paper_relmse_verdict", "best"):
        table[col] = [cols[k][col] if k in cols else (False if col == "best" else "") for k in keys]
    return table


def verdicts(table):
    """Fill above_one and goal_met per row (best, vs_paper: paired_tests):
    above_one: the equal-error interval's lower end > 1; goal_met: the best
    variant's above_one, and the paired test does not rank it below the
    paper's rule. Returns TABLE."""
    table["above_one"] = [bool(report.isnum(x) and x > 1.0) for x in table["lo"]]
    table["goal_met"] = [bool(b and a and v != "lower") for b, a, v in
                         zip(table["best"], table["above_one"], table["vs_paper"])]
    return table


def case_references(table, cases):
    """{case: {"ref", "ref_noise", "ref_bias", "tightest", "sentence"}}:
    per case of CASES {id: (scene, size, REF)} the reference's noise and
    bias in relMSE (reference.measured: nan when not measured), the case's
    tightest equal-error target (the smallest finite `tightest` of its rows
    in TABLE; None when there is none) and reference.describe's sentence
    checked against it. Exits 2 (bad input) naming a reference's JSON that
    is not JSON or lacks the numbers."""
    out = {}
    for cid, (_scene, _size, ref) in cases.items():
        t = table.loc[table["case"] == cid, "tightest"] if "tightest" in table else pd.Series([], dtype=float)
        t = t.astype(float)[np.isfinite(t.astype(float))]
        tightest = float(t.min()) if len(t) else None
        try:
            _info, noise, bias = reference.measured(ref)
        except ValueError as e:
            report.die(WHERE, str(e), report.EXIT_BAD_INPUT)
        # nan, not None: the sentence then says that there is no target to check it against
        sentence = (reference.describe(ref, math.nan if tightest is None else tightest) if ref else
                    "No reference is named for this case: its own error is not measured.")
        out[cid] = {"ref": ref, "ref_noise": noise, "ref_bias": bias, "tightest": tightest, "sentence": sentence}
    return out


def add_references(table, refs):
    """TABLE with ref_noise and ref_bias per row, from its case's entry of
    REFS (case_references)."""
    for col in ("ref_noise", "ref_bias"):
        table[col] = [refs[c][col] if c in refs else math.nan for c in table["case"]]
    return table


def references_md(refs, cases):
    """The lines of STEM.md's References section."""
    out = ["## References", "",
           "Per case its reference's own error, from the JSON beside it (experiments/analysis/reference.py: the "
           "noise of the mean over the reference's seeds, from their halves, and the kernel bias, from halving "
           "P_e; both in relMSE), checked against the tightest equal-error target of the case (the smallest "
           f"tightest target of its variants' curves): each should be at most {reference.MARGIN:.0%} of it. "
           "A reference without that JSON (a POV-Ray render) has its error not measured; no number is given "
           "for it. Columns `ref_noise` and `ref_bias` of the CSV hold the same numbers per case.", ""]
    for cid, r in refs.items():
        scene, size, _ref = cases[cid]
        out.append(f"- **{cid}** ({scene} at {size}): {r['sentence']}")
    return out


def pct(x):
    """'12.3%' of a fraction, 'n/a' when not a number."""
    return f"{100 * x:.1f}%" if report.isnum(x) else "n/a"


def interval(row):
    """'1.23 [1.01, 1.50]' of a row's speed-up."""
    return f"{fmt(row['speedup'])} [{fmt(row['lo'])}, {fmt(row['hi'])}]"


PAIRED_WORDS = {"higher": "faster", "lower": "slower", "undetermined": "not ranked", "unknown": "no test"}


def paired_text(row):
    """'1.05 [1.01, 1.09], faster (Holm p 0.012)' of a row's paired time
    ratio against the paper's rule; '' for the paper's rule itself."""
    if not row.get("vs_paper"):
        return ""
    return (f"{fmt(row['vs_paper_ratio'])} [{fmt(row['vs_paper_ratio_lo'])}, {fmt(row['vs_paper_ratio_hi'])}], "
            f"{PAIRED_WORDS.get(row['vs_paper'], row['vs_paper'])} (Holm p {fmt(row['vs_paper_p_holm'], 2)}); "
            f"relMSE {row['vs_paper_relmse_verdict']}")


def group_label(table, row):
    """The variant's name, or 'a = b = c' for the bit-identical variants
    reported in its row."""
    same = table[(table["case"] == row["case"]) & (table["estimate"] == row["estimate"])
                 & (table["image_group"] == row["variant"])]["variant"].tolist()
    return " = ".join(same) if len(same) > 1 else row["variant"]


def why(g, best, paper):
    """The sentences saying why a case misses the goal: where the time goes
    and where the error lies, for the best variant against the paper's rule."""
    s = []
    if not report.isnum(best["speedup"]):
        return ["no variant reaches a common error range with the conventional method in this grid"]
    if not best["above_one"]:
        s.append(f"the best variant ({best['variant']}) has its interval's lower end at {fmt(best['lo'])}, not above 1.0")
    if best["vs_paper"] == "lower":
        s.append(f"the paired test ranks it slower than the paper's rule ({paired_text(best)})")
    s.append(f"time: its precompute is {pct(best['precompute_share'])} and its eye pass {pct(best['render_share'])} of "
             f"its total (median over renders; the paper's rule: {pct(paper['precompute_share'])} and "
             f"{pct(paper['render_share'])}; the conventional eye pass: {pct(best['conv_render_share'])} of its total)")
    s.append(f"error: at the same cells and seeds its relMSE is {fmt(best['error_ratio'])}x the conventional one "
             f"(the paper's rule: {fmt(paper['error_ratio'])}x), with {pct(best['fallback_rate'])} of the eye samples "
             f"falling back to the conventional estimate and {pct(best['evaluated_share'])} of the representatives "
             "evaluated")
    s.append(where_error(best) + f" (the paper's rule: {pct(paper['excess_edge_share'])} on the edges, mean excess "
             f"relMSE {fmt(paper['excess_relmse'])})")
    return s


def where_error(row):
    """The sentence part saying where ROW's excess error lies."""
    if not report.isnum(row["excess_edge_share"]):
        return f"no excess error over the conventional renders to place (mean excess relMSE {fmt(row['excess_relmse'])})"
    return (f"{pct(row['excess_edge_share'])} of its excess squared error over the conventional renders lies on the "
            f"{pct(row['edge_pixels'])} of the pixels within {EDGE_RADIUS} pixels of an edge of the reference "
            f"(mean excess relMSE {fmt(row['excess_relmse'])})")


def figure(table, path, note):
    """Speed-up with its interval per case and variant (log y, 1.0 marked)."""
    cases = list(dict.fromkeys(table["case"]))
    variants = list(dict.fromkeys(table["variant"]))
    fig, ax = plt.subplots(figsize=(max(6.0, 1.1 * len(cases) * max(1, len(variants)) / 3), 4.2))
    width = 0.8 / max(1, len(variants))
    for j, v in enumerate(variants):
        g = table[table["variant"] == v].set_index("case").reindex(cases)
        x = np.arange(len(cases)) + (j - (len(variants) - 1) / 2) * width
        y = g["speedup"].astype(float).to_numpy()
        lo = g["lo"].astype(float).to_numpy()
        hi = g["hi"].astype(float).to_numpy()
        err = np.vstack([np.where(np.isfinite(lo), y - lo, 0), np.where(np.isfinite(hi), hi - y, 0)])
        ax.errorbar(x, y, yerr=np.clip(err, 0, None), fmt="o", ms=4, capsize=2, label=v,
                    color=plotting.RULE_COLOURS[j % len(plotting.RULE_COLOURS)])
    ax.axhline(1.0, color="#888888", lw=0.8)
    ax.set_yscale("log")
    ends = table[["lo", "hi", "speedup"]].astype(float).to_numpy().ravel()
    ends = ends[np.isfinite(ends) & (ends > 0)]
    if len(ends):
        ylo, yhi = min(ends.min(), 1.0) / 1.05, max(ends.max(), 1.0) * 1.05
        ax.set_ylim(ylo, yhi)
        plotting.log_ticks(ax.yaxis, ylo, yhi, extra=(1.0,))
    ax.set_xticks(np.arange(len(cases)))
    ax.set_xticklabels(cases, rotation=20, ha="right", fontsize=8)
    ax.set_ylabel("speed-up at equal relMSE (95% defined)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.005, 1.0), title="variant", title_fontsize=7)
    fig.subplots_adjust(left=0.07, right=0.88, top=0.95,
                        bottom=0.18 + 0.025 * plotting.footer_lines(note, fig.get_figwidth()))
    plotting.footer(fig, note)
    plotting.save(fig, path)
    plt.close(fig)


def main():
    """Command line: --case ID SCENE SIZE REF ... --variant ID NAME ARGS RUNS_CSV ...; see
    experiments/rules/beyond.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", nargs=4, action="append", default=[], metavar=("ID", "SCENE", "SIZE", "REF"))
    ap.add_argument("--variant", nargs=4, action="append", default=[], metavar=("ID", "NAME", "ARGS", "RUNS_CSV"))
    ap.add_argument("--time", default="total_s", choices=sorted(report.TIME_LABEL))
    ap.add_argument("--bootstrap", type=int, default=2000)
    ap.add_argument("--bootstrap-seed", type=int, default=1)
    ap.add_argument("--pm", default="build/photonmap")
    ap.add_argument("--gate", default="plane-lookup", help="the --rep-gate of the gated variants (for the text)")
    ap.add_argument("--settings", default="", help="the make command line that made the runs (quoted)")
    ap.add_argument("--out", required=True, help="output stem: STEM.md, STEM.csv")
    ap.add_argument("--figure", default="")
    args = ap.parse_args()
    cases = {c[0]: c[1:] for c in args.case}
    if not cases:
        report.die(WHERE, "no --case")
    for cid in cases:
        names = [v[1] for v in args.variant if v[0] == cid]
        if "paper" not in names:
            report.die(WHERE, f"case {cid}: no --variant {cid} paper (the rule every variant is compared with)")
    rows, frames = [], {}
    for cid, name, vargs, csv in args.variant:
        if cid not in cases:
            report.die(WHERE, f"--variant {cid} {name}: no --case {cid}")
        scene, size, _ref = cases[cid]
        # one bootstrap stream per (case, variant): a row's interval does not
        # depend on which other cases the run included or their order
        rng = np.random.default_rng([args.bootstrap_seed, zlib.crc32(f"{cid}/{name}".encode())])
        rows += measure(cid, scene, size, name, vargs, csv, args.time, rng, args.bootstrap, _ref)
        frames.setdefault(cid, {})[name] = report.read_csv(csv, NEED, WHERE)
    table = pd.DataFrame(rows)
    table = verdicts(add_paired(table, frames, args.time))
    refs = case_references(table, cases)
    table = add_references(table, refs)
    report.write_csv_atomic(table[COLUMNS], args.out + ".csv")
    write_md(table, cases, args, refs)
    if args.figure:
        figure(table, args.figure, f"Data: {args.out}.csv; {args.bootstrap} bootstrap resamples over seeds; "
               f"time: {report.TIME_LABEL[args.time]}.")
    print(f"wrote {args.out}.md and {args.out}.csv ({len(table)} rows)")


def write_md(table, cases, args, refs=None):
    """STEM.md: settings and provenance, the table, the verdict per case,
    the references' own error (REFS: case_references)."""
    load = stats.median_range(table["load"].to_numpy(np.float64))
    out = ["# Beyond the paper: representative variants at equal error", "",
           f"Generated on {report.today()} by `{args.settings or 'make beyond'}` "
           f"(data: [`{os.path.basename(args.out)}.csv`]({os.path.basename(args.out)}.csv); per-study tables "
           f"in `studies/`). Machine: {report.machine()}; median 1-minute load average at the start of the "
           f"renders {fmt(load[0])} (range {fmt(load[1])}-{fmt(load[2])}); commit {report.commit()}; renderer: "
           f"{report.renderer_note(args.pm)}. Time: {report.TIME_LABEL[args.time]}.", "",
           "Speed-up: conventional time / variant time at the tightest relMSE target of the equal-error curve "
           f"that at least {100 * equal_error.DEFINED_MIN:.0f}% of the bootstrap resamples reach on both fronts "
           "(`equal_error.headline`; each variant against the conventional renders of the same seeds and photon "
           f"maps, its own such target; none: n/a), with the 95% percentile interval of {args.bootstrap} bootstrap resamples "
           f"over seeds (random seed {args.bootstrap_seed}, one stream per case and variant). Reference: each scene's converged render at its size "
           "(`converged_ref` of `experiments/analysis/runs.py`, made by `experiments/rules/reference.smk`; its own "
           "error per case: section References). "
           "Fallback rate: rep_fallbacks / eye samples; evaluated: "
           "reps_evaluated / representatives (both pooled over the variant's renders). Error ratio: the variant's "
           "mean relMSE over the conventional one's at the same cells and seeds. All the renders of one (cell, seed) "
           "of a case, the conventional, the paper's rule and every variant, ran back to back in one group "
           "(`experiments/launch.py`, in the order given at odd seeds and reversed at even ones), so each time "
           "ratio is a paired sample of one machine state.", "",
           "Against the paper's rule (paired): per seed the paper's rule's time over the variant's, each summed "
           "over the case's grid cells, exp of the mean log ratio with its 95% t interval over seeds (above 1: "
           "the variant is faster), its t test Holm-corrected over the case's variants (\"faster\" / "
           f"\"slower\" at a family-wise {100 * ALPHA:g}%, else \"not ranked\"), and the paired relMSE difference "
           "(mean over the cells per seed; `stats.compare_family`, Holm over the variants). Variants whose "
           "images are bit-identical (relMSE equal on every cell and seed) from the same work (the renders' work "
           "counters equal) are one row, named a = b; the row's numbers are the first's.", "",
           "| case | variant | target relMSE | speed-up [95%] | against the paper's rule (paired) | fallback | evaluated | precompute | eye pass | error ratio |",
           "|---|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for _, r in table.iterrows():
        if r["image_group"] and r["image_group"] != r["variant"]:
            continue
        mark = " (best)" if r["best"] else ""
        out.append(f"| {r['case']} | {group_label(table, r)}{mark} | {fmt(r['target'])} | {interval(r)} | "
                   f"{paired_text(r)} | {pct(r['fallback_rate'])} | {pct(r['evaluated_share'])} | "
                   f"{pct(r['precompute_share'])} | {pct(r['render_share'])} | {fmt(r['error_ratio'])} |")
    out += ["", "## Where the time goes and where the error lies", "",
            "Per case and variant, medians over the variant's renders of the renderer's own timers (`--stats` "
            "time_s, each the minimum over the render's repeats: the photon pass with the kd-tree build, the minimum of "
            "their sum per repeat; the precompute, which a "
            "lazy variant folds into its eye pass; and the eye pass), the share of "
            "the representatives evaluated and the eye samples that fell back, and where its excess error lies: "
            "the mean over pixels of (its per-pixel relMSE term minus the conventional render's of the same cell "
            "and seed), pooled over every cell and seed, and the share of that excess on the pixels within "
            f"{EDGE_RADIUS} pixels of an edge of the reference (a luminance step of more than {EDGE_STEP:g} of "
            f"(the larger side + {EDGE_OFFSET:g}) between neighbours: geometric edges and shadow boundaries "
            "alike). A share well above the edge pixels' share says the representatives' error is an edge "
            "error (a representative across an edge); near the pixel share, it is spread over flat regions.", "",
            "| case | variant | photon pass s | precompute s | eye pass s | evaluated | fallback | excess relMSE | edge pixels | excess on edges |",
            "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for _, r in table.iterrows():
        out.append(f"| {r['case']} | {r['variant']} | {fmt(r['photons_med_s'])} | {fmt(r['precompute_med_s'])} | {fmt(r['render_med_s'])} | "
                   f"{pct(r['evaluated_share'])} | {pct(r['fallback_rate'])} | {fmt(r['excess_relmse'])} | "
                   f"{pct(r['edge_pixels'])} | {pct(r['excess_edge_share'])} |")
    out += ["", "## The goal per case", "",
            "The goal: the best variant's equal-error interval lies above 1.0 and the paired test does not rank it "
            "slower than the paper's rule. The best is the variant the paired tests rank faster than every other "
            "(the paper's rule and the other image groups; Holm over those comparisons) without ranking its error "
            "higher; a case where no variant is so ranked has no best.", ""]
    met = 0
    for (cid, est), g in table.groupby(["case", "estimate"], sort=False):
        best = g[g["best"]]
        paper = g[g["variant"] == "paper"].iloc[0]
        if best.empty:
            out.append(f"- **{cid}** ({est}): no variant is ranked faster than every other by the paired tests: "
                       "no best, so the goal does not hold.")
            continue
        b = best.iloc[0]
        rel = {"higher": "faster than the paper's rule (paired, Holm)",
               "undetermined": "not ranked against the paper's rule (paired, Holm)",
               "lower": "slower than the paper's rule (paired, Holm)",
               "unknown": "not compared with the paper's rule"}[b["vs_paper"]]
        head = (f"- **{cid}** ({est}): best {group_label(table, b)} {interval(b)}, "
                f"{'above' if b['above_one'] else 'not above'} 1.0 and {rel} ({paired_text(b)}; the paper's rule "
                f"at equal error: {interval(paper)}): ")
        if b["goal_met"]:
            met += 1
            out.append(head + "the goal holds.")
        else:
            out.append(head + "the goal does not hold; " + "; ".join(why(g, b, paper)) + ".")
    n = table.groupby(["case", "estimate"]).ngroups
    out += ["", f"The goal holds in {met} of {n} cases. Not measured: the error's share in the pixels that fell "
            "back (the renderer writes no per-pixel fallback map; the pooled fallback rate stands for it)."]
    out += [""] + references_md(refs if refs is not None else case_references(table, cases), cases)
    report.write_atomic(args.out + ".md", "\n".join(out) + "\n")


if __name__ == "__main__":
    main()
