"""Tests of experiments/analysis/beyond.py: the verdict of the goal per case,
the error ratio at equal cells, the pooled counters, and the refusal of a
variant whose renders are missing; each with a control that must flip."""

import json
import math
import os
import sys

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments.analysis import beyond  # noqa: E402


def table(rows):
    """A beyond table of (variant, speedup, lo, hi, best, vs_paper) rows of one case."""
    return pd.DataFrame([{"case": "c", "estimate": "paper", "variant": v, "speedup": s, "lo": lo, "hi": hi,
                          "best": b, "vs_paper": vp} for v, s, lo, hi, b, vp in rows])


def test_goal_holds_when_best_is_above_one_and_not_slower_than_paper():
    t = beyond.verdicts(table([("paper", 0.9, 0.8, 1.0, False, ""), ("lazy", 1.5, 1.2, 1.8, True, "higher"),
                               ("gated0.1", 1.1, 0.9, 1.3, False, "undetermined")]))
    assert list(t.loc[t["goal_met"], "variant"]) == ["lazy"]
    t = beyond.verdicts(table([("paper", 1.3, 1.1, 1.5, False, ""), ("lazy", 1.4, 1.2, 1.6, True, "undetermined")]))
    assert bool(t["goal_met"].iloc[1])


def test_goal_fails_when_interval_reaches_one_or_slower():
    # controls: the same best with its lower end at 0.95, or ranked slower than the paper's rule
    t = beyond.verdicts(table([("paper", 0.7, 0.6, 0.8, False, ""), ("lazy", 1.2, 0.95, 1.4, True, "higher")]))
    assert not bool(t["above_one"].iloc[1]) and not t["goal_met"].any()
    t = beyond.verdicts(table([("paper", 3.0, 2.5, 3.5, False, ""), ("lazy", 1.5, 1.2, 1.8, True, "lower")]))
    assert not t["goal_met"].any()


def test_no_best_no_goal():
    t = beyond.verdicts(table([("paper", 1.2, 1.1, 1.3, False, ""), ("lazy", 2.0, 1.5, 2.5, False, "higher")]))
    assert not t["goal_met"].any()


CELLS = [(50000, 10), (50000, 100), (100000, 10)]


def variant_runs(speed, err_shift, seeds, rng, sigma=0.05, errs=None):
    """A variant's runs.csv rows (precomputed grid renders, paper estimate):
    each (cell, seed) takes 1 / SPEED the time of a common per-cell base,
    with log-normal noise SIGMA (each render its own draw); its relMSE is
    ERRS[(cell, seed)] + ERR_SHIFT."""
    rows = []
    for (p, n) in CELLS:
        for s in range(1, seeds + 1):
            base = 1.0 + n / 100 + p / 100000
            rows.append({"role": "grid", "status": "ok", "estimate": "paper", "method": "precomputed", "photons": p,
                         "nn": n, "seed": s, "total_s": base / speed * math.exp(rng.normal(0, sigma)),
                         "relmse_ref": errs[(p, n, s)] + err_shift})
    return pd.DataFrame(rows)


def base_errors(seeds, rng):
    return {(p, n, s): 0.01 + 0.002 * rng.random() for (p, n) in CELLS for s in range(1, seeds + 1)}


def test_paired_best_only_when_ranked_above_all():
    """lazy is 30% faster than the paper's rule and 15% faster than gated:
    the paired tests rank it best; its relMSE, the paper's plus 0.0005 on
    every render, is ranked higher than the paper's (a positive control of
    the error test)."""
    rng = np.random.default_rng(1)
    errs = base_errors(5, rng)
    frames = {"paper": variant_runs(1.0, 0.0, 5, rng, errs=errs),
              "lazy": variant_runs(1.3, 0.0, 5, rng, errs={k: v + 1e-6 * rng.normal() for k, v in errs.items()}),
              "gated": variant_runs(1.13, 0.0005, 5, rng, errs=errs)}
    out = beyond.paired_tests(frames, "paper", "total_s")
    assert out["lazy"]["best"] and not out["gated"]["best"]
    assert out["lazy"]["vs_paper"] == "higher" and out["lazy"]["vs_paper_ratio_lo"] > 1.2
    assert out["gated"]["vs_paper_relmse_verdict"] == "higher"
    assert {n: out[n]["image_group"] for n in out} == {"paper": "paper", "lazy": "lazy", "gated": "gated"}


