"""Tests of experiments/prediction.py, the line a study's dry run prints:
the wall time a cost model (a fake model.json with known coefficients)
predicts for the study's missing renders, worked out by hand (the
renders' count, their --repeats, the counters scaled by P_e); controls:
no model, a broken model, renders with final gathering (not predicted),
and the Snakefile printing it only on PREDICT=1."""

import os
import subprocess
import sys

import numpy as np
import pytest

ROOT = os.path.join(os.path.dirname(__file__), "..")
sys.path.insert(0, ROOT)
from experiments import calibrate, prediction, studies  # noqa: E402

# table1 at P_e 2000 and 4000, n 10 and 20, both methods and estimates, 2 seeds: 32 renders
TINY = {"PHOTONS": "2000 4000", "NNS": "10 20", "SEEDS": "2", "SIZE": "32x24"}


@pytest.fixture(autouse=True)
def repo_root(monkeypatch):
    monkeypatch.chdir(ROOT)


def fake_model(results, constant=0.0, per_photon=0.0, written="2026-01-02"):
    """RESULTS/calibrate/model.json: the trace phase takes CONSTANT seconds
    plus PER_PHOTON per traced photon (one traced photon per photon emitted,
    every other counter 0), every other part nothing."""
    model = {p: np.zeros(1 + len(calibrate.FEATURES[p])) for p in calibrate.PARTS}
    model["trace"][0] = constant
    model["trace"][1 + calibrate.FEATURES["trace"].index("traced_photons")] = per_photon
    names = sorted({n for f in calibrate.FEATURES.values() for n in f} | {"traced_photons"})
    unit = {ph: {n: (1.0 if (ph, n) == ("trace", "traced_photons") else 0.0) for n in names} for ph in calibrate.PHASES}
    per_unit = {"cornell": {"conventional": unit, "precomputed": unit}}
    path = os.path.join(results, "calibrate", "model.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    calibrate.write_model(path, model, 0.02, 0.05, {p: 0.0 for p in calibrate.PHASES}, {"cpu": "x"}, per_unit,
                          written=written)
    return path


def test_constant_time_times_repeats(tmp_path):
    """40 s a render: --repeats auto runs it 3 times (at least 3; 2 s budget
    spent by the first), in 2 processes (TIME_PROCESSES' default): 32
    renders x 240 s = 2 h 8 min; TIME_PROCESSES=1: 1 h 4 min;
    TIME_REPEATS=2: 160 s each, 1 h 25 min; with 8 records written, 24 x
    240 s = 1 h 36 min."""
    path = fake_model(str(tmp_path), constant=40.0)
    s = studies.load("table1", dict(TINY, RESULTS=str(tmp_path)))
    assert prediction.line(s) == (f"predicted: 32 renders missing, about 2 h 8 min on this machine at the "
                                  f"repeats' minima; the wall is longer (repeats above their minimum, processes "
                                  f"the gauge adds, each process's start) (cost model {path} of 2026-01-02)")
    s1 = studies.load("table1", dict(TINY, RESULTS=str(tmp_path), TIME_PROCESSES="1"))
    assert "32 renders missing, about 1 h 4 min" in prediction.line(s1)
    s2 = studies.load("table1", dict(TINY, RESULTS=str(tmp_path), TIME_REPEATS="2"))
    assert "32 renders missing, about 1 h 25 min" in prediction.line(s2)
    for record in s.run_files[:8]:
        os.makedirs(os.path.dirname(record), exist_ok=True)
        open(record, "w").close()
    assert "24 renders missing, about 1 h 36 min" in prediction.line(s)


def test_counters_scale_with_the_photons(tmp_path):
    """0.01 s per traced photon, one repeat: 16 renders at 2000 photons (20 s)
    and 16 at 4000 (40 s): 960 s = 16 min."""
    fake_model(str(tmp_path), per_photon=0.01)
    s = studies.load("table1", dict(TINY, RESULTS=str(tmp_path), TIME_REPEATS="1", TIME_PROCESSES="1"))
    assert "32 renders missing, about 0 h 16 min" in prediction.line(s)


def test_no_model_and_broken_model(tmp_path):
    s = studies.load("table1", dict(TINY, RESULTS=str(tmp_path)))
    assert prediction.line(s) == "no cost model: run make calibrate"
    os.makedirs(tmp_path / "calibrate")
    (tmp_path / "calibrate" / "model.json").write_text("{")
    line = prediction.line(s)
    assert line.startswith("no cost model: ") and str(tmp_path / "calibrate" / "model.json") in line


def test_final_gathering_not_predicted(tmp_path):
    """The cost model has no gather counters: every render of a gather grid
    is counted as not predicted, and the time is called a lower bound."""
    fake_model(str(tmp_path), constant=40.0)
    s = studies.load("gather", dict(TINY, RESULTS=str(tmp_path), SCENES="scenes/cornell.scene", GATHERS="4",
                                    GATHER_CORNELL_SIZES="32x24"))
    n = len(s.run_files)
    assert prediction.line(s).startswith(f"predicted: {n} renders missing, about 0 h 0 min")
    assert f"; {n} of them not predicted" in prediction.line(s) and "lower bound" in prediction.line(s)
    assert prediction.gathers("--gather 16 --direct shadow-rays") == 16 and prediction.gathers("") == 0


def dry_run(results, *extra):
    cmd = ["snakemake", "-s", "experiments/Snakefile", "-n", "-q", "--cores", "1", "--nolock", "--config",
           "STUDY=table1", f"RESULTS={results}", "PHOTONS=2000", "NNS=10", "SEEDS=1", "SIZE=32x24", *extra,
           "--", "runs"]
    return subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)


def test_snakefile_prints_it_once_on_a_dry_run(tmp_path):
    """PREDICT=1 (make's front door on a dry run): the line, once; control:
    without it, no line."""
    fake_model(str(tmp_path), constant=40.0)
    r = dry_run(str(tmp_path), "PREDICT=1")
    assert r.returncode == 0, r.stderr
    assert (r.stdout + r.stderr).count("predicted: 4 renders missing, about 0 h 16 min") == 1  # 4 x 40 s x 3 repeats x 2 processes
    r = dry_run(str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "predicted:" not in r.stdout + r.stderr


@pytest.mark.parametrize("args, expect", [(["SNAKEFLAGS=-n"], "PREDICT=1"), (["SNAKEFLAGS=--dry-run"], "PREDICT=1"),
                                          (["-n"], "PREDICT=1"), (["SNAKEFLAGS=-p"], ""), ([], "")])
def test_make_passes_predict_on_a_dry_run_only(args, expect):
    """experiments/snakemake.mk's smk_predict: PREDICT=1 under make -n or
    -n in SNAKEFLAGS; nothing otherwise (a target of no prerequisites
    prints it: nothing is built)."""
    r = subprocess.run(["make", "-s", "--no-print-directory", "--eval", "print-pred: ; +@echo '<$(smk_predict)>'",
                        "print-pred", *args], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == f"<{expect}>"
