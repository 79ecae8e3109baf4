#!/usr/bin/python3
"""repstudy.py: the representative study -> STEM.md, STEM.csv, STEM-cells.csv
and a figure.

Owns the question "which rule for choosing representatives reproduces the
paper's cost pattern?". Input: the runs.csv of the untagged grid (its
precomputed runs use the renderer's default rule; its conventional runs are
what every rule is compared with) and one runs-TAG.csv per variant rule
(`make rep-study`: precomputed only, paper estimate). A rule is named
everyK (--rep-every K), countN (--rep-count N) or shared (the default rule
with --rep-tree shared); the name is checked against the runs.

Times are the renderer's own phase timers, precompute + eye pass
(precompute_s + render_s from --stats): the photon trace and tree build are
the same code in both methods. Process CPU (--time) is a secondary column.
Per (rule, P_e) and seed the cost model time = a + b n is fitted over the n
(stats.linear_fit); the comparable quantity is the slope ratio b_prec /
b_conv: both slopes are kNN work per unit of n (the precompute's queries at
the representatives, the eye pass's at the eye samples), so the machine's
speed cancels. The same seed is the same photon map for both methods, so
the ratio is formed per seed and its mean taken with a Student-t interval
over the seeds (seeds - 1 degrees of freedom).

The paper's Table 1 is one run per cell. Assumption: each of its times is
one measurement with a known relative standard deviation, the spread our
own single runs show (timing_noise: the median over our cells of the sd of
log(time) over seeds); its slopes and slope ratio get normal errors
propagated from that (wls_slope, Fieller with infinite dof). Agreement per
P_e: a Welch t test of ours - paper (compare_with_paper), turned into a
normal score z; per rule chi^2 = sum z^2 with one degree of freedom per P_e,
less one for a rule with a parameter fitted to the paper (countN by
default, --fitted); Holm's correction over the rules (score_rules). Output
STEM-rules.csv holds those tests, and their verdicts with the paper's noise
scaled by each SENSITIVITY factor (columns verdict_noise_xF); findings.py
reads it.

A cost model over the rules: per P_e the precomputed slope is linear in the
number of representatives R (b_prec = beta0 + beta1 R, fitted over the
rules with the separate tree), so the paper's slope ratio names the R it
implies, R* = (ratio_paper b_conv - beta0) / beta1, with the interval of
the paper's ratio. A rule family is a map P_e -> R: a fixed fraction
(R = f x stored photons) or a fixed count (R = min(N, stored)); its best
parameter minimises the chi^2 of the slope ratios it predicts against the
paper's. (A spacing radius d gives R = min(stored, A / (c d^2)) over a lit
area A: the fixed-count family's shape.)
"""

import argparse
import math
import os
import re

import numpy as np
import pandas as pd
from scipy import optimize
from scipy import stats as sps

from experiments.analysis import metrics
from experiments.analysis import plotting
from experiments.analysis import report
from experiments.analysis import stats
from experiments.analysis.report import fmt, fmt_interval

NEED = ["method", "estimate", "photons", "nn", "seed", "status", "role", "rep_every", "representatives",
        "photons_stored", "cpu_s", "total_s", metrics.PRIMARY_COLUMN, "relmse_conv", "precompute_s", "render_s", "size"]


FIT_COLUMNS = ["rule", "label", "kind", "photons", "stored", "reps", "reps_fraction", "seeds", "points",
               "a_prec", "a_prec_half", "b_prec", "b_prec_half", "a_conv", "a_conv_half", "b_conv", "b_conv_half",
               "slope_ratio", "slope_ratio_lo", "slope_ratio_hi", "slope_ratio_se", "icpt_ratio", "icpt_ratio_lo",
               "icpt_ratio_hi", "paper_slope_ratio", "paper_slope_ratio_lo", "paper_slope_ratio_hi",
               "paper_slope_ratio_se", "paper_icpt_ratio", "paper_icpt_ratio_lo", "paper_icpt_ratio_hi",
               "t", "dof_welch", "p_pe", "z", "z_icpt", "slope_ratio_secondary", "slope_ratio_secondary_lo",
               "slope_ratio_secondary_hi", "b_eye_prec", "b_eye_prec_half"]
SCORE_COLUMNS = ["rule", "label", "kind", "pe_compared", "fitted", "chi2", "dof", "p_value", "p_holm", "verdict",
                 "max_abs_z", "chi2_icpt", "p_icpt", "shape_factor", "shape_cells"]


def parse_rule(name):
    """A rule name -> dict(name, kind, value, label). Exits on a bad name."""
    m = re.fullmatch(r"every([1-9][0-9]*)|count([1-9][0-9]*)|shared", name)
    if not m:
        report.die("repstudy.py", f"rule '{name}': expected everyK, countN or shared")
    if m.group(1):
        k = int(m.group(1))
        label = "every photon" if k == 1 else f"every {plotting.ordinal(k)}"
        return {"name": name, "kind": "every", "value": k, "label": label}
    if m.group(2):
        n = int(m.group(2))
        return {"name": name, "kind": "count", "value": n, "label": f"count {plotting.kilo(n)}"}
    return {"name": name, "kind": "shared", "value": 0, "label": "shared tree"}


def read_runs(path):
    """A runs.csv with the columns this script needs, checked by name."""
    f = report.read_csv(path, NEED, "repstudy.py")
    # the minimum over repeats of precompute + eye pass (runs.csv without it: one timed run each)
    f[PHASE] = (f["precompute_render_s"].astype(float) if "precompute_render_s" in f
                else f["precompute_s"].astype(float) + f["render_s"].astype(float))
    f[SLOPE] = np.where(f["method"] == "precomputed", f["precompute_s"].astype(float), f[PHASE])
    if "rep_count" not in f.columns:
        f["rep_count"] = 0
    f["rep_count"] = f["rep_count"].fillna(0)
    return f


def precomputed_runs(frame):
    """The ok precomputed renders of the paper estimate in a grid."""
    return frame[(frame["method"] == "precomputed") & (frame["estimate"] == "paper") & (frame["role"] == "grid")
                 & (frame["status"] == "ok")]


def check_rule(rule, runs, path):
    """Exit unless RUNS were rendered with the rule RULE names."""
    if runs.empty:
        report.die("repstudy.py", f"{path}: no ok precomputed render of the paper estimate")
    rc = runs["rep_count"].astype(float)
    if rule["kind"] == "count":
        want = np.minimum(rule["value"], runs["photons_stored"].astype(float))
        bad = (rc != rule["value"]) | (runs["representatives"].astype(float) != want)
    elif rule["kind"] == "every":
        bad = (rc != 0) | (runs["rep_every"].astype(float) != rule["value"])
    else:
        bad = rc != 0
    if bad.any():
        r = runs[bad].iloc[0]
        report.die("repstudy.py", f"{path}: rule '{rule['name']}' but {r['run']} has rep_every {r['rep_every']}, "
                   f"rep_count {r['rep_count']}, {r['representatives']} representatives")