def test_noisy_equal_variants_get_no_best():
    """Negative control: three variants as fast as the paper's rule (the
    same true times, 5% noise per render), 5 seeds: over 50 draws no
    variant is ever called best (the family-wise error is held by Holm)."""
    rng = np.random.default_rng(2)
    bests = 0
    for _ in range(50):
        errs = base_errors(5, rng)
        frames = {"paper": variant_runs(1.0, 0.0, 5, rng, errs=errs)}
        for name in ("lazy", "gated0.1", "gated0.5"):
            frames[name] = variant_runs(1.0, 0.0, 5, rng, errs={k: v + 1e-6 * rng.normal() for k, v in errs.items()})
        out = beyond.paired_tests(frames, "paper", "total_s")
        bests += sum(bool(o["best"]) for o in out.values())
    assert bests <= 1, bests


def test_bit_identical_variants_are_one_row():
    """gated0.1, gated0.2 and gated0.5 give the same relMSE on every cell and
    seed (bit-identical images), with different noisy times: one image
    group, reported in the first's row, and counted once in the family;
    a variant that differs in one render's relMSE (control) is its own."""
    rng = np.random.default_rng(3)
    errs = base_errors(5, rng)
    other = dict(errs)
    other[(50000, 10, 3)] += 1e-7
    frames = {"paper": variant_runs(1.0, 0.0, 5, rng, errs=errs)}
    for name in ("gated0.1", "gated0.2", "gated0.5"):
        frames[name] = variant_runs(1.1, 0.001, 5, rng, errs=errs)
    frames["lazy"] = variant_runs(1.1, 0.001, 5, rng, errs=other)
    out = beyond.paired_tests(frames, "paper", "total_s")
    assert [out[n]["image_group"] for n in ("gated0.1", "gated0.2", "gated0.5", "lazy")] == \
        ["gated0.1", "gated0.1", "gated0.1", "lazy"]
    assert out["gated0.5"]["vs_paper_ratio"] == out["gated0.1"]["vs_paper_ratio"]
    assert not out["gated0.2"]["best"] and not out["gated0.5"]["best"]
    t = pd.DataFrame([{"case": "c", "estimate": "paper", "variant": n, **out[n]} for n in out])
    assert beyond.group_label(t, t.iloc[1]) == "gated0.1 = gated0.2 = gated0.5"
    assert beyond.group_label(t, t.iloc[4]) == "lazy"


def test_same_images_other_work_is_not_merged(tmp_path):
    """Where the stats have work counters: a variant with the paper's rule's
    images and work (a gate that changes nothing) is reported in the
    paper's row; one with the same images from other work (lazy
    evaluation) keeps its own row and its paired test."""
    rng = np.random.default_rng(4)
    errs = base_errors(5, rng)
    frames = {}
    for name, evaluated in (("paper", 900), ("gated0.1", 900), ("lazy", 300)):
        f = variant_runs(1.0 if evaluated == 900 else 1.3, 0.0, 5, rng, errs=errs)
        runs = []
        for i in range(len(f)):
            stem = str(tmp_path / f"{name}-{i}")
            with open(stem + ".stats.json", "w", encoding="utf-8") as fh:
                json.dump({"work": {"precompute": {"rep_evaluations": evaluated + i}}}, fh)
            runs.append(stem)
        frames[name] = f.assign(run=runs)
    out = beyond.paired_tests(frames, "paper", "total_s")
    assert [out[n]["image_group"] for n in ("paper", "gated0.1", "lazy")] == ["paper", "paper", "lazy"]
    assert out["lazy"]["vs_paper"] == "higher" and out["lazy"]["best"]
    assert out["gated0.1"]["vs_paper"] == "" and not out["gated0.1"]["best"]


def runs_frame(pre_err, conv_err):
    rows = []
    for seed, (pe, ce) in enumerate(zip(pre_err, conv_err), 1):
        base = {"estimate": "paper", "photons": 1000, "nn": 10, "seed": seed, "status": "ok"}
        rows.append({**base, "method": "precomputed", "role": "grid", "relmse_ref": pe})
        rows.append({**base, "method": "conventional", "role": "comparison", "relmse_ref": ce})
    return pd.DataFrame(rows)


def test_error_ratio_of_equal_images_is_one_and_doubles():
    assert beyond.error_ratio(runs_frame([0.1, 0.2], [0.1, 0.2]), "paper") == pytest.approx(1.0)
    assert beyond.error_ratio(runs_frame([0.2, 0.4], [0.1, 0.2]), "paper") == pytest.approx(2.0)


def test_counters_pool_over_renders(tmp_path):
    runs = []
    for i, (fb, smp, ev, reps) in enumerate([(10, 100, 5, 10), (30, 100, 10, 10)]):
        stem = str(tmp_path / f"r{i}")
        with open(stem + ".stats.json", "w", encoding="utf-8") as f:
            json.dump({"rep_fallbacks": fb, "samples": smp, "reps_evaluated": ev, "representatives": reps}, f)
        runs.append(stem)
    fb, ev = beyond.counters(pd.DataFrame({"run": runs}))
    assert fb == pytest.approx(0.2) and ev == pytest.approx(0.75)


