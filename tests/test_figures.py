"""Tests of experiments/analysis/figures.py's record functions: what each
figure shows, computed from synthetic tables, runs and images of known
answer (the images handed in through read_image, the camera through a
stand-in projection), each checked against a value computed another way
(by hand, brute force, or metrics.py's own relMSE), with negative controls.
The drawing functions are exercised end to end by tests/figures.test.sh.

Run by pytest from the repository root (`python3 -m pytest tests/`).
"""

import argparse
import json
import math
import os

import numpy as np
import pandas as pd
import pytest
from scipy import stats as sps

from experiments.analysis import figures
from experiments.analysis import metrics
from experiments.analysis import scene_info

PES = (1000, 2000)
NNS = (10, 20)
SEEDS = (1, 2, 3)


def base_time(method, p, n):
    """The synthetic mean render time of a cell: grows with P_e and n, the
    precomputed method faster."""
    return (1.0 if method == "conventional" else 0.6) * (1 + p / 1000) * (1 + n / 10)


def error_of(method, p, n):
    """The synthetic mean relMSE of a cell: falls with P_e, rises with n."""
    return (0.02 if method == "conventional" else 0.03) * (1000 / p) * (n / 10)


def table_frame():
    """A table1.csv with the columns the figures read: both methods, every cell."""
    rows = []
    for p in PES:
        for n in NNS:
            for m in ("conventional", "precomputed"):
                r = {"photons": p, "nn": n, "method": m, "seeds": len(SEEDS), "width": 64, "height": 48,
                     "subpixels": 1, "relmse_ref_mean": error_of(m, p, n), "relmse_ref_ci95": 0.001,
                     "relmse_conv_mean": 0.01, "relmse_conv_ci95": 0.002, "paper_ratio_percent": math.nan}
                if m == "precomputed":
                    r.update(ratio_percent=60.0, ratio_ci95_lo=50.0, ratio_ci95_hi=70.0,
                             paired_ratio_percent=61.0, paired_ratio_ci95_lo=55.0, paired_ratio_ci95_hi=67.0 + n,
                             cpu_ratio_percent=62.0, cpu_ratio_ci95_lo=52.0, cpu_ratio_ci95_hi=72.0,
                             paper_ratio_percent=150.0 if (p, n) == (2000, 20) else 80.0)
                rows.append(r)
    return pd.DataFrame(rows)


def runs_frame():
    """runs.csv rows: three seeds per cell and method, times base + 0.1 s,
    0.2 s, 0.3 s (mean base + 0.2, sd 0.1); every phase 1 s, CPU half the wall clock."""
    rows = []
    for p in PES:
        for n in NNS:
            for m in ("conventional", "precomputed"):
                for s in SEEDS:
                    t = base_time(m, p, n) + 0.1 * s
                    rows.append({"method": m, "estimate": "paper", "photons": p, "nn": n, "seed": s, "status": "ok",
                                 "role": "grid", "run": f"runs/{m}-{p}-{n}-{s}", "loadavg_1min": 1.0 + s,
                                 "cpu_s": t / 2, "total_s": t, "trace_s": 1.0 * s, "build_s": 2.0,
                                 "precompute_s": 3.0 if m == "precomputed" else 0.0, "render_s": 4.0})
    return pd.DataFrame(rows)


def make_args(tmp_path, **kw):
    """The namespace main() gives the figure functions."""
    a = argparse.Namespace(table="table1.csv", runs="runs.csv", ref="ref.exr", ref_label="the reference",
                           time="total_s", rep_study_cells="", out=str(tmp_path), cells="1000:10 2000:20",
                           paper_cells=1, seed=1, crop="32x24+10+10", crop_at="64x48", error_block=2,
                           fig2_run=os.path.join(str(tmp_path), "fig2"), fig2_plane="z",
                           fig2_window="-0.4 0.2 1.0 1.45", normal_cos=0.9, scene="x.scene", pm="pm")
    a.table_frame, a.runs_frame = table_frame(), runs_frame()
    for k, v in kw.items():
        setattr(a, k, v)
    return a