PHASE = "phase_s"  # the renderer's own phase timers: precompute + eye pass (stats JSON time_s)
# the timer that carries the n-dependent kNN work: the precompute's for the
# precomputed method (its eye pass looks up one representative, whatever n),
# the eye pass's for the conventional one (it has no precompute)
SLOPE = "knn_phase_s"


def fit_by_photons(runs, time_col):
    """{photons: linear_fit of TIME_COL on nn} over RUNS (pooled over seeds)."""
    return {int(p): stats.linear_fit(g["nn"], g[time_col]) for p, g in runs.groupby("photons")}


def per_seed_slopes(runs, time_col):
    """{seed: slope b of TIME_COL = a + b n} over the n of one P_e's RUNS;
    a seed with fewer than two distinct n is left out."""
    out = {}
    for s, g in runs.groupby("seed"):
        if g["nn"].nunique() >= 2:
            out[int(s)] = stats.linear_fit(g["nn"], g[time_col])["b"]
    return out


def seed_slope_ratio(pre, conv, time_col, level=stats.LEVEL):
    """The slope ratio b_prec / b_conv over seeds: per seed s (the same seed
    is the same photon map for both methods) r_s = b_prec,s / b_conv,s, then
    the mean of r_s with its Student-t interval over the seeds (k - 1
    degrees of freedom). Returns dict(ratio, lo, hi, se, seeds); se, lo, hi
    are nan with fewer than two common seeds, everything with none."""
    bp, bc = per_seed_slopes(pre, time_col), per_seed_slopes(conv, time_col)
    r = np.array([bp[s] / bc[s] for s in sorted(set(bp) & set(bc)) if bc[s] != 0], dtype=np.float64)
    m, h = stats.t_interval(r, level)
    se = float(np.std(r, ddof=1) / math.sqrt(r.size)) if r.size >= 2 else math.nan
    return {"ratio": m, "lo": m - h, "hi": m + h, "se": se, "seeds": int(r.size)}


def timing_noise(frames, time_col):
    """The relative spread of one run's time: per cell (method, P_e, n) of
    FRAMES the standard deviation of log(time) over its seeds (ddof = 1),
    the median over the cells. It includes the seed's photon map as well as
    the machine's noise, so it is an upper estimate of a single run's timing
    noise. nan when no cell has two seeds."""
    sds = []
    for f in frames:
        for _, g in f.groupby(["method", "photons", "nn"]):
            v = g[time_col].to_numpy(np.float64)
            v = v[np.isfinite(v) & (v > 0)]
            if v.size >= 2:
                sds.append(float(np.std(np.log(v), ddof=1)))
    return float(np.median(sds)) if sds else math.nan


def wls_slope(nn, times, rel_sd):
    """(a, se_a, b, se_b) of the least-squares line times = a + b nn when each
    time is one measurement with standard deviation REL_SD x time (known, so
    normal intervals): the ordinary least-squares coefficients, their
    variances propagated from the assumed per-point variances."""
    x = np.asarray(nn, dtype=np.float64)
    y = np.asarray(times, dtype=np.float64)
    var = (rel_sd * y) ** 2
    xb = x.mean()
    sxx = float(np.sum((x - xb) ** 2))
    wb = (x - xb) / sxx
    wa = 1.0 / x.size - xb * wb
    return float(wa @ y), math.sqrt(float(wa ** 2 @ var)), float(wb @ y), math.sqrt(float(wb ** 2 @ var))


def paper_fits(paper, rel_sd):
    """{photons: (conventional, proposed)} of the paper's Table 1, each a
    dict(a, se_a, b, se_b) from wls_slope: every time one noisy measurement
    with relative standard deviation REL_SD."""
    out = {}
    for k, g in paper.groupby("emitted_kphotons"):
        fits = []
        for col in ("conventional_s", "proposed_s"):
            a, sa, b, sb = wls_slope(g["nn"], g[col], rel_sd)
            fits.append({"a": a, "se_a": sa, "b": b, "se_b": sb})
        out[int(round(k * 1000))] = tuple(fits)
    return out


def ratio_of(fit_num, fit_den, key, dof):
    """(ratio, lo, hi, se) of coefficient KEY ('a' or 'b') of two fits:
    Fieller's interval with DOF degrees of freedom (inf: normal), the
    delta-method standard error."""
    se = "se_" + key
    r, lo, hi = stats.fieller_ratio(fit_num[key], fit_num[se], fit_den[key], fit_den[se], dof)
    return r, lo, hi, stats.ratio_se(fit_num[key], fit_num[se], fit_den[key], fit_den[se])


def compare_with_paper(ours, se_ours, dof_ours, paper, se_paper):
    """(t, nu, p, z) of ours - paper: t = difference / sqrt(se_ours^2 +
    se_paper^2), nu its Welch-Satterthwaite degrees of freedom (the paper's
    standard error is known: infinite degrees of freedom), p the two-sided
    Student-t probability, z the normal score with the same p and sign. All
    nan when an input is not a number or DOF_OURS < 1."""
    vals = (ours, se_ours, paper, se_paper)
    if any(not (isinstance(v, (int, float)) and math.isfinite(v)) for v in vals) or not dof_ours >= 1:
        return math.nan, math.nan, math.nan, math.nan
    se = math.hypot(se_ours, se_paper)
    if se == 0:
        return math.nan, math.nan, math.nan, math.nan
    t = (ours - paper) / se
    nu = math.inf if se_ours == 0 else dof_ours * (se / se_ours) ** 4
    p = float(2 * sps.t.sf(abs(t), nu))
    z = math.copysign(float(sps.norm.isf(p / 2)), t) if p > 0 else math.copysign(math.inf, t)
    return t, nu, p, z


def score_rules(rows, alpha=1 - stats.LEVEL):
    """Per rule (ROWS: dicts with rule, zs, fitted) chi^2 = sum z^2 over the
    P_e with dof = number of P_e less the parameters fitted to the paper,
    its p-value, and the Holm-adjusted p over the rules (a rule with no dof
    left has no test: nan, and does not count in Holm's m). Returns a list
    of dicts (chi2, dof, p_value, p_holm, verdict) in the order of ROWS."""
    out = []
    for r in rows:
        z = np.asarray(r["zs"], dtype=np.float64)
        z = z[np.isfinite(z)]
        dof = max(int(z.size - r["fitted"]), 0)
        chi2 = float(np.sum(z ** 2)) if z.size else math.nan
        p = float(sps.chi2.sf(chi2, dof)) if dof > 0 else math.nan
        out.append({"chi2": chi2, "dof": dof, "p_value": p})
    adj = stats.holm([o["p_value"] for o in out])
    for o, q in zip(out, adj):
        o["p_holm"] = float(q)
        o["verdict"] = ("no test" if not math.isfinite(q) else
                        "incompatible" if q < alpha else "not rejected")
    return out