def test_missing_render_is_refused(tmp_path):
    cols = {c: [0.0, 0.0] for c in beyond.NEED}
    f = pd.DataFrame(cols)
    f["role"], f["method"], f["estimate"], f["run"], f["size"] = "grid", "precomputed", "paper", "x", "8x6"
    f["status"] = ["ok", "missing"]
    p = tmp_path / "runs.csv"
    f.to_csv(p, index=False)
    with pytest.raises(SystemExit):
        beyond.measure("c", "cornell", "8x6", "lazy", "", str(p), "total_s", np.random.default_rng(1), 10)


def step_image(h=12, w=16, at=8, lo=0.2, hi=1.0):
    """An (H, W, 3) image: LO left of column AT, HI from it on (one vertical edge)."""
    img = np.full((h, w, 3), lo)
    img[:, at:, :] = hi
    return img


def test_edge_mask_marks_the_step_within_the_radius_only():
    m = beyond.edge_mask(step_image(), radius=2)
    # the step lies between columns 7 and 8: columns 5..10 are within 2 pixels
    assert m[:, 5:11].all() and not m[:, :5].any() and not m[:, 11:].any()


def test_edge_mask_of_a_flat_or_smooth_image_is_empty():
    # control: no step (flat), and a gentle ramp below EDGE_STEP per pixel
    assert not beyond.edge_mask(np.full((8, 8, 3), 0.5)).any()
    ramp = np.repeat(np.linspace(0.5, 0.6, 8)[None, :, None], 8, axis=0).repeat(3, axis=2)
    assert not beyond.edge_mask(ramp).any()


def test_error_map_mean_is_relmse():
    rng = np.random.default_rng(3)
    ref = rng.uniform(0.1, 1.0, (6, 5, 3))
    x = ref + rng.normal(0, 0.05, ref.shape)
    assert beyond.error_map(x, ref).mean() == pytest.approx(beyond.metrics.relmse(x, ref))


def test_error_location_puts_edge_error_on_edges_and_flat_error_off_them():
    ref = step_image()
    mask = beyond.edge_mask(ref, radius=2)
    on_edge = np.where(mask, 0.01, 0.0)
    mean, px, share = beyond.error_location(on_edge, mask)
    assert share == pytest.approx(1.0) and px == pytest.approx(6 / 16) and mean == pytest.approx(0.01 * 6 / 16)
    # control: the same excess on the flat pixels only has none on the edges
    _, _, share = beyond.error_location(np.where(mask, 0.0, 0.01), mask)
    assert share == pytest.approx(0.0)
    # uniform excess: the share equals the edge pixels' share
    _, px, share = beyond.error_location(np.full(mask.shape, 0.01), mask)
    assert share == pytest.approx(px)
    # no excess (the variant as good as the conventional renders): nothing to place
    _, _, share = beyond.error_location(np.full(mask.shape, -0.01), mask)
    assert math.isnan(share)


def test_case_references_name_each_reference_error(tmp_path):
    """Known answer: a case whose reference has a JSON gets its noise and
    bias on every row and the describe sentence checked against the
    case's tightest target (the smallest over its variants: 0.002, so 5.0%
    and 2.0%); control: a noisier reference is flagged; a case whose
    reference has no JSON (a POV-Ray render) gets empty columns and the
    sentence says its error is not measured, with no number."""
    from helpers import write_reference_json
    good, noisy, pov = (str(tmp_path / f"{n}.exr") for n in ("good", "noisy", "pov"))
    write_reference_json(good, 1e-4, 4e-5)
    write_reference_json(noisy, 5e-4, 4e-5)
    cases = {"a": ("cornell", "64x48", good), "b": ("box", "64x48", noisy), "c": ("cornell", "32x24", pov)}
    t = pd.DataFrame([{"case": c, "variant": v, "tightest": x} for c, v, x in
                      [("a", "paper", 0.004), ("a", "lazy", 0.002), ("a", "gated", math.nan),
                       ("b", "paper", 0.002), ("c", "paper", 0.003)]])
    refs = beyond.case_references(t, cases)
    assert refs["a"]["tightest"] == 0.002 and refs["c"]["tightest"] == 0.003
    assert "noise 5.0%, bias 2.0% of it" in refs["a"]["sentence"] and "WARNING" not in refs["a"]["sentence"]
    assert "its noise is 25%" in refs["b"]["sentence"] and "WARNING" in refs["b"]["sentence"]
    assert "not measured" in refs["c"]["sentence"] and "noise" not in refs["c"]["sentence"]
    t0 = pd.DataFrame({"case": ["a"], "variant": ["paper"], "tightest": [math.nan]})
    r0 = beyond.case_references(t0, {"a": cases["a"]})["a"]
    assert r0["tightest"] is None and "no tightest target to judge it by" in r0["sentence"].lower()
    t = beyond.add_references(t, refs)
    assert (t.loc[t["case"] == "a", "ref_noise"] == 1e-4).all() and (t.loc[t["case"] == "a", "ref_bias"] == 4e-5).all()
    assert t.loc[t["case"] == "c", ["ref_noise", "ref_bias"]].isna().all().all()
    md = "\n".join(beyond.references_md(refs, cases))
    assert md.startswith("## References") and md.count("\n- **") == 3
    assert f"- **c** (cornell at 32x24): Reference `{pov}`: its own error is not measured" in md


