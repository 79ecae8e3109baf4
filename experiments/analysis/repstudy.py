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

Per (rule, P_e) the cost model time = a + b n is fitted by least squares
over every seed's render (stats.linear_fit), the same for the conventional
method and for the paper's Table 1 (one run per cell, so 2 degrees of
freedom). The comparable quantity is the slope ratio b_prec / b_conv: both
slopes are kNN work per unit of n (the precompute's queries at the
representatives, the eye pass's at the eye samples), so the machine's speed
cancels and what is left is how many queries the representatives cost
relative to the eye samples. Intervals: Fieller's (stats.fieller_ratio).
Agreement with the paper: z = (ours - paper) / sqrt(se_ours^2 + se_paper^2)
per P_e with delta-method standard errors (stats.ratio_se), chi^2 = sum z^2
over the P_e (p-value: chi^2 distribution, one degree of freedom per P_e).

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
               "paper_slope_ratio_se", "paper_icpt_ratio", "paper_icpt_ratio_lo", "paper_icpt_ratio_hi", "z", "z_icpt"]


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


def fit_by_photons(runs, time_col):
    """{photons: linear_fit of TIME_COL on nn} over RUNS."""
    return {int(p): stats.linear_fit(g["nn"], g[time_col]) for p, g in runs.groupby("photons")}


def paper_fits(paper):
    """{photons: (conventional fit, proposed fit)} of the paper's Table 1."""
    out = {}
    for k, g in paper.groupby("emitted_kphotons"):
        out[int(round(k * 1000))] = (stats.linear_fit(g["nn"], g["conventional_s"]),
                                     stats.linear_fit(g["nn"], g["proposed_s"]))
    return out


def ratio_of(fit_num, fit_den, key):
    """(ratio, lo, hi, se) of coefficient KEY ('a' or 'b') of two fits:
    Fieller's interval with the smaller of the two fits' degrees of freedom,
    the delta-method standard error."""
    se = "se_" + key
    dof = min(fit_num["dof"], fit_den["dof"])
    r, lo, hi = stats.fieller_ratio(fit_num[key], fit_num[se], fit_den[key], fit_den[se], dof)
    return r, lo, hi, stats.ratio_se(fit_num[key], fit_num[se], fit_den[key], fit_den[se])