def noise_sensitivity(fits, scores, factor):
    """The rule tests again with the paper's assumed noise FACTOR times as
    large (its standard errors scale with the noise): a list of dicts as
    score_rules returns, in the order of SCORES."""
    rows = []
    for _, s in scores.iterrows():
        f = fits[fits["rule"] == s["rule"]]
        zs = [compare_with_paper(r["slope_ratio"], r["slope_ratio_se"], r["seeds"] - 1, r["paper_slope_ratio"],
                                 factor * r["paper_slope_ratio_se"])[3] for _, r in f.iterrows()]
        rows.append({"zs": zs, "fitted": int(s["fitted"])})
    return score_rules(rows)


def analyse(base, variants, paper, time_col, fitted=None):
    """The study on the phase timers (PHASE), TIME_COL a secondary column:
    a dict with 'rules' (list), 'fits' (DataFrame, one row per rule and
    P_e), 'cells' (one row per rule, P_e, n), 'scores' (one row per rule),
    'model' (one row per P_e), 'families' (one row per family), 'noise'
    (the relative timing noise assumed for the paper's numbers). FITTED:
    the names of rules with one parameter fitted to the paper (None: every
    countN rule)."""
    conv = base[(base["method"] == "conventional") & (base["estimate"] == "paper") & (base["role"] == "grid")
                & (base["status"] == "ok")]
    if conv.empty:
        report.die("repstudy.py", "the base grid has no ok conventional render of the paper estimate")
    rules = []
    base_pre = precomputed_runs(base)
    if not base_pre.empty:
        k = int(base_pre["rep_every"].iloc[0])
        rule = parse_rule(f"every{k}") if (base_pre["rep_count"] == 0).all() else \
            parse_rule(f"count{int(base_pre['rep_count'].iloc[0])}")
        rule["label"] += " (default)"
        rules.append((rule, base_pre))
    for rule, frame, path in variants:
        pre = precomputed_runs(frame)
        check_rule(rule, pre, path)
        rules.append((rule, pre))
    noise = timing_noise([conv] + [pre for _, pre in rules], PHASE)
    conv_fit = fit_by_photons(conv, PHASE)
    conv_slope = fit_by_photons(conv, SLOPE)
    pfits = paper_fits(paper, noise) if math.isfinite(noise) else {}
    fits, cells, scores, tests = [], [], [], []
    for rule, pre in rules:
        is_fitted = (rule["kind"] == "count") if fitted is None else (rule["name"] in fitted)
        pre_fit = fit_by_photons(pre, PHASE)
        pre_slope = fit_by_photons(pre, SLOPE)
        pre_eye = fit_by_photons(pre, "render_s")
        zs, zi, logs = [], [], []
        for p in sorted(pre_fit):
            if p not in conv_fit:
                continue
            f, c = pre_fit[p], conv_fit[p]
            fs, cs, fe = pre_slope[p], conv_slope[p], pre_eye[p]
            g = pre[pre["photons"] == p]
            gc = conv[conv["photons"] == p]
            row = {"rule": rule["name"], "label": rule["label"], "kind": rule["kind"], "photons": p,
                   "stored": float(np.median(g["photons_stored"])), "reps": float(np.median(g["representatives"])),
                   "points": f["points"],
                   "b_prec": fs["b"], "b_prec_half": fs["half_b"], "a_prec": f["a"], "a_prec_half": f["half_a"],
                   "b_conv": cs["b"], "b_conv_half": cs["half_b"], "a_conv": c["a"], "a_conv_half": c["half_a"],
                   "b_eye_prec": fe["b"], "b_eye_prec_half": fe["half_b"]}
            row["reps_fraction"] = row["reps"] / row["stored"] if row["stored"] > 0 else math.nan
            sr = seed_slope_ratio(g, gc, SLOPE)
            row["seeds"] = sr["seeds"]
            row["slope_ratio"], row["slope_ratio_lo"], row["slope_ratio_hi"] = sr["ratio"], sr["lo"], sr["hi"]
            row["slope_ratio_se"] = sr["se"]
            sc = seed_slope_ratio(g, gc, time_col)
            row["slope_ratio_secondary"], row["slope_ratio_secondary_lo"], row["slope_ratio_secondary_hi"] = \
                sc["ratio"], sc["lo"], sc["hi"]
            row["icpt_ratio"], row["icpt_ratio_lo"], row["icpt_ratio_hi"], _ = ratio_of(
                f, c, "a", min(f["dof"], c["dof"]))
            pr = pfits.get(p)
            if pr:
                pc, pp = pr
                (row["paper_slope_ratio"], row["paper_slope_ratio_lo"], row["paper_slope_ratio_hi"],
                 row["paper_slope_ratio_se"]) = ratio_of(pp, pc, "b", math.inf)
                (row["paper_icpt_ratio"], row["paper_icpt_ratio_lo"], row["paper_icpt_ratio_hi"], se_ip) = \
                    ratio_of(pp, pc, "a", math.inf)
                row["t"], row["dof_welch"], row["p_pe"], row["z"] = compare_with_paper(
                    row["slope_ratio"], sr["se"], sr["seeds"] - 1, row["paper_slope_ratio"],
                    row["paper_slope_ratio_se"])
                zs.append(row["z"])
                se_ia = stats.ratio_se(f["a"], f["se_a"], c["a"], c["se_a"])
                row["z_icpt"] = compare_with_paper(row["icpt_ratio"], se_ia, min(f["dof"], c["dof"]),
                                                   row["paper_icpt_ratio"], se_ip)[3]
                zi.append(row["z_icpt"])
            fits.append(row)
            for n, gn in g.groupby("nn"):
                cn = gc[gc["nn"] == n]
                both = sorted(set(gn["seed"]) & set(cn["seed"]))
                a_ = gn.set_index("seed")
                b_ = cn.drop_duplicates("seed").set_index("seed")
                ratio, lo, hi, pairs = stats.paired_log_ratio(a_.loc[both, PHASE].to_numpy(float),
                                                              b_.loc[both, PHASE].to_numpy(float))
                r2, lo2, hi2, _ = stats.paired_log_ratio(a_.loc[both, time_col].to_numpy(float),
                                                         b_.loc[both, time_col].to_numpy(float))
                em, eh = stats.t_interval(gn[metrics.PRIMARY_COLUMN])
                cm, ch = stats.t_interval(gn["relmse_conv"])
                tm, tlo, thi = stats.median_range(gn[time_col])
                pm_, plo, phi = stats.median_range(gn[PHASE])
                pap = paper[(paper["emitted_kphotons"] * 1000 == p) & (paper["nn"] == n)]
                paper_ratio = float(pap["ratio_percent"].iloc[0]) if len(pap) else math.nan
                cells.append({"rule": rule["name"], "label": rule["label"], "photons": p, "nn": int(n),
                              "seeds": int(len(gn)), "pairs": pairs, "reps": float(np.median(gn["representatives"])),
                              "time_median_s": tm, "time_min_s": tlo, "time_max_s": thi,
                              "phase_median_s": pm_, "phase_min_s": plo, "phase_max_s": phi,
                              "precompute_median_s": float(np.median(gn["precompute_s"])),
                              "render_median_s": float(np.median(gn["render_s"])),
                              "ratio_percent": 100 * ratio, "ratio_ci95_lo": 100 * lo, "ratio_ci95_hi": 100 * hi,
                              "ratio_secondary_percent": 100 * r2, "ratio_secondary_ci95_lo": 100 * lo2,
                              "ratio_secondary_ci95_hi": 100 * hi2,
                              "paper_ratio_percent": paper_ratio,
                              "relmse_ref_mean": em, "relmse_ref_ci95": eh,
                              "relmse_conv_mean": cm, "relmse_conv_ci95": ch})
                if math.isfinite(paper_ratio) and ratio > 0:
                    logs.append(math.log(100 * ratio / paper_ratio))
        tests.append({"zs": zs, "fitted": 1 if is_fitted else 0})
        zi_ = np.asarray(zi, dtype=np.float64)
        zi_ = zi_[np.isfinite(zi_)]
        scores.append({"rule": rule["name"], "label": rule["label"], "kind": rule["kind"], "pe_compared": len(zs),
                       "fitted": 1 if is_fitted else 0,
                       "max_abs_z": float(np.nanmax(np.abs(zs))) if np.isfinite(zs).any() else math.nan,
                       "chi2_icpt": float(np.sum(zi_ ** 2)) if zi_.size else math.nan,
                       "p_icpt": float(sps.chi2.sf(float(np.sum(zi_ ** 2)), zi_.size)) if zi_.size else math.nan,
                       "shape_factor": math.exp(math.sqrt(np.mean(np.square(logs)))) if logs else math.nan,
                       "shape_cells": len(logs)})
    for s, t in zip(scores, score_rules(tests)):
        s.update(t)
    fits = pd.DataFrame(fits).reindex(columns=FIT_COLUMNS)
    cells = pd.DataFrame(cells)
    scores = pd.DataFrame(scores).reindex(columns=SCORE_COLUMNS)
    if math.isfinite(noise) and len(scores):
        for factor in SENSITIVITY:
            scores[sensitivity_column(factor)] = [a["verdict"] for a in noise_sensitivity(fits, scores, factor)]
    model = cost_model(fits)
    families = family_fits(model)
    return {"rules": [r for r, _ in rules], "fits": fits, "cells": cells, "scores": scores, "model": model,
            "families": families, "conv": conv, "noise": noise}


