"""Unit tests of experiments/analysis/gather.py: the final-gathering study's
report (make gather).

Run by pytest from the repository root (tests/pytest.test.sh). Every check
compares against a value known by construction (synthetic runs whose
speed-ups, shares, memory and work costs are set), so each can fail;
negative controls: a grid without a speed-up must not read one, and the
work bound must move with the cost put into the lookups. Random numbers come
from fixed seeds.
"""

import json
import math
import os

import numpy as np
import pandas as pd
import pytest

from experiments.analysis import gather
from helpers import close

CELLS = [(p, n, g) for p in (10000, 40000) for n in (10, 50) for g in (4, 16)]


def synthetic(speedup, seeds=4, noise=0.02, c_map=2e-9, c_rep=1e-9, pre_share=0.03, mem=0.25):
    """A runs frame with the gather keys: error = 1/(P N / n) up to noise,
    conventional time T = work, precomputed T / SPEEDUP; the render time
    difference is c_map x extra map work - c_rep x rep work exactly; the
    precompute is PRE_SHARE of the time saved; representatives MEM of the maps."""
    rng = np.random.default_rng(5)
    rows = []
    for p, n, g in CELLS:
        for s in range(1, seeds + 1):
            err = n / (p * g) * math.exp(noise * rng.standard_normal())
            t_c = 1e-4 * p * g / 100 * math.exp(noise * rng.standard_normal()) + 1.0
            t_p = t_c / speedup
            rep_work = 1e6 * g
            map_extra = (t_c - t_p + c_rep * rep_work) / c_map  # render_c - render_p = c_map dmap - c_rep rep
            for m, t in (("conventional", t_c), ("precomputed", t_p)):
                rows.append({"method": m, "status": "ok", "role": "grid", "photons": p, "nn": n, "N": g, "seed": s,
                             "scene": "s", "size": "64x48", "total_s": t, "render_s": t - 0.5,
                             "relmse_ref": err, "precompute_s": pre_share * (t_c - t_p) if m == "precomputed" else 0.0,
                             "gather_s": (t - 0.6) if m == "conventional" else (t_c - 0.6) / (2 * speedup),
                             "map_work": 1e7 + (map_extra if m == "conventional" else 0.0),
                             "rep_work": rep_work if m == "precomputed" else 0.0,
                             "bytes_photon_map": 1000.0, "bytes_caustic_map": 200.0,
                             "bytes_representatives": mem * 1200.0 if m == "precomputed" else 0.0})
    return pd.DataFrame(rows)


def test_equal_error_speedup_recovered():
    """Precomputed 3x faster at every cell: every counted target reads 3
    within 5% and its band holds 3; control: equal times read 1, band holding 1."""
    s = gather.grid_summary(synthetic(3.0), "total_s", np.random.default_rng(1), 400)
    counted = [r for r in s["rows"] if r["counts"]]
    assert counted, s["rows"]
    for r in counted:
        close(r["speedup"], 3.0, 0.15, "speed-up")
        assert r["lo"] <= 3.0 <= r["hi"], r
    s1 = gather.grid_summary(synthetic(1.0), "total_s", np.random.default_rng(1), 400)
    for r in (r for r in s1["rows"] if r["counts"]):
        close(r["speedup"], 1.0, 0.05, "no speed-up")
        assert r["lo"] <= 1.0 <= r["hi"], r


