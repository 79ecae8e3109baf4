"""Tests of experiments/analysis/repstudy.py: the per-seed slope ratio on the
kNN phase timers, the paper's slopes with assumed known noise, the Welch
comparison, the chi^2 with a fitted rule's degrees of freedom, and Holm over
the rules; synthetic renders of known answer, with negative controls (a rule
whose slope differs must be rejected after Holm, one that matches must not)."""

import math
import os
import sys

import numpy as np
import pandas as pd
import pytest
from scipy import stats as sps

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments.analysis import metrics  # noqa: E402
from experiments.analysis import repstudy  # noqa: E402

PES = (50000, 100000, 500000)
NNS = (10, 20, 50, 100)
SEEDS = (1, 2, 3, 4, 5)
B_CONV = {50000: 0.024, 100000: 0.027, 500000: 0.023}  # s per unit n, conventional eye pass


def render_rows(method, slope_of, seeds=SEEDS, rep_every=4, rep_count=0, jitter=0.002, seed=7):
    """Synthetic runs rows: the kNN timer (precompute for precomputed, eye pass
    for conventional) = a + b n, with a small seeded jitter per render; the
    precomputed eye pass constant (plus jitter)."""
    rng = np.random.default_rng(seed)
    rows = []
    for p in PES:
        stored = 3.6 * p
        reps = min(rep_count, stored) if rep_count else stored / rep_every
        for s in seeds:
            for n in NNS:
                e = rng.normal(0, jitter, 2)
                knn = 0.05 + slope_of[p] * n + e[0]
                pre, ren = (knn, 1.25 + e[1]) if method == "precomputed" else (0.0, 1.2 + knn)
                rows.append({"method": method, "estimate": "paper", "photons": p, "nn": n, "seed": s, "status": "ok",
                             "role": "grid", "rep_every": rep_every, "rep_count": rep_count,
                             "representatives": reps if method == "precomputed" else 0, "photons_stored": stored,
                             "cpu_s": pre + ren + 0.3, "total_s": pre + ren + 0.1, metrics.PRIMARY_COLUMN: 0.02,
                             "relmse_conv": 0.001, "precompute_s": pre, "render_s": ren, "size": "1024x768",
                             "run": f"r/{method}/{p}/{n}/{s}"})
    return rows


def paper_table(ratio):
    """A Table 1 whose proposed slope is RATIO[p] x the conventional one, exact."""
    rows = []
    for p in PES:
        for n in NNS:
            c = 10 + 0.5 * n
            pr = 8 + ratio[p] * 0.5 * n
            rows.append({"emitted_kphotons": p / 1000, "nn": n, "conventional_s": c, "proposed_s": pr,
                         "ratio_percent": 100 * pr / c})
    return pd.DataFrame(rows)


def write(tmp_path, name, rows):
    path = os.path.join(str(tmp_path), name)
    pd.DataFrame(rows).to_csv(path, index=False)
    return repstudy.read_runs(path), path


PAPER_RATIO = {50000: 0.1, 100000: 0.1, 500000: 0.25}


def study(tmp_path, off=3.0, fitted=None):
    """Base grid (default rule every4 matching the paper), a matching variant
    every1 and a variant every8 whose slope ratio is OFF x the paper's."""
    conv = render_rows("conventional", B_CONV, seed=1)
    match = {p: PAPER_RATIO[p] * B_CONV[p] for p in PES}
    wrong = {p: off * PAPER_RATIO[p] * B_CONV[p] for p in PES}
    base, _ = write(tmp_path, "runs.csv", conv + render_rows("precomputed", match, rep_every=4, seed=2))
    v1, p1 = write(tmp_path, "v1.csv", render_rows("precomputed", match, rep_every=1, seed=3, seeds=(1, 2, 3)))
    v8, p8 = write(tmp_path, "v8.csv", render_rows("precomputed", wrong, rep_every=8, seed=4, seeds=(1, 2, 3)))
    variants = [(repstudy.parse_rule("every1"), v1, p1), (repstudy.parse_rule("every8"), v8, p8)]
    return repstudy.analyse(base, variants, paper_table(PAPER_RATIO), "cpu_s", fitted)


