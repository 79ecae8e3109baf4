"""Tests of make evaluate's final-gathering grid: the evaluate study's
block gather (experiments/studies.yaml: one grid per N of EVAL_GATHERS,
both methods with --gather N --direct shadow-rays, its own P_e x n unless
the command line gives them; a bad N refused; none without EVAL_GATHERS),
and the verdict experiments/analysis/evaluate.py writes from
analysis/gather.py's CSV: a known answer (a band above 1 at the counted
targets, the cheapest configuration per target named) and negative
controls (targets too few resamples reach are not worded; a band
containing 1 is undetermined)."""

import os
import sys

import pandas as pd
import pytest

ROOT = os.path.join(os.path.dirname(__file__), "..")
sys.path.insert(0, ROOT)
from experiments import studies  # noqa: E402
from experiments.analysis import evaluate  # noqa: E402

KNOBS = {"SCENE": "tests/evaluate/box.scene", "RESULTS": "/r"}


@pytest.fixture(autouse=True)
def repo_root(monkeypatch):
    monkeypatch.chdir(ROOT)


def test_gather_block_one_grid_per_n():
    s = studies.load("evaluate", dict(KNOBS))
    names = [g.name for g in s.grids]
    assert names == ["grid", "lazy", "plane-lookup", "N4", "N16"]
    g = s.by_name["N16"]
    assert g.pm_args == "--gather 16 --direct shadow-rays" and g.knobs["GATHER"] == "16"
    assert g.methods == ["conventional", "precomputed"] and g.paired
    assert (g.photons, g.nns, g.estimates, g.seeds) == (["25000", "100000"], ["10", "100"], ["paper"], [1, 2, 3])
    assert g.root.startswith("/r/evaluate/box/runs/grid-") and g.root.endswith("-128x96-t1-gather16")
    assert g.files["runs_csv"] == "/r/evaluate/box/gather/runs-N16.csv"
    assert s.files["gather"] == "/r/evaluate/box/gather/gather"
    assert len(g.run_files) == 2 * 2 * 2 * 3
    # the main grid keeps its own P_e x n and both estimates
    assert s.by_name["grid"].photons == ["25000", "50000", "100000"] and s.by_name["grid"].estimates == ["paper", "corrected"]
    # eye samples 128 x 96 x 4 = 49,152 x N x n below ONE_REPEAT_WORK (1e8): TIME_REPEATS; at it: once
    assert g.repeats("conventional", 100) == "auto"
    heavy = studies.load("evaluate", dict(KNOBS, ONE_REPEAT_WORK="78643200")).by_name["N16"]
    assert heavy.repeats("conventional", 100) == "1" and heavy.repeats("precomputed", 100) == "auto"


def test_gather_block_knobs_and_refusals():
    s = studies.load("evaluate", dict(KNOBS, PHOTONS="4000 8000", NNS="10 30", EVAL_GATHERS="8"))
    assert [g.name for g in s.grids][-1:] == ["N8"] and len(s.grids) == 4
    assert s.by_name["N8"].photons == ["4000", "8000"] and s.by_name["N8"].nns == ["10", "30"]
    assert [g.name for g in studies.load("evaluate", dict(KNOBS, EVAL_GATHERS="")).grids] == ["grid", "lazy", "plane-lookup"]
    for bad in ("0", "x", "-4"):
        with pytest.raises(studies.StudyError, match="EVAL_GATHERS: '.*' is not a positive number of gather rays"):
            studies.load("evaluate", dict(KNOBS, EVAL_GATHERS=bad))


def frame(defined, lo, hi, best):
    rows = [{"kind": "equal_error", "target": t, "conventional_s": 2.0, "precomputed_s": 1.0, "speedup": 2.0,
             "lo": lo, "hi": hi, "defined": defined} for t in (0.01, 0.02, 0.04)]
    rows.append({"kind": "gather_phase", "speedup": 3.0, "lo": 2.5, "hi": 3.5})
    rows += [{"kind": "best", "target": t, "mode": m, "setting": st, "conventional_s": sec} for t, m, st, sec in best]
    return pd.DataFrame(rows)


BEST = [(0.04, "direct conventional paper", "P_e=25000 n=10", 0.5),
        (0.01, "gather precomputed", "P_e=100000 n=100 N=16", 4.0),
        (0.005, "", "", float("nan"))]


def test_gather_verdict_known_answer():
    sentence, lines = evaluate.gather_verdict(frame(0.99, 1.5, 2.5, BEST))
    assert sentence.startswith("Final gathering (--gather N")
    assert "pays (band above 1) at relMSE 0.01-0.04, by 2-2x" in sentence
    assert "the gather phase alone 3x [2.5, 3.5]" in sentence
    assert ("0.04: direct conventional paper P_e=25000 n=10 (0.5 s); 0.01: gather precomputed "
            "P_e=100000 n=100 N=16 (4 s); 0.005: none reaches it") in sentence
    assert lines[0] == "## Final gathering"
    assert "| 0.005 | none reaches it |  | n/a |" in lines
    assert not any("(not counted)" in x for x in lines)


def test_gather_verdict_controls():
    # too few resamples reach both fronts: nothing worded, every row marked
    sentence, lines = evaluate.gather_verdict(frame(0.6, 1.5, 2.5, BEST))
    assert "at no target do 95% of the resamples reach both fronts" in sentence and "pays" not in sentence
    assert sum("(not counted)" in x for x in lines) == 3
    # a band containing 1: undetermined, not "pays"
    sentence, _ = evaluate.gather_verdict(frame(0.99, 0.8, 2.5, BEST))
    assert "undetermined (band contains 1) at relMSE 0.01-0.04" in sentence and "pays" not in sentence
    # fronts sharing no range
    sentence, _ = evaluate.gather_verdict(frame(0.99, 1.5, 2.5, BEST).query("kind != 'equal_error'"))
    assert "share no relMSE range" in sentence
