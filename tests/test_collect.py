"""Unit tests of experiments/analysis/collect.py: the reference's own error in
runs.csv and cells.csv (ref_noise, ref_bias, relmse_ref_less_noise,
relmse_ref_less_noise_mean).

Run by pytest from the repository root (tests/pytest.test.sh). A synthetic
grid (two methods, three seeds, 8x6 EXRs with noise from fixed seeds) is
collected against a reference with a known JSON beside it: the columns
must hold the JSON's numbers and relMSE minus its noise exactly. Negative
controls: the same grid against the same reference without its JSON (a
POV-Ray reference) leaves the columns empty and the corrected relMSE equal
to the raw one; a JSON in other units corrects nothing; the paired
difference of two methods is the same on either column (the term cancels)
while the margin that scales with the level does not.
"""

import argparse
import json
import math
import os
import sys

import numpy as np
import pandas as pd
import pytest

from experiments.analysis import collect, reference, stats
from experiments.analysis import runs as layout
from helpers import close, write_reference_json

W, H = 8, 6
SEEDS = (1, 2, 3)
NOISE, BIAS = 0.0003, 0.0001


def write_render(root, method, seed, img, cpu=None, processes=None):
    """One ok render's files (run.json, stats.json, EXR) under ROOT; CPU:
    the record's pinned CPU (None: a record without one, as before pinning);
    PROCESSES: the stats' processes (None: none, as one process writes)."""
    base = layout.run_base(str(root), method, "paper", 1000, 10, seed)
    os.makedirs(os.path.dirname(base), exist_ok=True)
    rec = {"exit": 0, "loadavg_1min": 0.5, "cpu_s": 1.0, "user_s": 0.9, "sys_s": 0.1}
    if cpu is not None:
        rec["cpu"] = cpu
    with open(base + ".run.json", "w") as f:
        json.dump(rec, f)
    st = {"time_s": {"trace": 0.1, "build": 0.1, "precompute": 0.2 if method == "precomputed" else 0.0,
                     "render": 0.5, "total": 0.9},
          "repeats": 1, "photons_stored": 900, "representatives": 100 if method == "precomputed" else 0,
          "empty_estimates": 0, "nonfinite_pixels": 0, "rep_every": 4, "threads": 1, "width": W, "height": H,
          "rep_count": 0}
    if processes is not None:
        st["processes"] = processes
    with open(base + ".stats.json", "w") as f:
        json.dump(st, f)
    reference.write_exr(img, base + ".exr")


def grid(tmp_path, with_json=True, metric="relmse"):
    """The collect arguments of a synthetic grid: the precomputed renders
    noisier than the conventional ones, seed by seed."""
    rng = np.random.default_rng(7)
    ref = np.full((H, W, 3), 0.5, dtype=np.float32) + 0.1 * rng.random((H, W, 3)).astype(np.float32)
    root = tmp_path / "runs"
    for s in SEEDS:
        base_noise = rng.standard_normal((H, W, 3)).astype(np.float32)
        write_render(root, "conventional", s, ref + 0.02 * base_noise)
        write_render(root, "precomputed", s, ref + 0.03 * base_noise + 0.01 * rng.standard_normal((H, W, 3)))
    exr = str(tmp_path / "ref" / "ref.exr")
    os.makedirs(os.path.dirname(exr))
    reference.write_exr(ref, exr)
    if with_json:
        write_reference_json(exr, NOISE, BIAS, metric)
    return argparse.Namespace(runroot=str(root), conv_runroot=str(root), scene="scenes/x.scene", width=W, height=H,
                              subpixels=1, threads="1", tag="", methods="conventional precomputed",
                              estimates="paper", photons="1000", nns="10", seeds=" ".join(map(str, SEEDS)),
                              ref=exr, ref_fast="", runs_csv=str(tmp_path / "runs.csv"),
                              cells_csv=str(tmp_path / "cells.csv"))


def test_runs_carry_the_references_error(tmp_path):
    """Known answer: every row holds the JSON's noise and bias, and the
    corrected relMSE is relmse_ref - noise exactly; the cells' corrected
    mean is the mean minus the noise."""
    runs, cells = collect.collect(grid(tmp_path))
    ok = runs[runs["status"] == "ok"]
    assert len(ok) == 2 * len(SEEDS)
    assert (runs["ref_noise"] == NOISE).all() and (runs["ref_bias"] == BIAS).all()
    assert np.allclose(ok["relmse_ref_less_noise"], ok["relmse_ref"] - NOISE, rtol=0, atol=1e-15)
    assert (ok["relmse_ref"] > NOISE).all()  # the correction is visible against the raw numbers
    for _, c in cells.iterrows():
        close(c["relmse_ref_less_noise_mean"], c["relmse_ref_mean"] - NOISE, 1e-15, "cell's corrected mean")
        mine = ok[ok["method"] == c["method"]]
        close(c["relmse_ref_less_noise_mean"], mine["relmse_ref_less_noise"].mean(), 1e-9, "mean over seeds")
    # the interface: every existing column is still there, the new ones after them
    assert list(runs.columns[-6:]) == ["ref_noise", "ref_bias", "relmse_ref_less_noise", "cpu", "processes",
                                     "gauge_added"]
    assert list(cells.columns).index("relmse_ref_less_noise_mean") == list(cells.columns).index("relmse_ref_mean") + 1