def test_seed_slope_ratio_exact_without_noise():
    conv = pd.DataFrame(render_rows("conventional", B_CONV, jitter=0.0))
    pre = pd.DataFrame(render_rows("precomputed", {p: 0.3 * B_CONV[p] for p in PES}, jitter=0.0))
    for f in (conv, pre):
        f[repstudy.SLOPE] = np.where(f["method"] == "precomputed", f["precompute_s"], f["precompute_s"] + f["render_s"])
    r = repstudy.seed_slope_ratio(pre[pre.photons == 50000], conv[conv.photons == 50000], repstudy.SLOPE)
    assert r["ratio"] == pytest.approx(0.3, rel=1e-9) and r["seeds"] == len(SEEDS)
    assert r["hi"] - r["lo"] == pytest.approx(0.0, abs=1e-9)


def test_seed_slope_ratio_t_interval_over_seeds():
    """Per-seed ratios 1, 2, 3 (one P_e): mean 2, half-width t_{0.975,2} x 1 / sqrt(3)."""
    rows = []
    for s, k in zip((1, 2, 3), (1.0, 2.0, 3.0)):
        for n in NNS:
            rows.append({"seed": s, "nn": n, "t": k * n, "m": "p"})
            rows.append({"seed": s, "nn": n, "t": float(n), "m": "c"})
    f = pd.DataFrame(rows)
    r = repstudy.seed_slope_ratio(f[f.m == "p"], f[f.m == "c"], "t")
    half = sps.t.ppf(0.975, 2) / math.sqrt(3)
    assert r["ratio"] == pytest.approx(2.0) and r["hi"] - 2.0 == pytest.approx(half)
    assert r["se"] == pytest.approx(1 / math.sqrt(3))


def test_wls_slope_exact_line_and_variance_by_monte_carlo():
    x = np.array(NNS, dtype=float)
    y = 3 + 0.5 * x
    a, sa, b, sb = repstudy.wls_slope(x, y, 0.05)
    assert a == pytest.approx(3) and b == pytest.approx(0.5)
    rng = np.random.default_rng(3)
    sims = [np.polyfit(x, y * (1 + 0.05 * rng.standard_normal(x.size)), 1)[0] for _ in range(20000)]
    assert np.std(sims) == pytest.approx(sb, rel=0.03)


def test_compare_with_paper_known_paper_error_is_welch():
    # the paper's error 0: nu = the seeds' dof, the test is the one-sample t test
    t, nu, p, z = repstudy.compare_with_paper(1.2, 0.1, 4, 1.0, 0.0)
    assert t == pytest.approx(2.0) and nu == pytest.approx(4) and p == pytest.approx(2 * sps.t.sf(2.0, 4))
    assert z == pytest.approx(sps.norm.isf(p / 2))
    # equal standard errors: nu = 4 x (sqrt 2)^4 = 16
    assert repstudy.compare_with_paper(1.0, 0.1, 4, 1.0, 0.1)[1] == pytest.approx(16)
    assert math.isnan(repstudy.compare_with_paper(1.0, 0.1, 0, 1.0, 0.1)[0])


def test_score_rules_fitted_dof_and_holm():
    s = repstudy.score_rules([{"zs": [0.5, -0.5, 0.5], "fitted": 0}, {"zs": [0.5, -0.5, 0.5], "fitted": 1},
                              {"zs": [4.0, 4.0, 4.0], "fitted": 0}, {"zs": [1.0], "fitted": 1}])
    assert [x["dof"] for x in s] == [3, 2, 3, 0]
    assert s[0]["p_value"] == pytest.approx(sps.chi2.sf(0.75, 3)) and s[1]["p_value"] == pytest.approx(sps.chi2.sf(0.75, 2))
    assert s[1]["p_value"] < s[0]["p_value"]  # a fitted parameter costs a degree of freedom
    assert s[3]["verdict"] == "no test" and math.isnan(s[3]["p_holm"])
    p3 = sps.chi2.sf(48.0, 3)  # smallest of three tested: Holm multiplies it by 3
    assert s[2]["p_holm"] == pytest.approx(3 * p3) and s[2]["verdict"] == "incompatible"
    assert s[0]["verdict"] == "not rejected"