def analyse(base, variants, paper, time_col, rng, replicates):
    """The study: a dict with 'rules' (list), 'fits' (DataFrame, one row per
    rule and P_e), 'cells' (one row per rule, P_e, n), 'scores' (one row per
    rule), 'model' (one row per P_e), 'families' (one row per family)."""
    conv = base[(base["method"] == "conventional") & (base["estimate"] == "paper") & (base["role"] == "grid")
                & (base["status"] == "ok")]
    if conv.empty:
        report.die("repstudy.py", "the base grid has no ok conventional render of the paper estimate")
    conv_fit = fit_by_photons(conv, time_col)
    pfits = paper_fits(paper)
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
    fits, cells, scores = [], [], []
    for rule, pre in rules:
        pre_fit = fit_by_photons(pre, time_col)
        zs, zi, logs = [], [], []
        for p in sorted(pre_fit):
            if p not in conv_fit:
                continue
            f, c = pre_fit[p], conv_fit[p]
            g = pre[pre["photons"] == p]
            row = {"rule": rule["name"], "label": rule["label"], "kind": rule["kind"], "photons": p,
                   "stored": float(np.median(g["photons_stored"])), "reps": float(np.median(g["representatives"])),
                   "seeds": int(g["seed"].nunique()), "points": f["points"],
                   "b_prec": f["b"], "b_prec_half": f["half_b"], "a_prec": f["a"], "a_prec_half": f["half_a"],
                   "b_conv": c["b"], "b_conv_half": c["half_b"], "a_conv": c["a"], "a_conv_half": c["half_a"]}
            row["reps_fraction"] = row["reps"] / row["stored"] if row["stored"] > 0 else math.nan
            row["slope_ratio"], row["slope_ratio_lo"], row["slope_ratio_hi"], se_o = ratio_of(f, c, "b")
            row["icpt_ratio"], row["icpt_ratio_lo"], row["icpt_ratio_hi"], _ = ratio_of(f, c, "a")
            row["slope_ratio_se"] = se_o
            pr = pfits.get(p)
            if pr:
                pc, pp = pr
                (row["paper_slope_ratio"], row["paper_slope_ratio_lo"], row["paper_slope_ratio_hi"],
                 se_p) = ratio_of(pp, pc, "b")
                (row["paper_icpt_ratio"], row["paper_icpt_ratio_lo"], row["paper_icpt_ratio_hi"], _) = \
                    ratio_of(pp, pc, "a")
                row["paper_slope_ratio_se"] = se_p
                row["z"] = (row["slope_ratio"] - row["paper_slope_ratio"]) / math.hypot(se_o, se_p)
                zs.append(row["z"])
                se_ia = stats.ratio_se(f["a"], f["se_a"], c["a"], c["se_a"])
                se_ip = stats.ratio_se(pp["a"], pp["se_a"], pc["a"], pc["se_a"])
                row["z_icpt"] = (row["icpt_ratio"] - row["paper_icpt_ratio"]) / math.hypot(se_ia, se_ip)
                zi.append(row["z_icpt"])
            fits.append(row)
            for n, gn in g.groupby("nn"):
                cn = conv[(conv["photons"] == p) & (conv["nn"] == n)]
                ratio, lo, hi = stats.median_ratio(gn[time_col].to_numpy(float), cn[time_col].to_numpy(float),
                                                   rng, replicates)
                em, eh = stats.t_interval(gn[metrics.PRIMARY_COLUMN])
                cm, ch = stats.t_interval(gn["relmse_conv"])
                tm, tlo, thi = stats.median_range(gn[time_col])
                pap = paper[(paper["emitted_kphotons"] * 1000 == p) & (paper["nn"] == n)]
                paper_ratio = float(pap["ratio_percent"].iloc[0]) if len(pap) else math.nan
                cells.append({"rule": rule["name"], "label": rule["label"], "photons": p, "nn": int(n),
                              "seeds": int(len(gn)), "reps": float(np.median(gn["representatives"])),
                              "time_median_s": tm, "time_min_s": tlo, "time_max_s": thi,
                              "precompute_median_s": float(np.median(gn["precompute_s"])),
                              "render_median_s": float(np.median(gn["render_s"])),
                              "ratio_percent": 100 * ratio, "ratio_ci95_lo": 100 * lo, "ratio_ci95_hi": 100 * hi,
                              "paper_ratio_percent": paper_ratio,
                              "relmse_ref_mean": em, "relmse_ref_ci95": eh,
                              "relmse_conv_mean": cm, "relmse_conv_ci95": ch})
                if math.isfinite(paper_ratio) and ratio > 0:
                    logs.append(math.log(100 * ratio / paper_ratio))
        chi2 = float(np.sum(np.square(zs))) if zs else math.nan
        scores.append({"rule": rule["name"], "label": rule["label"], "kind": rule["kind"], "pe_compared": len(zs),
                       "chi2": chi2, "p_value": float(sps.chi2.sf(chi2, len(zs))) if zs else math.nan,
                       "max_abs_z": float(np.max(np.abs(zs))) if zs else math.nan,
                       "chi2_icpt": float(np.sum(np.square(zi))) if zi else math.nan,
                       "p_icpt": float(sps.chi2.sf(float(np.sum(np.square(zi))), len(zi))) if zi else math.nan,
                       "shape_factor": math.exp(math.sqrt(np.mean(np.square(logs)))) if logs else math.nan,
                       "shape_cells": len(logs)})
    fits = pd.DataFrame(fits).reindex(columns=FIT_COLUMNS)
    cells, scores = pd.DataFrame(cells), pd.DataFrame(scores)
    model = cost_model(fits)
    families = family_fits(model)
    return {"rules": [r for r, _ in rules], "fits": fits, "cells": cells, "scores": scores, "model": model,
            "families": families, "conv": conv}


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