def test_phase_share_memory_and_bound():
    """The gather phase speed-up, the precompute share and the memory
    increase are the values put in; the fit recovers c_map and c_rep, and
    the bound equals T_conv / (T_conv - c_map x extra map work) computed
    directly; control: twice the lookup cost gives a larger bound."""
    runs = synthetic(3.0, c_map=2e-9)
    s = gather.grid_summary(runs, "total_s", np.random.default_rng(1), 400)
    pairs = gather.pairs_of(runs)
    # paired: the geometric mean of each cell and seed's own ratio, not a
    # ratio of medians pooled over the grid's cells
    want_gather = float(np.exp(np.mean(np.log(pairs["gather_s_c"] / pairs["gather_s_p"]))))
    close(s["gather"][0], want_gather, 1e-9, "gather phase speed-up")
    # control: cells whose ratios differ (one cell's conventional gather 3x
    # slower, and seeds of unequal speed), where a ratio of pooled medians
    # is not the paired mean
    runs2 = runs.copy()
    first = runs2["photons"] == runs2["photons"].iloc[0]
    conv = runs2["method"] == "conventional"
    runs2.loc[first & conv, "gather_s"] *= 3.0
    runs2.loc[runs2["seed"] == runs2["seed"].max(), "gather_s"] *= 1.7
    s2 = gather.grid_summary(runs2, "total_s", np.random.default_rng(1), 400)
    p2 = gather.pairs_of(runs2)
    want2 = float(np.exp(np.mean(np.log(p2["gather_s_c"] / p2["gather_s_p"]))))
    close(s2["gather"][0], want2, 1e-9, "paired gather speed-up, unequal cells")
    unpaired = np.median(p2["gather_s_c"]) / np.median(p2["gather_s_p"])
    assert abs(unpaired - want2) > 1e-3 * want2, (unpaired, want2)
    assert s2["gather"][1] < s2["gather"][0] < s2["gather"][2]
    close(s["share"][0], 0.03, 1e-9, "precompute share")
    close(s["memory"], 0.25, 1e-9, "memory increase")
    b, c_map, c_rep = s["bound"]
    close(c_map, 2e-9, 1e-6, "c_map")
    close(c_rep, 1e-9, 1e-6, "c_rep")
    t = pairs["total_s_c"].to_numpy()
    dmap = (pairs["map_work_c"] - pairs["map_work_p"]).to_numpy()
    close(b, float(np.median(t / (t - 2e-9 * dmap))), 1e-6, "bound")
    assert b > 3.0  # the bound lies above the speed-up: the precomputed lookups and precompute cost something
    b2 = gather.grid_summary(synthetic(5.0), "total_s", np.random.default_rng(1), 100)["bound"][0]
    assert b2 > b


def test_best_per_target_is_the_cheapest_reaching_cell():
    """Against a brute force over the cells: the cheapest cell whose mean
    error is at most the target; none for a target below every cell."""
    modes = {"a": {(1, 1): (np.array([1.0, 1.2]), np.array([0.1, 0.1])), (2, 1): (np.array([5.0]), np.array([0.01]))},
             "b": {(3, 1, 4): (np.array([2.0]), np.array([0.05])), (4, 1, 4): (np.array([9.0]), np.array([0.001]))}}
    rows = gather.best_per_target(modes, [0.2, 0.05, 0.01, 0.001, 1e-5])
    assert [(m, k) for _, m, k, _ in rows] == [("a", (1, 1)), ("b", (3, 1, 4)), ("a", (2, 1)), ("b", (4, 1, 4)), ("", None)]
    close(rows[0][3], 1.1, 1e-12, "median time")


def write_grids(tmp_path, speedup=2.0):
    """Two sub-grids' runs.csv (N 4 and 16) with stats JSONs under
    TMP_PATH; returns their --grid arguments."""
    runs = synthetic(speedup, seeds=3)
    grids = []
    for g in (4, 16):
        sub = runs[runs["N"] == g].copy()
        paths = []
        for i, r in sub.reset_index(drop=True).iterrows():
            base = str(tmp_path / f"r{g}-{i}")
            st = {"gather": g, "gather_time": {"gather_thread_s": r["gather_s"], "render_thread_s": r["render_s"]},
                  "work": {"render": {"map_nodes": r["map_work"], "map_points": 0, "rep_nodes": r["rep_work"], "rep_points": 0}},
                  "bytes_photon_map": r["bytes_photon_map"], "bytes_caustic_map": r["bytes_caustic_map"],
                  "bytes_representatives": r["bytes_representatives"], "gather_work": {"lookups": 1}}
            with open(base + ".stats.json", "w") as f:
                json.dump(st, f)
            paths.append(base)
        sub["run"] = paths
        csv = tmp_path / f"runs-{g}.csv"
        sub.drop(columns=["gather_s", "map_work", "rep_work", "bytes_photon_map", "bytes_caustic_map",
                          "bytes_representatives", "N", "scene", "size"]).to_csv(csv, index=False)
        grids += ["--grid", "scenes/x.scene", "64x48", str(g), str(csv)]
    return grids