def test_holm_turns_a_marginal_rule_to_not_rejected():
    """Control of the multiplicity correction: p = 0.03 alone rejects, among
    three tests with larger p Holm's adjusted 0.09 does not."""
    z = math.sqrt(sps.chi2.isf(0.03, 1))
    alone = repstudy.score_rules([{"zs": [z], "fitted": 0}])
    family = repstudy.score_rules([{"zs": [z], "fitted": 0}, {"zs": [0.1], "fitted": 0}, {"zs": [0.2], "fitted": 0}])
    assert alone[0]["verdict"] == "incompatible" and family[0]["verdict"] == "not rejected"
    assert family[0]["p_holm"] == pytest.approx(0.09)


def test_study_matching_rule_kept_differing_rule_rejected(tmp_path):
    res = study(tmp_path, off=3.0)
    sc = res["scores"].set_index("rule")
    assert sc.loc["every4", "verdict"] == "not rejected" and sc.loc["every1", "verdict"] == "not rejected"
    assert sc.loc["every8", "verdict"] == "incompatible" and sc.loc["every8", "p_holm"] < 0.05
    fits = res["fits"]
    m = fits[fits.rule == "every4"].set_index("photons")
    for p in PES:  # the slope ratio recovered from the precompute timer, the paper's exactly
        assert m.loc[p, "slope_ratio"] == pytest.approx(PAPER_RATIO[p], rel=0.05)
        assert m.loc[p, "paper_slope_ratio"] == pytest.approx(PAPER_RATIO[p], rel=1e-9)
        assert m.loc[p, "slope_ratio_lo"] <= m.loc[p, "slope_ratio_hi"]
        assert abs(m.loc[p, "b_eye_prec"]) < 1e-3  # the precomputed eye pass does not grow with n
    assert res["noise"] > 0 and (sc["dof"] == 3).all()


def test_study_control_equal_slopes_not_rejected(tmp_path):
    """Negative control of the rejection: the 'wrong' rule at the paper's slope."""
    sc = study(tmp_path, off=1.0)["scores"].set_index("rule")
    assert (sc["verdict"] == "not rejected").all()


def test_study_fitted_rule_loses_a_degree_of_freedom(tmp_path):
    sc = study(tmp_path, off=1.0, fitted=["every1"])["scores"].set_index("rule")
    assert sc.loc["every1", "dof"] == 2 and sc.loc["every1", "fitted"] == 1 and sc.loc["every4", "dof"] == 3


def test_markdown_numbers_and_rules_csv(tmp_path):
    res = study(tmp_path)

    class A:
        out = os.path.join(str(tmp_path), "rep-study")
        time = "cpu_s"
    md = repstudy.markdown(res, repstudy.conclusions(res), A, os.path.join(str(tmp_path), "runs.csv"),
                           ["v1.csv", "v8.csv"])
    assert "sigma = " in md and "Holm" in md and "nan" not in md.lower().split()
    assert "| every 8th |" in md and "incompatible" in md