def markdown(res, args, base_path, variant_paths):
    """The Markdown report."""
    fits, cells, scores, model, families = res["fits"], res["cells"], res["scores"], res["model"], res["families"]
    conv = res["conv"]
    size = conv["size"].iloc[0]
    seeds = " ".join(str(s) for s in sorted(set(conv["seed"])))
    out = ["# The representative study", "",
           f"Generated by `make rep-study` on {report.today()}. Data: [`{os.path.basename(base_path)}`]"
           f"({os.path.relpath(base_path, os.path.dirname(args.out) or '.')}) (the untagged grid: the default rule "
           "and the conventional renders every rule is compared with) and "
           + ", ".join(f"`{os.path.basename(p)}`" for p in variant_paths) + " (one per rule); "
           f"size {size}, paper estimate, conventional seeds {seeds}; time = `{args.time}` "
           f"({'CPU seconds of the process' if args.time == 'cpu_s' else 'wall-clock seconds'}). "
           f"This report's numbers: [`{os.path.basename(args.out)}.csv`]({os.path.basename(args.out)}.csv) "
           f"(fits), [`{os.path.basename(args.out)}-cells.csv`]({os.path.basename(args.out)}-cells.csv) (cells); "
           "figure: `figures/rep-study.png`.", "",
           f"- Machine: {report.machine()}; load average now {report.loadavg_now()}; commit {report.commit()}.",
           "- Paper: Table 1 (`experiments/paper-table1.csv`), one run per cell; its fits have 2 degrees of "
           "freedom, so its slopes are uncertain (the 95% intervals below).", ""]
    if size != "1024x768":
        out += [f"**Note:** these renders are {size}, the paper's 1024x768. The conventional slope scales with "
                "the eye samples and the precomputed one does not, so slope ratios are not comparable with the "
                "paper's at this size.", ""]
    out += ["## Which rule reproduces the paper's cost pattern", "",
            "The cost model time = a + b n, fitted per P_e (least squares over every seed's render). The slope "
            "ratio b_prec / b_conv is the comparable quantity: both slopes are kNN work per unit of n, at the "
            "representatives (precompute) and at the eye samples (eye pass), so the machine cancels. "
            "[lo, hi]: 95% Fieller interval. z: (ours - paper) / combined standard error (delta method).", ""]
    ps = sorted(set(fits["photons"]))
    hdr = ["rule"] + [f"P_e={plotting.kilo(p)}: reps (fraction)" for p in ps] + \
          [f"slope ratio {plotting.kilo(p)} [95% CI]" for p in ps] + ["chi^2 (p)", "intercepts: chi^2 (p)",
                                                                      "table shape (x)"]
    rows = []
    pap_row = ["**paper**"] + ["not stated" for _ in ps]
    first = fits.drop_duplicates("photons").set_index("photons")
    for p in ps:
        r = first.loc[p]
        pap_row.append(f"**{fmt(r.get('paper_slope_ratio'), 2)}** "
                       + fmt_interval(r.get("paper_slope_ratio_lo"), r.get("paper_slope_ratio_hi")))
    rows.append(pap_row + ["", "", ""])
    for _, s in scores.iterrows():
        f = fits[fits["rule"] == s["rule"]].set_index("photons")
        row = [s["label"]]
        for p in ps:
            row.append(f"{fmt(f.loc[p, 'reps'], 3)} ({fmt(f.loc[p, 'reps_fraction'], 2)})" if p in f.index else "")
        for p in ps:
            if p in f.index:
                z = f.loc[p].get("z", math.nan)
                row.append(f"{fmt(f.loc[p, 'slope_ratio'], 2)} {fmt_interval(f.loc[p, 'slope_ratio_lo'], f.loc[p, 'slope_ratio_hi'])}"
                           + (f" z={z:+.1f}" if report.isnum(z) else ""))
            else:
                row.append("")
        row.append(f"{fmt(s['chi2'], 3)} ({fmt(s['p_value'], 2)})")
        row.append(f"{fmt(s['chi2_icpt'], 3)} ({fmt(s['p_icpt'], 2)})")
        row.append(fmt(s["shape_factor"], 3))
        rows.append(row)
    out += report.md_table(hdr, rows, ["l"] + ["r"] * (len(hdr) - 1))
    out += ["", "chi^2 = sum of z^2 over the P_e (p: its chi^2 probability with one degree of freedom per P_e; "
            "p < 0.05 means the rule's slopes are not compatible with the paper's). Intercepts: the same for the "
            "intercept ratio a_prec / a_conv (secondary: it also depends on how the machine's ray tracing compares "
            "with its kNN queries). Table shape: the typical "
            "factor between our precomputed/conventional time ratio and the paper's over the cells, "
            "exp(rms(log(ours / paper))) (1 = the same table shape).", ""]
    best = scores.dropna(subset=["chi2"]).sort_values("chi2")
    if len(best):
        b = best.iloc[0]
        compatible = best[best["p_value"] >= 0.05]["label"].tolist()
        out += [f"**Finding.** Of the rules run, **{b['label']}** matches the paper's slope ratios best "
                f"(chi^2 {fmt(b['chi2'], 3)}, p = {fmt(b['p_value'], 2)}). Rules compatible with the paper at the "
                f"5% level: {', '.join(compatible) if compatible else 'none'}. "
                "Best table shape: " + (lambda r: f"{r['label']} (x{fmt(r['shape_factor'], 3)})")(
                    scores.dropna(subset=["shape_factor"]).sort_values("shape_factor").iloc[0]) + ". "
                "(A countN rule whose N was taken from the family fit below has one parameter fitted to the "
                "paper's slopes: judge its chi^2 with one degree of freedom fewer.)", ""]
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
            f"a (s) and b (s per unit n) of time = a + b n with 95% t-intervals; ratios precomputed / conventional "
            f"with Fieller intervals. Conventional: the untagged grid.", ""]
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
            "Time ratio: median precomputed / median conventional time, % [95% bootstrap interval]; relMSE "
            "against the reference and against the conventional image of the same seed: mean ± 95% t half-width "
            "over seeds.", ""]
    rows = []
    for _, c in cells.iterrows():
        rows.append([c["label"], plotting.kilo(c["photons"]), c["nn"], c["seeds"], fmt(c["reps"], 3),
                     report.fmt_range(c["time_median_s"], c["time_min_s"], c["time_max_s"]),
                     report.fmt_ci(c["ratio_percent"], c["ratio_ci95_lo"], c["ratio_ci95_hi"], 0),
                     fmt(c["paper_ratio_percent"], 3),
                     report.fmt_pm(c["relmse_ref_mean"], c["relmse_ref_ci95"]),
                     report.fmt_pm(c["relmse_conv_mean"], c["relmse_conv_ci95"])])
    out += report.md_table(["rule", "P_e", "n", "seeds", "reps", "time s (min-max)", "ratio %", "paper %",
                            "relMSE vs ref", "relMSE vs conv."], rows, ["l"] + ["r"] * 9)
    return "\n".join(out) + "\n"