def cost_model(fits):
    """Per P_e: b_prec = beta0 + beta1 R over the rules with the separate
    tree, and the R the paper's slope ratio implies (with its interval)."""
    rows = []
    sep = fits[fits["kind"] != "shared"] if len(fits) else fits
    for p, g in sep.groupby("photons"):
        fit = stats.linear_fit(g["reps"], g["b_prec"])
        row = {"photons": int(p), "stored": float(np.median(g["stored"])), "rules": len(g),
               "beta0": fit["a"], "beta1": fit["b"], "beta1_half": fit["half_b"], "r2": fit["r2"],
               "b_conv": float(g["b_conv"].iloc[0])}
        for key in ("", "_lo", "_hi"):
            col = "paper_slope_ratio" + key
            r = g[col].iloc[0] if col in g else math.nan
            row["needed_reps" + key] = ((r * row["b_conv"] - fit["a"]) / fit["b"]
                                        if fit["b"] > 0 and report.isnum(r) else math.nan)
        row["paper_slope_ratio"] = g["paper_slope_ratio"].iloc[0] if "paper_slope_ratio" in g else math.nan
        row["paper_slope_ratio_se"] = g["paper_slope_ratio_se"].iloc[0] if "paper_slope_ratio_se" in g else math.nan
        rows.append(row)
    return pd.DataFrame(rows)


def family_chi2(model, reps_of):
    """chi^2 of the slope ratios the model predicts with R = REPS_OF(stored)
    against the paper's, per P_e with the paper's standard error."""
    total = 0.0
    for _, m in model.iterrows():
        if not (report.isnum(m["paper_slope_ratio"]) and report.isnum(m["paper_slope_ratio_se"])
                and m["paper_slope_ratio_se"] > 0):
            continue
        pred = (m["beta0"] + m["beta1"] * reps_of(m["stored"])) / m["b_conv"]
        total += ((pred - m["paper_slope_ratio"]) / m["paper_slope_ratio_se"]) ** 2
    return total


def family_fits(model):
    """The best parameter of each rule family (fixed fraction f of the stored
    photons; fixed count N, all when fewer are stored) and its chi^2."""
    ok = model.dropna(subset=["beta0", "beta1", "paper_slope_ratio", "paper_slope_ratio_se"]) if len(model) else model
    if ok.empty or (ok["beta1"] <= 0).any():
        return pd.DataFrame()
    rows = []
    res = optimize.minimize_scalar(lambda lf: family_chi2(ok, lambda s: math.exp(lf) * s),
                                   bounds=(math.log(1e-4), 0.0), method="bounded")
    rows.append({"family": "fixed fraction", "parameter": "f", "best": math.exp(res.x), "chi2": float(res.fun)})
    top = float(ok["stored"].max()) * 4
    res = optimize.minimize_scalar(lambda ln: family_chi2(ok, lambda s: min(math.exp(ln), s)),
                                   bounds=(math.log(100.0), math.log(top)), method="bounded")
    rows.append({"family": "fixed count", "parameter": "N", "best": math.exp(res.x), "chi2": float(res.fun)})
    dof = max(len(ok) - 1, 1)
    for r in rows:
        r["dof"] = dof
        r["p_value"] = float(sps.chi2.sf(r["chi2"], dof))
        r["predicted"] = "; ".join(
            f"{plotting.kilo(m['photons'])}: R={fmt(reps_of_family(r, m['stored']))} ratio "
            f"{fmt((m['beta0'] + m['beta1'] * reps_of_family(r, m['stored'])) / m['b_conv'])}"
            for _, m in ok.iterrows())
    return pd.DataFrame(rows)


def reps_of_family(row, stored):
    """The representatives a family row gives for STORED photons."""
    return row["best"] * stored if row["parameter"] == "f" else min(row["best"], stored)


SENSITIVITY = (0.5, 2.0)  # the factors on the paper's assumed noise whose verdicts the report also gives


def sensitivity_column(factor):
    """The rules CSV's column of the verdicts with the paper's noise FACTOR
    times the assumed one: 'verdict_noise_x0.5'."""
    return f"verdict_noise_x{factor:g}"


