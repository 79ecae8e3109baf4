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
    """A beyond table of (variant, speedup, lo, hi) rows of one case."""
    return pd.DataFrame([{"case": "c", "estimate": "paper", "variant": v, "speedup": s, "lo": lo, "hi": hi}
                         for v, s, lo, hi in rows])


def test_goal_holds_when_best_is_above_one_and_above_paper():
    t = beyond.verdicts(table([("paper", 0.9, 0.8, 1.0), ("lazy", 1.5, 1.2, 1.8), ("gated0.1", 1.1, 0.9, 1.3)]))
    best = t[t["best"]]
    assert list(best["variant"]) == ["lazy"]
    assert best["vs_paper"].iloc[0] == "higher" and bool(best["goal_met"].iloc[0])


def test_overlap_with_paper_is_not_below_and_counts():
    t = beyond.verdicts(table([("paper", 1.3, 1.1, 1.5), ("lazy", 1.4, 1.2, 1.6)]))
    b = t[t["best"]].iloc[0]
    assert b["vs_paper"] == "overlap" and bool(b["goal_met"])


def test_goal_fails_when_interval_reaches_one():
    # control: the same best with its lower end at 0.95 no longer holds
    t = beyond.verdicts(table([("paper", 0.7, 0.6, 0.8), ("lazy", 1.2, 0.95, 1.4)]))
    b = t[t["best"]].iloc[0]
    assert not bool(b["above_one"]) and not bool(b["goal_met"])


def test_goal_fails_below_paper():
    t = beyond.verdicts(table([("paper", 3.0, 2.5, 3.5), ("lazy", 1.5, 1.2, 1.8)]))
    b = t[t["best"]].iloc[0]
    assert b["vs_paper"] == "lower" and not bool(b["goal_met"])


def test_no_defined_variant_has_no_best():
    t = beyond.verdicts(table([("paper", 1.2, 1.1, 1.3), ("lazy", math.nan, math.nan, math.nan)]))
    assert not t["best"].any()


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