def figure(res, args, caption):
    """rep-study.png: (a) slope ratio per P_e against the paper's, (b) the
    representatives the paper implies against the two families, (c) the
    table's shape, (d) the accuracy against the number of representatives."""
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
    first = fits.drop_duplicates("photons").set_index("photons")
    for p in ps:
        r = first.loc[p]
        if report.isnum(r.get("paper_slope_ratio")):
            x = xpos[p] - 0.4 + width / 2
            lo, hi = r["paper_slope_ratio_lo"], r["paper_slope_ratio_hi"]
            ax.errorbar([x], [r["paper_slope_ratio"]], yerr=[[r["paper_slope_ratio"] - lo], [hi - r["paper_slope_ratio"]]],
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
    ax.set_title("(a) cost per unit n, precomputed / conventional, 95% Fieller intervals")
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
    sep = cells[~cells["rule"].isin([r for r in rules if fits.loc[fits["rule"] == r, "kind"].iloc[0] == "shared"])]
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
    plotting.footer(fig, caption)
    plotting.save(fig, args.figure)


def main():
    """Command line: see the module docstring and experiments/repstudy.mk."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base-runs", required=True, help="runs.csv of the untagged grid")
    ap.add_argument("--variant", action="append", default=[], metavar="RULE=RUNS.csv",
                    help="a rule (everyK, countN, shared) and its runs-TAG.csv; repeatable")
    ap.add_argument("--paper", required=True)
    ap.add_argument("--time", default="cpu_s", choices=sorted(report.TIME_LABEL))
    ap.add_argument("--out", required=True, help="output stem: STEM.md, STEM.csv, STEM-cells.csv")
    ap.add_argument("--figure", required=True)
    ap.add_argument("--bootstrap", type=int, default=2000)
    ap.add_argument("--bootstrap-seed", type=int, default=1)
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
    res = analyse(base, variants, paper, args.time, np.random.default_rng(args.bootstrap_seed), args.bootstrap)
    report.write_csv_atomic(res["fits"], args.out + ".csv", "%.6g")
    report.write_csv_atomic(res["cells"], args.out + "-cells.csv", "%.6g")
    report.write_atomic(args.out + ".md", markdown(res, args, args.base_runs, paths))
    conv = res["conv"]
    caption = (f"Data: {args.base_runs} (default rule; conventional renders) and "
               + ", ".join(os.path.basename(p) for p in paths)
               + f"; {conv['size'].iloc[0]}, paper estimate, seeds "
               + " ".join(str(s) for s in sorted(set(conv["seed"])))
               + f" (conventional), time = {args.time}; paper: experiments/paper-table1.csv. "
               "Fits: least squares over every seed's render; slope-ratio intervals: Fieller, 95%.")
    figure(res, args, caption)
    print(f"wrote {args.out}.md, {args.out}.csv and {args.out}-cells.csv ({len(res['rules'])} rules)")


if __name__ == "__main__":
    main()