def test_tradeoff_record(tmp_path):
    """Each line's points are the cells' mean times (runs.csv, t interval
    over the seeds) against their mean relMSE in order of n; the front is
    the brute-force Pareto front of the method's points; the axes span the
    means; a cell without its mean error is left out (negative control)."""
    args = make_args(tmp_path)
    rec = figures.tradeoff_record(args)
    assert [p["estimate"] for p in rec["panels"]] == ["paper"] and rec["rules"] is None
    half = sps.t.ppf(0.975, len(SEEDS) - 1) * 0.1 / math.sqrt(len(SEEDS))
    for m in rec["panels"][0]["methods"]:
        for p, pts in m["lines"]:
            want = [base_time(m["method"], p, n) + 0.2 for n in NNS]
            assert np.allclose(pts["x"], want) and np.allclose(pts["xh"], half)
            assert np.allclose(pts["y"], [error_of(m["method"], p, n) for n in NNS])
        x, y = np.array(m["front_x"]), np.array(m["front_y"])
        brute = {i for i in range(len(x)) if not any((x[j] <= x[i]) & (y[j] < y[i]) or (x[j] < x[i]) & (y[j] <= y[i])
                                                     for j in range(len(x)))}
        assert set(m["front"]) == brute and brute
    times = [base_time(m, p, n) + 0.2 for m in ("conventional", "precomputed") for p in PES for n in NNS]
    assert rec["xlim"] == pytest.approx((min(times) / 1.3, max(times) * 1.3))
    errs = [error_of(m, p, n) for m in ("conventional", "precomputed") for p in PES for n in NNS]
    assert rec["ylim"] == pytest.approx((min(errs) / 1.6, max(errs) * 1.6))
    assert "No rep-study data" in rec["footer"]
    t = args.table_frame
    t.loc[(t["method"] == "conventional") & (t["photons"] == 1000) & (t["nn"] == 20), "relmse_ref_mean"] = math.nan
    rec = figures.tradeoff_record(args)
    assert len(rec["panels"][0]["methods"][0]["lines"][0][1]["x"]) == 1


def test_tradeoff_record_rules(tmp_path):
    """The rep-study panel: the largest P_e the rules share with the grid,
    each rule's points at it in order of n, with min-max time bars."""
    path = os.path.join(str(tmp_path), "rep-study-cells.csv")
    pd.DataFrame([{"rule": r, "label": r.upper(), "photons": p, "nn": n, "time_median_s": 1.0 + k + n / 100,
                   "time_min_s": 0.9 + k, "time_max_s": 1.5 + k, "relmse_ref_mean": 0.01, "relmse_ref_ci95": 0.001}
                  for k, r in enumerate(("every1", "every8")) for p in (2000, 9000) for n in (20, 10)]).to_csv(
        path, index=False)
    rec = figures.tradeoff_record(make_args(tmp_path, rep_study_cells=path))
    r = rec["rules"]
    assert r["photons"] == 2000 and [x["label"] for x in r["lines"]] == ["EVERY1", "EVERY8"]
    assert np.allclose(r["lines"][1]["x"], [2.1, 2.2]) and np.allclose(r["lines"][1]["lo"], [0.2, 0.3])
    assert np.allclose(r["conventional"]["x"], [base_time("conventional", 2000, n) + 0.2 for n in NNS])


def test_ratio_vs_n_record(tmp_path):
    """The paired ratio where the table has it (its interval as the error
    bar), else the ratio of medians; the y range covers 100, every upper end
    and the paper's values."""
    rec = figures.ratio_vs_n_record(make_args(tmp_path))
    assert rec["paired"] and not rec["cpu"] and [p["photons"] for p in rec["panels"]] == list(PES)
    o = rec["panels"][0]["ours"][0]
    assert o["estimate"] == "paper" and np.allclose(o["y"], 61) and np.allclose(o["err"], [[6, 6], [16, 26]])
    assert rec["ymax"] == 150.0 and rec["panels"][1]["paper"][1].tolist() == [80.0, 150.0]
    t = table_frame().drop(columns=["paired_ratio_percent", "paired_ratio_ci95_lo", "paired_ratio_ci95_hi"])
    t.loc[t["photons"] == 2000, "paper_ratio_percent"] = math.nan
    rec = figures.ratio_vs_n_record(make_args(tmp_path, table_frame=t))
    assert not rec["paired"] and np.allclose(rec["panels"][0]["ours"][0]["y"], 60)
    assert rec["ymax"] == 100 and rec["panels"][1]["paper"] is None