def conclusions(res):
    """What the report and the figure state beyond analyse's tables, from
    RES: the renders' size and conventional seeds, the paper's slope ratio
    per P_e, the rules tested (Holm), the one with the largest Holm p
    (chi^2 per dof breaking ties), those not rejected, the best table shape, the verdicts with the paper's noise
    scaled by each factor of SENSITIVITY, and the rules with the shared tree."""
    fits, scores, conv = res["fits"], res["scores"], res["conv"]
    first = fits.drop_duplicates("photons").set_index("photons")
    rec = {"size": conv["size"].iloc[0], "seeds": sorted(set(conv["seed"])),
           "paper_ratio": {p: {k: first.loc[p].get(f"paper_slope_ratio{k}") for k in ("", "_lo", "_hi")}
                           for p in sorted(set(fits["photons"]))},
           "tested": int(scores["p_holm"].notna().sum()), "best": None, "best_ties": [], "kept": [],
           "best_shape": None,
           "sensitivity": [],
           "shared": [r for r in dict.fromkeys(fits["rule"])
                      if fits.loc[fits["rule"] == r, "kind"].iloc[0] == "shared"]}
    tested = scores.dropna(subset=["p_holm"])
    if len(tested):
        # the rule with the least evidence against it: the largest p (chi^2
        # alone would favour the rules fitted to the paper, one dof fewer)
        b = tested.assign(_fit=tested["chi2"] / tested["dof"].clip(lower=1)).sort_values(
            ["p_holm", "_fit"], ascending=[False, True]).iloc[0]
        rec["best"] = {k: b[k] for k in ("label", "chi2", "dof", "p_holm")}
        # Holm's adjustment caps p at 1, so several rules can share the largest:
        # then none has less evidence against it than the others
        rec["best_ties"] = tested[tested["p_holm"] == b["p_holm"]]["label"].tolist()
        rec["kept"] = tested[tested["verdict"] == "not rejected"]["label"].tolist()
        shape = scores.dropna(subset=["shape_factor"]).sort_values("shape_factor")
        if len(shape):
            rec["best_shape"] = (shape.iloc[0]["label"], shape.iloc[0]["shape_factor"])
        for factor in (f for f in SENSITIVITY if sensitivity_column(f) in scores.columns):
            col = sensitivity_column(factor)
            rec["sensitivity"].append({"factor": factor, "noise": factor * res["noise"], "kept": [
                lab for lab, v in zip(scores["label"], scores[col]) if v == "not rejected"]})
    return rec