def test_conclusions_record(tmp_path):
    """The record the report and the figure are written from: the rule that
    differs from the paper is the one left out of those not rejected, the
    rule with the largest Holm p is a matching rule, the paper's slope ratios are the ones
    the synthetic table was built with, and the sensitivity rows scale the
    noise; negative control: with every rule at the paper's slope none is
    left out."""
    res = study(tmp_path, off=3.0)
    rec = repstudy.conclusions(res)
    label = res["scores"].set_index("rule")["label"]
    assert rec["tested"] == 3 and rec["size"] == "1024x768" and rec["seeds"] == list(SEEDS)
    assert rec["kept"] == [label["every4"], label["every1"]] and rec["best"]["label"] in rec["kept"]
    assert rec["shared"] == [] and rec["best_shape"] is not None
    for p in PES:
        assert rec["paper_ratio"][p][""] == pytest.approx(PAPER_RATIO[p], rel=1e-9)
    assert [a["factor"] for a in rec["sensitivity"]] == [0.5, 2.0]
    assert rec["sensitivity"][1]["noise"] == pytest.approx(2 * res["noise"])
    assert rec["kept"] == [a for a in rec["sensitivity"][1]["kept"] if a in rec["kept"]]
    md = repstudy.markdown(res, {**rec, "kept": ["made-up rule"]}, type("A", (), {"out": "x", "time": "cpu_s"}),
                           "runs.csv", [])
    assert "after Holm over 3 rules: made-up rule;" in md  # the report words the record, it does not recount
    assert len(repstudy.conclusions(study(tmp_path, off=1.0))["kept"]) == 3


def test_markdown_names_no_least_rejected_rule_on_a_tie(tmp_path):
    """Holm caps p at 1, so rules can tie for the largest Holm p: the report
    then names no rule as the one with the least evidence against it; control:
    a rule alone at the largest p is named in bold."""
    res = study(tmp_path, off=3.0)
    rec = repstudy.conclusions(res)
    A = type("A", (), {"out": "x", "time": "cpu_s"})
    one = repstudy.markdown(res, {**rec, "best_ties": [rec["best"]["label"]]}, A, "runs.csv", [])
    assert f"(the largest Holm p): **{rec['best']['label']}**" in one
    tie = repstudy.markdown(res, {**rec, "best_ties": ["rule a", "rule b"]}, A, "runs.csv", [])
    assert "is shared by 2 rules (rule a, rule b), so none has less evidence" in tie
    assert "(the largest Holm p): **" not in tie
    assert rec["best"]["label"] in rec["best_ties"]


# the synthetic rules' slopes fall with R (every8 is the slow one), so the
# cost model implies no R and panel (b) has only nan points to draw
@pytest.mark.filterwarnings("ignore:All-NaN axis encountered:RuntimeWarning")
def test_figure_drawn_from_the_record(tmp_path):
    """The figure is drawn from analyse's and conclusions' records alone (a PNG
    comes out) and its footer is the caption made from the record."""
    res = study(tmp_path)
    rec = repstudy.conclusions(res)
    cap = repstudy.caption(rec, "runs.csv", ["a/v1.csv"], res["noise"])
    assert "v1.csv; 1024x768, paper estimate, seeds 1 2 3 4 5 (conventional)" in cap
    path = os.path.join(str(tmp_path), "rep-study.png")
    repstudy.figure(res, rec, path, cap)
    with open(path, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_noise_sensitivity_larger_noise_rejects_less(tmp_path):
    res = study(tmp_path, off=3.0)
    base = [x["verdict"] for x in repstudy.noise_sensitivity(res["fits"], res["scores"], 1.0)]
    assert base == list(res["scores"]["verdict"])  # factor 1 is the study itself
    wide = repstudy.noise_sensitivity(res["fits"], res["scores"], 1000.0)
    assert all(x["verdict"] == "not rejected" for x in wide)  # a paper known to nothing rejects nothing


def test_rules_csv_carries_the_sensitivity_verdicts(tmp_path):
    """The scores (rules CSV) carry, per SENSITIVITY factor, the verdicts
    noise_sensitivity gives at that factor, and conclusions' kept lists are
    read from them; control: a column changed by hand changes the list."""
    res = study(tmp_path, off=3.0)
    for f in repstudy.SENSITIVITY:
        col = repstudy.sensitivity_column(f)
        assert list(res["scores"][col]) == [x["verdict"] for x in
                                            repstudy.noise_sensitivity(res["fits"], res["scores"], f)]
    assert repstudy.sensitivity_column(0.5) == "verdict_noise_x0.5"
    col = repstudy.sensitivity_column(2.0)
    res["scores"][col] = "incompatible"
    assert repstudy.conclusions(res)["sensitivity"][1]["kept"] == []