def test_phases_record(tmp_path):
    """Per-phase medians over the seeds (trace 1, 2, 3 s -> 2 s), scaled by
    cpu_s / total_s (here 1/2) when the figure shows CPU time; the footer
    quotes the median load average (2, 3, 4 -> 3)."""
    rec = figures.phases_record(make_args(tmp_path))
    bars = rec["panels"][0]["bars"]
    assert bars[(10, "conventional")] == {"trace": 2.0, "build": 2.0, "precompute": 0.0, "render": 4.0}
    assert bars[(20, "precomputed")]["precompute"] == 3.0 and rec["panels"][0]["nns"] == list(NNS)
    assert "median 3 on" in rec["footer"]
    rec = figures.phases_record(make_args(tmp_path, time="cpu_s"))
    assert rec["panels"][1]["bars"][(10, "precomputed")] == {"trace": 1.0, "build": 1.0, "precompute": 1.5,
                                                             "render": 2.0}


def images(monkeypatch, shape=(48, 64, 3), seed=5):
    """read_image answered from memory: the reference 1 + noise, the
    conventional render the reference, the precomputed one 10% brighter at
    P_e = 1000 and 30% at P_e = 2000; returns the images by name."""
    rng = np.random.default_rng(seed)
    ref = 1.0 + 0.1 * rng.random(shape)
    got = {"ref.exr": ref}
    for p, k in ((1000, 1.1), (2000, 1.3)):
        for n in NNS:
            got[f"runs/conventional-{p}-{n}-1.exr"] = ref
            got[f"runs/precomputed-{p}-{n}-1.exr"] = k * ref
    monkeypatch.setattr(figures, "read_image", lambda path, what: got[path])
    return got


def test_fig3_record(monkeypatch, tmp_path):
    """The crops are the window enlarged to 300 pixels wide (32 -> x10),
    the difference is (prec - conv) / reference luminance (0.1 and 0.3 here),
    each row's range its 99th percentile rounded to one digit; the paired
    ratio column where the table has it; a cell outside the table exits."""
    got = images(monkeypatch)
    rec = figures.fig3_record(make_args(tmp_path))
    assert rec["zoom"] == 10 and rec["window"] == (32, 24, 10, 10) and rec["size"] == (64, 48)
    a, b = rec["rows"]
    assert a["images"]["conventional"].shape == (240, 320, 3)
    assert np.array_equal(a["images"]["conventional"][::10, ::10], got["ref.exr"][10:34, 10:42])
    assert np.allclose(a["diff"], 0.1) and np.allclose(b["diff"], 0.3) and (a["lim"], b["lim"]) == (0.1, 0.3)
    assert a["rcol"] == "paired_ratio" and figures.fig3_record(make_args(tmp_path, time="cpu_s"))["rows"][0]["rcol"] \
        == "cpu_ratio"
    assert a["precomputed"]["method"] == "precomputed" and b["conventional"]["nn"] == 20
    with pytest.raises(SystemExit):
        figures.fig3_record(make_args(tmp_path, cells="1000:10 4000:10"))


def test_glance_record(monkeypatch, tmp_path):
    """glance.png's frames: a 1100-pixel-wide image halved twice (to 275),
    each pixel the mean of its 4x4 block; the cell's two table rows; the
    curves read per estimate in target order with what the resamples
    reach; controls: no equal-error file gives no curve, a cell outside the
    grid exits."""
    got = images(monkeypatch, shape=(16, 1100, 3))
    ee = pd.DataFrame([{"estimate": e, "kind": k, "target": t, "speedup": 2.0, "lo": 1.5, "hi": 2.5,
                        "defined_fraction": d} for e in ("paper", "corrected") for k, t, d in
                       (("curve", 0.02, 0.99), ("curve", 0.01, 0.5), ("tightest", 0.01, 0.5))])
    ee.to_csv(tmp_path / "ee.csv", index=False)
    rec = figures.glance_record(make_args(tmp_path, glance_cell="2000:20", equal_error=str(tmp_path / "ee.csv")))
    ref = rec["images"]["reference"]
    assert rec["factor"] == 4 and ref.shape == (4, 275, 3)
    assert np.isclose(ref[1, 2, 0], got["ref.exr"][4:8, 8:12, 0].mean())
    assert np.allclose(rec["images"]["precomputed"], 1.3 * ref)
    assert rec["rows"]["conventional"]["nn"] == 20 and rec["rows"]["precomputed"]["method"] == "precomputed"
    c = rec["curves"]["paper"]
    assert list(c["target"]) == [0.01, 0.02] and list(c["defined_fraction"]) == [0.5, 0.99]
    assert set(rec["curves"]) == {"paper", "corrected"} and rec["defined_min"] == 0.95
    assert figures.glance_record(make_args(tmp_path, glance_cell="2000:20", equal_error=""))["curves"] == {}
    # no cell given: the second of --cells (2000:20 here)
    assert figures.glance_record(make_args(tmp_path, glance_cell="", equal_error=""))["cell"] == (2000, 20)
    with pytest.raises(SystemExit):
        figures.glance_record(make_args(tmp_path, glance_cell="4000:20", equal_error=""))