def markdown(res, rec, args, base_path, variant_paths):
    """The Markdown report, worded from RES (analyse) and REC (conclusions)."""
    fits, cells, scores, model, families = res["fits"], res["cells"], res["scores"], res["model"], res["families"]
    size = rec["size"]
    seeds = " ".join(str(s) for s in rec["seeds"])
    stem = os.path.basename(args.out)
    out = ["# The representative study", "",
           f"Generated by `make rep-study` on {report.today()}. Data: [`{os.path.basename(base_path)}`]"
           f"({os.path.relpath(base_path, os.path.dirname(args.out) or '.')}) (the untagged grid: the default rule "
           "and the conventional renders every rule is compared with) and "
           + ", ".join(f"`{os.path.basename(p)}`" for p in variant_paths) + " (one per rule); "
           f"size {size}, paper estimate, conventional seeds {seeds}. Time: the renderer's own phase timers, "
           "precompute + eye pass (`precompute_s + render_s`, the stats JSON's `time_s`; the photon trace and the "
           f"tree build are the same code in both methods and left out); `{args.time}` "
           f"({report.TIME_LABEL.get(args.time, args.time)}) is a secondary column. "
           f"This report's numbers: [`{stem}.csv`]({stem}.csv) (fits), [`{stem}-rules.csv`]({stem}-rules.csv) "
           f"(one test per rule), [`{stem}-cells.csv`]({stem}-cells.csv) (cells); figure: `figures/rep-study.png`.",
           "", f"- Machine: {report.machine()}; load average now {report.loadavg_now()}; commit {report.commit()}.",
           "- Ours: per P_e and seed, the slopes b of time = a + b n over the n (the same seed is the same photon "
           "map for both methods), each from the timer that holds the n-dependent kNN work: the precompute's for "
           "the precomputed method (its eye pass looks up one representative whatever n; that eye pass's own "
           "slope is `b_eye_prec` in the fits CSV, a check that it is near 0), the eye pass's for the "
           "conventional one. The slope ratio is the mean over the seeds of b_prec / b_conv with its "
           "Student-t 95% interval (seeds - 1 degrees of freedom).",
           "- **Assumption about the paper.** Table 1 (`experiments/paper-table1.csv`) is one run per cell, "
           "each time taken as one measurement with a known relative standard deviation equal to the spread our "
           f"own single runs show: sigma = {fmt(res['noise'], 2)} (the median over our cells of the standard "
           "deviation of log(time) over the seeds; it includes the seeds' photon maps, so it errs on the wide "
           "side). The paper's slopes and ratios then have normal (known-variance) errors propagated from it; "
           "its intercepts too.", ""]
    if size != "1024x768":
        out += [f"**Note:** these renders are {size}, the paper's 1024x768. The conventional slope scales with "
                "the eye samples and the precomputed one does not, so slope ratios are not comparable with the "
                "paper's at this size.", ""]
    out += ["## Which rule reproduces the paper's cost pattern", "",
            "The slope ratio b_prec / b_conv is the comparable quantity: both slopes are kNN work per unit of n, "
            "at the representatives (precompute) and at the eye samples (eye pass), so the machine cancels. "
            "[lo, hi]: 95% interval (ours: t over seeds; the paper's: Fieller with its assumed known errors). "
            "z: the normal score of the Welch t test of ours - paper (Welch-Satterthwaite degrees of freedom).", ""]
    ps = sorted(set(fits["photons"]))
    hdr = ["rule"] + [f"P_e={plotting.kilo(p)}: reps (fraction)" for p in ps] + \
          [f"slope ratio {plotting.kilo(p)} [95% CI]" for p in ps] + \
          [f"{args.time} slope ratio {plotting.kilo(p)}" for p in ps] + \
          ["chi^2", "dof", "p", "p (Holm)", "verdict", "intercepts: chi^2 (p)", "table shape (x)"]
    rows = []
    pap_row = ["**paper**"] + ["not stated" for _ in ps]
    for p in ps:
        r = rec["paper_ratio"][p]
        pap_row.append(f"**{fmt(r[''], 2)}** " + fmt_interval(r["_lo"], r["_hi"]))
    rows.append(pap_row + [""] * (len(ps) + 7))
    for _, s in scores.iterrows():
        f = fits[fits["rule"] == s["rule"]].set_index("photons")
        row = [s["label"] + (" (fitted)" if s["fitted"] else "")]
        for p in ps:
            row.append(f"{fmt(f.loc[p, 'reps'], 3)} ({fmt(f.loc[p, 'reps_fraction'], 2)})" if p in f.index else "")
        for p in ps:
            if p in f.index:
                z = f.loc[p].get("z", math.nan)
                row.append(f"{fmt(f.loc[p, 'slope_ratio'], 2)} {fmt_interval(f.loc[p, 'slope_ratio_lo'], f.loc[p, 'slope_ratio_hi'])}"
                           + (f" z={z:+.1f}" if report.isnum(z) else ""))
            else:
                row.append("")
        for p in ps:
            row.append(f"{fmt(f.loc[p, 'slope_ratio_secondary'], 2)} "
                       f"{fmt_interval(f.loc[p, 'slope_ratio_secondary_lo'], f.loc[p, 'slope_ratio_secondary_hi'])}"
                       if p in f.index else "")
        row += [fmt(s["chi2"], 3), str(int(s["dof"])), fmt(s["p_value"], 2), fmt(s["p_holm"], 2), s["verdict"],
                f"{fmt(s['chi2_icpt'], 3)} ({fmt(s['p_icpt'], 2)})", fmt(s["shape_factor"], 3)]
        rows.append(row)
    out += report.md_table(hdr, rows, ["l"] + ["r"] * (len(hdr) - 1))
    m = rec["tested"]
    out += ["", f"chi^2 = sum of z^2 over the P_e; dof = the P_e compared, less one for a rule with a parameter "
            "fitted to the paper (marked fitted: a countN rule whose N was taken from the family fit below); p: "
            f"chi^2 probability; p (Holm): Holm's adjustment over the {m} rules tested. Verdict: incompatible "
            "(Holm p < 0.05: the rule's slopes are not the paper's) or not rejected (compatibility is not shown "
            "equality). Intercepts: the same for the intercept ratio a_prec / a_conv (secondary: it also depends on "
            "how the machine's ray tracing compares with its kNN queries; the paper's times include the photon "
            "trace and build, ours do not). Table shape: the typical factor between our precomputed/conventional "
            "time ratio and the paper's over the cells, exp(rms(log(ours / paper))) (1 = the same table shape).",
            ""]
    b, kept = rec["best"], rec["kept"]
    if b is not None:
        ties = rec.get("best_ties") or [b["label"]]
        least = (f"the least evidence against it (the largest Holm p): **{b['label']}** (chi^2 "
                 f"{fmt(b['chi2'], 3)} with {int(b['dof'])} dof, Holm p = {fmt(b['p_holm'], 2)})"
                 if len(ties) == 1 else
                 f"the largest Holm p, {fmt(b['p_holm'], 2)}, is shared by {len(ties)} rules "
                 f"({', '.join(ties)}), so none has less evidence against it than the others")
        out += [f"**Finding.** Rules not rejected against the paper's slope ratios after Holm over {m} rules: "
                f"{', '.join(kept) if kept else 'none'}; {least}; the rules not rejected are not ranked among "
                "themselves."
                + (f" Best table shape: {rec['best_shape'][0]} (x{fmt(rec['best_shape'][1], 3)})."
                   if rec["best_shape"] is not None else ""), ""]
        for a in rec["sensitivity"]:
            out += [f"Sensitivity to the assumption: with the paper's noise taken as {fmt(a['factor'], 2)} x sigma "
                    f"({fmt(a['noise'], 2)}), the rules not rejected after Holm are: "
                    f"{', '.join(a['kept']) if a['kept'] else 'none'}.", ""]
    out += ["## What the paper's slopes imply: the representatives per P_e", "",
            "Per P_e the precomputed slope grows linearly with the number of representatives R over our rules "
            "(b_prec = beta0 + beta1 R; fit over the rules with the separate tree). Solving for the paper's slope "
            "ratio gives the R its implementation would have had if its per-query costs were ours:", ""]
    rows = []
    for _, m in model.iterrows():
        rows.append([plotting.kilo(m["photons"]), fmt(m["stored"], 3), int(m["rules"]), fmt(m["beta1"] * 1e6, 3),
                     fmt(m["r2"], 3), fmt(m["needed_reps"], 2),
                     fmt_interval(max(m["needed_reps_lo"], 0) if report.isnum(m["needed_reps_lo"]) else math.nan,
                                  m["needed_reps_hi"], None),
                     fmt(m["needed_reps"] / m["stored"], 2)])
    out += report.md_table(["P_e", "stored photons", "rules", "beta1 (s per n per million reps)", "R^2",
                            "R implied by the paper", "95% interval", "R / stored"], rows)
    if len(families):
        out += ["", "Best parameter of each rule family (the slope ratios it predicts through the model above, "
                "against the paper's; chi^2 with the paper's standard errors, one parameter fitted):", ""]
        rows = [[f["family"], f"{f['parameter']} = {fmt(f['best'], 3)}", fmt(f["chi2"], 3), int(f["dof"]),
                 fmt(f["p_value"], 2), f["predicted"]] for _, f in families.iterrows()]
        out += report.md_table(["family", "best", "chi^2", "dof", "p", "predicted R and slope ratio per P_e"], rows,
                               ["l", "l", "r", "r", "r", "l"])
        out += ["", "A spacing radius d (a representative where none lies within d) gives R = min(stored, "
                "A/(c d^2)) for a lit area A: every photon while photons are sparse, a constant count once they "
                "are dense, i.e. the fixed-count family's shape."]
    out += ["", "## Cost model per rule", "",
            "a (s) of time (precompute + eye pass) = a + b n and b (s per unit n, from the kNN timer as above), "
            "least squares pooled over the seeds, with 95% t-intervals; intercept ratios precomputed / conventional with Fieller intervals (the "
            "paper's: normal, from its assumed errors). Conventional: the untagged grid.", ""]
    rows = []
    for _, f in fits.iterrows():
        rows.append([f["label"], plotting.kilo(f["photons"]), fmt(f["reps"], 3),
                     f"{fmt(f['a_prec'], 3)} ± {fmt(f['a_prec_half'], 2)}",
                     f"{fmt(f['b_prec'], 3)} ± {fmt(f['b_prec_half'], 2)}",
                     f"{fmt(f['a_conv'], 3)} ± {fmt(f['a_conv_half'], 2)}",
                     f"{fmt(f['b_conv'], 3)} ± {fmt(f['b_conv_half'], 2)}",
                     f"{fmt(f['icpt_ratio'], 3)} {fmt_interval(f['icpt_ratio_lo'], f['icpt_ratio_hi'])}",
                     f"{fmt(f.get('paper_icpt_ratio'), 3)} "
                     f"{fmt_interval(f.get('paper_icpt_ratio_lo'), f.get('paper_icpt_ratio_hi'))}"])
    out += report.md_table(["rule", "P_e", "reps", "a prec.", "b prec.", "a conv.", "b conv.",
                            "intercept ratio", "paper's intercept ratio"], rows, ["l"] + ["r"] * 8)
    out += ["", "## Time and error per cell", "",
            "Time: precompute + eye pass, median (min-max) over seeds (the cells CSV's `time_median_s` is "
            f"`{args.time}`, for the trade-off figure). Ratio: precomputed / conventional, the "
            "geometric mean of the per-seed ratios (same seed, same photon map), % [95% t interval over the "
            f"seeds]; `{args.time}` the same, secondary. relMSE against the reference and against the "
            "conventional image of the same seed: mean ± 95% t half-width over seeds.", ""]
    rows = []
    for _, c in cells.iterrows():
        rows.append([c["label"], plotting.kilo(c["photons"]), c["nn"], c["seeds"], fmt(c["reps"], 3),
                     report.fmt_range(c["phase_median_s"], c["phase_min_s"], c["phase_max_s"]),
                     report.fmt_ci(c["ratio_percent"], c["ratio_ci95_lo"], c["ratio_ci95_hi"], 0),
                     report.fmt_ci(c["ratio_secondary_percent"], c["ratio_secondary_ci95_lo"],
                                   c["ratio_secondary_ci95_hi"], 0),
                     fmt(c["paper_ratio_percent"], 3),
                     report.fmt_pm(c["relmse_ref_mean"], c["relmse_ref_ci95"]),
                     report.fmt_pm(c["relmse_conv_mean"], c["relmse_conv_ci95"])])
    out += report.md_table(["rule", "P_e", "n", "seeds", "reps", "time s (min-max)", "ratio %",
                            f"{args.time} ratio %", "paper %", "relMSE vs ref", "relMSE vs conv."], rows,
                           ["l"] + ["r"] * 10)
    return "\n".join(out) + "\n"