def test_reference_without_json_is_not_measured(tmp_path, monkeypatch):
    """Negative control: no JSON beside the reference (a POV-Ray render):
    ref_noise and ref_bias are empty fields in the written runs.csv, the
    corrected relMSE equals the raw one, and describe() says "not
    measured" without a number."""
    args = grid(tmp_path, with_json=False)
    argv = ["collect.py"] + [w for k, v in vars(args).items()
                             for w in (f"--{k.replace('_', '-')}", str(v))]
    monkeypatch.setattr(sys, "argv", argv)
    collect.main()
    runs = pd.read_csv(args.runs_csv)
    cells = pd.read_csv(args.cells_csv)
    assert runs["ref_noise"].isna().all() and runs["ref_bias"].isna().all()
    ok = runs[runs["status"] == "ok"]
    assert (ok["relmse_ref_less_noise"] == ok["relmse_ref"]).all()
    assert (cells["relmse_ref_less_noise_mean"] == cells["relmse_ref_mean"]).all()
    with open(args.runs_csv) as f:
        header, first = f.readline().rstrip("\n").split(","), f.readline().rstrip("\n").split(",")
    assert first[header.index("ref_noise")] == "" and first[header.index("ref_bias")] == ""
    text = reference.describe(args.ref, 0.01)
    assert "not measured" in text and "noise" not in text


def test_json_in_other_units_corrects_nothing(tmp_path):
    """Negative control: a JSON whose metric is not relMSE (its noise in
    other units) neither fills the columns nor changes relmse_ref."""
    runs, cells = collect.collect(grid(tmp_path, metric="nmse"))
    ok = runs[runs["status"] == "ok"]
    assert runs["ref_noise"].isna().all()
    assert (ok["relmse_ref_less_noise"] == ok["relmse_ref"]).all()


def test_paired_difference_unchanged_by_the_correction(tmp_path):
    """The term cancels: the paired difference precomputed - conventional
    per seed has the same mean, interval and p on relmse_ref and on
    relmse_ref_less_noise; control: the margin delta (a share of the
    conventional level) is smaller by exactly MARGIN x noise on the
    corrected column, so the test can tell the columns apart."""
    runs, _ = collect.collect(grid(tmp_path))
    ok = runs[runs["status"] == "ok"].sort_values("seed")
    pre, conv = ok[ok["method"] == "precomputed"], ok[ok["method"] == "conventional"]
    raw = stats.paired_difference(pre["relmse_ref"].to_numpy(), conv["relmse_ref"].to_numpy())
    cor = stats.paired_difference(pre["relmse_ref_less_noise"].to_numpy(), conv["relmse_ref_less_noise"].to_numpy())
    for k in ("mean", "lo", "hi"):
        close(cor[k], raw[k], 1e-15, k)
    close(cor["p"], raw["p"], 1e-9, "p")
    assert raw["mean"] > 0 and raw["p"] < 0.05  # a real difference, not a trivially equal pair
    close(raw["delta"] - cor["delta"], stats.EQUIVALENCE_MARGIN * NOISE, 1e-15, "delta follows the level")
    assert not math.isclose(cor["relative"], raw["relative"])


def test_malformed_json_names_the_file(tmp_path, capsys):
    """A JSON beside the reference that is not JSON: bad input, exit 2 naming it."""
    args = grid(tmp_path)
    with open(reference.sidecar(args.ref), "w") as f:
        f.write("{not json")
    with pytest.raises(SystemExit) as e:
        collect.collect(args)
    assert e.value.code == 2
    assert reference.sidecar(args.ref) in capsys.readouterr().err


def test_runs_carry_the_pinned_cpu(tmp_path):
    """runs.csv's cpu column is the record's "cpu" (TIME_CPU); a record
    without one (before pinning, or --cpu none) leaves it empty."""
    args = grid(tmp_path)
    write_render(tmp_path / "runs", "conventional", 1, np.full((H, W, 3), 0.5, dtype=np.float32), cpu=1)
    runs, _ = collect.collect(args)
    got = runs.set_index(["method", "seed"])["cpu"]
    assert got[("conventional", 1)] == 1 and got[("precomputed", 1)] != got[("precomputed", 1)]


def test_runs_carry_the_processes(tmp_path):
    """runs.csv's processes column is the stats' "processes" (TIME_PROCESSES,
    launch.py's merged stats); stats without it (one process) say 1."""
    args = grid(tmp_path)
    write_render(tmp_path / "runs", "conventional", 1, np.full((H, W, 3), 0.5, dtype=np.float32), processes=2)
    runs, _ = collect.collect(args)
    got = runs.set_index(["method", "seed"])["processes"]
    assert got[("conventional", 1)] == 2 and got[("precomputed", 1)] == 1 and got[("conventional", 2)] == 1