def test_main_writes_report(tmp_path):
    """End to end: two sub-grids' runs.csv with stats JSONs -> gather.md and
    gather.csv naming the grid and a speed-up near the one put in."""
    grids = write_grids(tmp_path)
    out = str(tmp_path / "out" / "gather")
    gather.main(grids + ["--out", out, "--bootstrap", "200"])
    md = open(out + ".md").read()
    assert "## scenes/x.scene at 64x48" in md and "Which configuration to pick" in md
    c = pd.read_csv(out + ".csv")
    ee = c[(c["kind"] == "equal_error") & (c["defined"] >= gather.DEFINED_MIN)]
    assert len(ee) and all(abs(v - 2.0) < 0.2 for v in ee["speedup"]), ee
    assert os.path.isfile(out + ".csv")
    # no --ref: the References section says so, and no number stands for the reference's error
    assert "- **scenes/x.scene at 64x48**: No reference is named for it (--ref)" in md
    assert c["ref_noise"].isna().all() and c["ref_bias"].isna().all()


def test_main_reports_the_references_error(tmp_path):
    """Known answer: --ref names a reference with a JSON: every gather.csv
    row of the grid holds its noise and bias, and gather.md's References
    checks them against the grid's tightest equal-error target (the
    smallest target of its equal_error rows); control: the same reference
    without its JSON (a POV-Ray render) gives empty columns and "not
    measured", no number."""
    from experiments.analysis import reference
    from helpers import write_reference_json
    grids = write_grids(tmp_path)
    ref = str(tmp_path / "ref.exr")
    write_reference_json(ref, 1e-7, 5e-8)
    out = str(tmp_path / "a" / "gather")
    gather.main(grids + ["--ref", "scenes/x.scene", "64x48", ref, "--out", out, "--bootstrap", "100"])
    c = pd.read_csv(out + ".csv")
    assert (c["ref_noise"] == 1e-7).all() and (c["ref_bias"] == 5e-8).all()
    tight = c.loc[c["kind"] == "equal_error", "target"].min()
    md = open(out + ".md").read()
    refs = md[md.index("## References"):]
    assert f"- **scenes/x.scene at 64x48**: Reference `{ref}`" in refs
    assert f"judges ({tight:.3g})" in refs and f"noise {1e-7 / tight:.1%}" in refs and "WARNING" not in refs
    os.remove(reference.sidecar(ref))
    out = str(tmp_path / "b" / "gather")
    gather.main(grids + ["--ref", "scenes/x.scene", "64x48", ref, "--out", out, "--bootstrap", "100"])
    c = pd.read_csv(out + ".csv")
    assert c["ref_noise"].isna().all() and c["ref_bias"].isna().all()
    refs = open(out + ".md").read().split("## References")[1]
    assert "its own error is not measured" in refs and "noise" not in refs.split("\n- **")[1]


def test_grid_reference_without_targets_and_two_refs_refused(tmp_path, capsys):
    """A grid without equal-error rows has no tightest target: the sentence
    says so; two references for one scene and size: exit 2 naming both."""
    from helpers import write_reference_json
    ref = str(tmp_path / "r.exr")
    write_reference_json(ref, 1e-5, 1e-5)
    r = gather.grid_reference(ref, [])
    assert r["tightest"] is None and "no tightest target to judge it by" in r["sentence"].lower()
    assert r["ref_noise"] == 1e-5
    with pytest.raises(SystemExit) as e:
        gather.main(write_grids(tmp_path) + ["--ref", "scenes/x.scene", "64x48", "a.exr", "--ref", "scenes/x.scene",
                                             "64x48", "b.exr", "--out", str(tmp_path / "g")])
    assert e.value.code == 2 and "a.exr and b.exr" in capsys.readouterr().err


def test_not_told_apart_names_the_overlapping_cells():
    """The cheapest reaching cell is not told apart from the other reaching
    cells whose range of times over seeds overlaps its own (control: a cell
    that does not reach the target, or whose times lie wholly above, is not
    named; no cell reaches it: none)."""
    modes = {"a": {(1, 1): (np.array([1.0, 1.4]), np.array([0.05, 0.05])),
                   (2, 1): (np.array([1.3, 2.0]), np.array([0.04, 0.04])),
                   (3, 1): (np.array([1.2, 1.3]), np.array([0.5, 0.5]))},
             "b": {(4, 1, 4): (np.array([3.0, 3.5]), np.array([0.01, 0.01]))}}
    rows = gather.best_per_target(modes, [0.1, 1e-5])
    assert rows[0][1:3] == ("a", (1, 1))
    assert gather.not_told_apart(modes, rows[0]) == [("a", (2, 1))]
    assert gather.not_told_apart(modes, rows[1]) == []