def test_fig3_errors_record(monkeypatch, tmp_path):
    """Each map's square averages to the render's relMSE (metrics.relmse, the
    blocks tile the frame), the map of an identical render is 0 (negative
    control), and the colour range lies inside the maps' values."""
    got = images(monkeypatch)
    rec = figures.fig3_errors_record(make_args(tmp_path))
    assert rec["block"] == 2 and rec["shape"] == (24, 32)
    for p, n, row in rec["maps"]:
        for m, e, r, this in row:
            x = got[f"runs/{m}-{p}-{n}-1.exr"]
            assert this == pytest.approx(metrics.relmse(x, got["ref.exr"]))
            assert float(np.mean(np.square(e))) == pytest.approx(this, rel=1e-12)
            assert (np.all(e == 0) if m == "conventional" else np.all(e > 0)) and r["method"] == m
    lo, hi = rec["range"]
    assert 0 < lo < hi


def test_fig2_record(monkeypatch, tmp_path):
    """The representatives on the plane z = min z facing +z inside the
    window are counted by hand; the estimate at each grid point is the
    irradiance of the nearest one (brute force) within the radius cap, 0
    beyond it (negative control); the outline is the window's corners as
    the projection gives them."""
    rng = np.random.default_rng(3)
    reps = []
    for _ in range(200):
        x, y, e = rng.uniform(-0.6, 0.4), rng.uniform(0.9, 1.6), rng.uniform(1, 2)
        reps.append({"x": x, "y": y, "z": -1.0, "nx": 0, "ny": 0, "nz": 1, "e_r": e, "e_g": e, "e_b": e})
    reps += [{"x": 0.0, "y": 1.2, "z": 0.5, "nx": 0, "ny": 0, "nz": 1, "e_r": 9, "e_g": 9, "e_b": 9},  # not on the plane
             {"x": 0.0, "y": 1.2, "z": -1.0, "nx": 1, "ny": 0, "nz": 0, "e_r": 9, "e_g": 9, "e_b": 9}]  # facing +x
    run = os.path.join(str(tmp_path), "fig2")
    pd.DataFrame(reps).to_csv(run + ".reps.csv", index=False)
    with open(run + ".stats.json", "w", encoding="utf-8") as f:
        json.dump({"max_radius": 0.04}, f)
    img = np.ones((48, 64, 3))
    monkeypatch.setattr(figures, "read_image", lambda path, what: img)
    monkeypatch.setattr(figures, "scene_facts", lambda args, w, h: None)
    monkeypatch.setattr(scene_info, "project", lambda info, pts: (20 + 40 * pts[:, 0], 40 * pts[:, 1] - 30))
    rec = figures.fig2_record(make_args(tmp_path))
    r = pd.DataFrame(reps[:200])
    inwin = (r.x >= -0.4) & (r.x <= 0.2) & (r.y >= 1.0) & (r.y <= 1.45)
    assert rec["at"] == -1.0 and rec["on_plane"] == 200 and rec["in_window"] == int(inwin.sum())
    assert np.allclose(np.sort(rec["e"]), np.sort(r.e_r[inwin]))
    field = rec["field"]
    gu = np.linspace(-0.4, 0.2, 700)
    gv = np.linspace(1.0, 1.45, field.shape[0])
    pts = r[["x", "y"]].to_numpy()
    for i, j in ((0, 0), (100, 350), (field.shape[0] - 1, 699), (200, 10), (300, 600)):
        d = np.hypot(pts[:, 0] - gu[j], pts[:, 1] - gv[i])
        want = r.e_r.iloc[int(np.argmin(d))] if d.min() <= 0.04 else 0.0
        assert field[i, j] == pytest.approx(want)
    assert np.any(field == 0) and np.any(field > 0)
    px, py = rec["outline"]
    assert np.allclose(px, [4, 28, 28, 4]) and np.allclose(py, [10, 10, 28, 28])
    assert rec["pixels"] == (0, 32, 6, 32) and rec["lum_range"] == pytest.approx((1.0, 1.0))