def test_case_references_refuse_a_broken_json(tmp_path, capsys):
    """A JSON beside a case's reference that is not JSON: bad input, exit 2 naming it."""
    exr = str(tmp_path / "r.exr")
    with open(str(tmp_path / "r.json"), "w") as f:
        f.write("[")
    with pytest.raises(SystemExit) as e:
        beyond.case_references(pd.DataFrame({"case": ["a"], "tightest": [0.01]}), {"a": ("s", "8x6", exr)})
    assert e.value.code == 2 and "r.json" in capsys.readouterr().err


def test_main_reports_the_references(tmp_path, monkeypatch):
    """End to end on a synthetic case per reference kind (EXRs, stats
    JSONs, runs.csv): beyond.csv has ref_noise and ref_bias per case (the
    JSON's, empty for the case whose reference has none) and beyond.md a
    References section checking each against its case's tightest target,
    the smallest `tightest` target of equal_error.analyse over its rows."""
    from experiments.analysis import equal_error, reference
    from helpers import write_reference_json
    rng = np.random.default_rng(3)
    ref_img = (0.4 + 0.2 * rng.random((6, 8, 3))).astype(np.float32)
    argv, runs_of = ["beyond.py"], {}
    for cid, with_json in (("conv", True), ("pov", False)):
        ref = str(tmp_path / f"{cid}.exr")
        reference.write_exr(ref_img, ref)
        if with_json:
            write_reference_json(ref, 2e-5, 1e-5)
        rows = []
        for (p, n) in CELLS:
            for s in (1, 2, 3):
                for m, speed in (("conventional", 1.0), ("precomputed", 1.5)):
                    run = str(tmp_path / f"{cid}-{m}-{p}-{n}-{s}")
                    err = (0.05 * n / p ** 0.5) * math.exp(0.05 * rng.normal())
                    reference.write_exr(ref_img + np.float32(math.sqrt(err * 0.2)), run + ".exr")
                    with open(run + ".stats.json", "w") as f:
                        json.dump({"samples": 100, "rep_fallbacks": 0, "representatives": 10, "reps_evaluated": 10}, f)
                    t = (1 + p / 50000 + n / 50) / speed * math.exp(0.02 * rng.normal())
                    rows.append({"role": "grid", "status": "ok", "estimate": "paper", "method": m, "photons": p,
                                 "nn": n, "seed": s, "relmse_ref": err, "precompute_s": 0.1, "render_s": t / 2,
                                 "total_s": t, "cpu_s": t, "run": run, "size": "8x6", "loadavg_1min": 1.0})
        csv = str(tmp_path / f"runs-{cid}.csv")
        pd.DataFrame(rows).to_csv(csv, index=False)
        runs_of[cid] = pd.DataFrame(rows)
        argv += ["--case", cid, "cornell", "8x6", ref, "--variant", cid, "paper", "", csv]
    out = str(tmp_path / "beyond")
    monkeypatch.setattr(sys, "argv", argv + ["--out", out, "--bootstrap", "100"])
    beyond.main()
    t = pd.read_csv(out + ".csv")
    assert list(t.columns[-2:]) == ["ref_noise", "ref_bias"]
    conv = t[t["case"] == "conv"]
    assert (conv["ref_noise"] == 2e-5).all() and (conv["ref_bias"] == 1e-5).all()
    assert t.loc[t["case"] == "pov", ["ref_noise", "ref_bias"]].isna().all().all()
    md = open(out + ".md").read()
    refs = md[md.index("## References"):]
    tight = equal_error.analyse(runs_of["conv"], "paper", "total_s", "auto", np.random.default_rng(1), 10)["tightest"]
    assert f"judges ({tight['target']:.3g})" in refs
    assert f"noise {2e-5 / tight['target']:.1%}" in refs
    assert "- **pov** (cornell at 8x6): Reference" in refs and "its own error is not measured" in refs
    assert "{args.bootstrap}" not in md and "interval of 100 bootstrap resamples" in md