def caption(rec, base_runs, variant_paths, noise):
    """The figure's footer: its data, from REC (conclusions)."""
    return (f"Data: {base_runs} (default rule; conventional renders) and "
            + ", ".join(os.path.basename(p) for p in variant_paths)
            + f"; {rec['size']}, paper estimate, seeds "
            + " ".join(str(s) for s in rec["seeds"])
            + " (conventional), time = precompute + eye pass (renderer's timers); paper: "
            f"experiments/paper-table1.csv, each time one measurement with relative sd {fmt(noise, 2)}. "
            "Slope ratios: mean over seeds of per-seed ratios, 95% t intervals.")


def figure(res, rec, path, caption_text):
    """rep-study.png at PATH, drawn from RES (analyse) and REC (conclusions):
    (a) slope ratio per P_e against the paper's, (b) the representatives the
    paper implies against the two families, (c) the table's shape, (d) the
    accuracy against the number of representatives."""
    fits, cells, model, families = res["fits"], res["cells"], res["model"], res["families"]
    fig = plotting.plt.figure(figsize=(13, 10.2))
    gs = fig.add_gridspec(2, 2, left=0.07, right=0.985, top=0.95, bottom=0.14, hspace=0.3, wspace=0.22)
    rules = list(dict.fromkeys(fits["rule"]))
    colour = {r: plotting.RULE_COLOURS[i % len(plotting.RULE_COLOURS)] for i, r in enumerate(rules)}
    label = dict(zip(fits["rule"], fits["label"]))
    ps = sorted(set(fits["photons"]))
    xpos = {p: i for i, p in enumerate(ps)}

    ax = fig.add_subplot(gs[0, 0])
    width = 0.8 / (len(rules) + 1)
    for p in ps:
        r = rec["paper_ratio"][p]
        if report.isnum(r[""]):
            x = xpos[p] - 0.4 + width / 2
            lo, hi = r["_lo"], r["_hi"]
            ax.errorbar([x], [r[""]], yerr=[[r[""] - lo], [hi - r[""]]],
                        fmt="*", ms=11, color=plotting.PAPER_COLOUR, capsize=3, lw=1.5,
                        label="paper (Table 1)" if p == ps[0] else None)
    for i, rule in enumerate(rules):
        f = fits[fits["rule"] == rule]
        x = [xpos[p] - 0.4 + width * (i + 1.5) for p in f["photons"]]
        y = f["slope_ratio"].to_numpy()
        err = [y - f["slope_ratio_lo"].to_numpy(), f["slope_ratio_hi"].to_numpy() - y]
        ax.errorbar(x, y, yerr=err, fmt="o", ms=5, color=colour[rule], capsize=2, lw=1.2, label=label[rule])
    ax.axhline(0, color="#888888", lw=0.8)
    ax.set_xticks(range(len(ps)), [f"P_e = {plotting.kilo(p)}" for p in ps])
    ax.set_ylabel("slope ratio b_prec / b_conv (time = a + b n)")
    ax.set_title("(a) cost per unit n, precomputed / conventional\n(ours: 95% t over seeds; paper: assumed known noise)")
    ax.legend(ncol=2, loc="upper left")

    ax = fig.add_subplot(gs[0, 1])
    if len(model):
        st = model["stored"].to_numpy()
        bottom = st.min() / 10
        ax.errorbar(model["stored"], model["needed_reps"],
                    yerr=[model["needed_reps"] - np.maximum(model["needed_reps_lo"], bottom),
                          model["needed_reps_hi"] - model["needed_reps"]],
                    fmt="*", ms=11, color=plotting.PAPER_COLOUR, capsize=3, lw=1.5,
                    label="R the paper's slope ratio implies (95%; a bar to the\nbottom edge: the interval reaches 0)")
        grid = np.geomspace(st.min() / 1.5, st.max() * 1.5, 100)
        for k, ls in ((1, "-"), (2, "--"), (4, ":")):
            ax.plot(grid, grid / k, ls, color="#999999", lw=1,
                    label=f"fixed fraction 1/{k}" if k > 1 else "every photon (fraction 1)")
        for _, fam in families.iterrows():
            ys = [reps_of_family(fam, s) for s in grid]
            ax.plot(grid, ys, "-", lw=2, color="#c8341c" if fam["parameter"] == "f" else "#3c8d2f",
                    label=f"best {fam['family']}: {fam['parameter']} = {fmt(fam['best'], 2)} "
                          f"(chi^2 {fmt(fam['chi2'], 2)}, p {fmt(fam['p_value'], 2)})")
        last = model["stored"].max()
        for _, m in model.iterrows():
            right = m["stored"] == last  # the rightmost label goes left of its star, inside the axes
            ax.annotate(f"P_e={plotting.kilo(m['photons'])}", (m["stored"], max(m["needed_reps"], bottom)),
                        textcoords="offset points", xytext=(-8 if right else 8, -4), fontsize=8.5, weight="bold",
                        ha="right" if right else "left")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(bottom, st.max() * 6)
        ax.set_xlim(grid[0], grid[-1])
        plotting.log_ticks(ax.xaxis, *ax.get_xlim(), label=plotting.count_label)
        plotting.log_ticks(ax.yaxis, *ax.get_ylim(), label=plotting.count_label)
        ax.set_xlabel("stored photons")
        ax.set_ylabel("representatives R")
        ax.legend(loc="lower right", fontsize=7.5)
    ax.set_title("(b) representatives the paper's slopes imply, and two rule families")

    ax = fig.add_subplot(gs[1, 0])
    allp = sorted(set(cells["photons"]))
    for rule in rules:
        c = cells[cells["rule"] == rule]
        for p in allp:
            cp = c[c["photons"] == p]
            cp = cp.sort_values("paper_ratio_percent")
            ax.plot(cp["paper_ratio_percent"], cp["ratio_percent"] / cp["paper_ratio_percent"],
                    plotting.photon_marker(p, allp) + ":", color=colour[rule], ms=6, lw=0.6, alpha=0.9)
    # ours divided by the paper's: the diagonal of a plot of one against the
    # other becomes the line 1, and the rules' offsets from it stand apart
    ax.axhline(1, color="#555555", lw=1.2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(15, 140)
    plotting.log_ticks(ax.xaxis, *ax.get_xlim())
    lo, hi = ax.get_ylim()
    ax.yaxis.set_major_locator(plotting.matplotlib.ticker.FixedLocator(
        [v for v in (0.5, 0.6, 0.7, 0.8, 0.9, 1, 1.1, 1.25, 1.5, 2, 2.5, 3) if lo <= v <= hi]))
    ax.yaxis.set_major_formatter(plotting.matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(plotting.matplotlib.ticker.NullFormatter())
    ax.set_xlabel("paper: precomputed / conventional time, %")
    ax.set_ylabel("ours / the paper's (precomputed / conventional time)")
    handles = [plotting.plt.Line2D([], [], color=colour[r], lw=2, label=label[r]) for r in rules]
    handles += [plotting.plt.Line2D([], [], color="#555555", marker=plotting.photon_marker(p, allp), ls="",
                                    label=f"P_e = {plotting.kilo(p)}") for p in allp]
    ax.legend(handles=handles, ncol=2, loc="lower left", fontsize=7.5)
    ax.set_title("(c) every cell: our time ratio over the paper's (1: equal)")

    ax = fig.add_subplot(gs[1, 1])
    sep = cells[~cells["rule"].isin(rec["shared"])]
    ns = sorted(set(cells["nn"]))
    shown = [n for n in (ns[0], ns[-1])] if len(ns) > 1 else ns
    for p in allp:
        for n, ls in zip(shown, ("-", "--")):
            g = sep[(sep["photons"] == p) & (sep["nn"] == n)].sort_values("reps")
            ax.plot(g["reps"], g["relmse_conv_mean"], ls, color="#999999", lw=1, zorder=1)
            first = p == allp[0] and len(allp) > 1  # the smallest P_e labelled at its left end: no overlap
            k = 0 if first else -1
            ax.annotate(f"P_e={plotting.kilo(p)}, n={n}", (g["reps"].iloc[k], g["relmse_conv_mean"].iloc[k]),
                        textcoords="offset points", xytext=(-7 if first else 5, 0), fontsize=7.5, va="center",
                        ha="right" if first else "left")
            for _, c in g.iterrows():
                ax.errorbar([c["reps"]], [c["relmse_conv_mean"]], yerr=[[min(np.nan_to_num(c["relmse_conv_ci95"]),
                                                                              0.999 * c["relmse_conv_mean"])],
                                                                         [np.nan_to_num(c["relmse_conv_ci95"])]],
                            fmt=plotting.photon_marker(p, allp), color=colour[c["rule"]], ms=5, capsize=1.5, zorder=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    lo, hi = ax.get_xlim()
    ax.set_xlim(lo / 4, hi * 4)
    plotting.log_ticks(ax.xaxis, *ax.get_xlim(), label=plotting.count_label)
    ax.set_xlabel("representatives R (median over seeds)")
    ax.set_ylabel("relMSE of precomputed vs conventional image (same seed)")
    ax.set_title(f"(d) accuracy against the number of representatives\n(n = {shown[0]} solid, {shown[-1]} "
                 "dashed; colours, markers as in (c); shared tree left out)")
    plotting.footer(fig, caption_text)
    plotting.save(fig, path)


def main():
    """Command line: see the module docstring and experiments/rules/rep-study.smk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base-runs", required=True, help="runs.csv of the untagged grid")
    ap.add_argument("--variant", action="append", default=[], metavar="RULE=RUNS.csv",
                    help="a rule (everyK, countN, shared) and its runs-TAG.csv; repeatable")
    ap.add_argument("--paper", required=True)
    ap.add_argument("--time", default="cpu_s", choices=sorted(report.TIME_LABEL),
                    help="the secondary time column (the study itself is on precompute_s + render_s)")
    ap.add_argument("--fitted", action="append", default=None, metavar="RULE",
                    help="a rule with one parameter fitted to the paper (repeatable; default: every countN rule)")
    ap.add_argument("--out", required=True, help="output stem: STEM.md, STEM.csv, STEM-cells.csv")
    ap.add_argument("--figure", required=True)
    ap.add_argument("--bootstrap", type=int, default=2000, help="accepted, unused: the intervals are t intervals")
    ap.add_argument("--bootstrap-seed", type=int, default=1, help="accepted, unused")
    args = ap.parse_args()
    base = read_runs(args.base_runs)
    variants, paths = [], []
    for v in args.variant:
        if "=" not in v:
            report.die("repstudy.py", f"--variant {v}: expected RULE=RUNS.csv")
        name, path = v.split("=", 1)
        variants.append((parse_rule(name), read_runs(path), path))
        paths.append(path)
    paper = report.read_csv(args.paper, ["emitted_kphotons", "nn", "conventional_s", "proposed_s"], "repstudy.py",
                            comment="#")
    res = analyse(base, variants, paper, args.time, args.fitted)
    rec = conclusions(res)
    report.write_csv_atomic(res["fits"], args.out + ".csv", "%.6g")
    report.write_csv_atomic(res["scores"], args.out + "-rules.csv", "%.6g")
    report.write_csv_atomic(res["cells"], args.out + "-cells.csv", "%.6g")
    report.write_atomic(args.out + ".md", markdown(res, rec, args, args.base_runs, paths))
    figure(res, rec, args.figure, caption(rec, args.base_runs, paths, res["noise"]))
    print(f"wrote {args.out}.md, {args.out}.csv, {args.out}-rules.csv and {args.out}-cells.csv ({len(res['rules'])} rules)")


if __name__ == "__main__":
    main()
