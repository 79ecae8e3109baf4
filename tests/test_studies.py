"""Tests of experiments/studies.py (with experiments/analysis/runs.py's
converged_ref): a study of studies.yaml with the knobs of a command line
applied, its blocks of grids, their references and the refusals. Every
expected value is written out by hand from the declaration (the grids a
study must have, the path a reference must have), and each refusal has a
control that passes, so each check can fail."""

import os
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments import studies  # noqa: E402
from experiments.analysis import runs as layout  # noqa: E402

TINY = {"PHOTONS": "2000 4000", "NNS": "10 20", "SEEDS": "2", "RESULTS": "/r"}
CONVREF = "-convref-p80000-n200-shadow-rays-s2-seeds1000001_1000002_1000003_1000004"


@pytest.fixture(autouse=True)
def repo_root(monkeypatch):
    """studies.py finds reference/ and scenes/ from the repository root, as make runs it."""
    monkeypatch.chdir(os.path.join(os.path.dirname(__file__), ".."))


def test_converged_ref_path_spelled_once():
    p = layout.converged_ref("/r", "scenes/cornell.scene", "32x24", 80000, 200, "shadow-rays", 2, [1000001, 1000002])
    assert p == "/r/runs/cornell-convref-p80000-n200-shadow-rays-s2-seeds1000001_1000002/32x24.exr"
    # the rule's pattern: the same function with wildcards
    assert layout.converged_ref("/r", "{name}", "{size}", "{p}", "{n}", "{d}", "{s}", "{seeds}") == \
        "/r/runs/{name}-convref-p{p}-n{n}-{d}-s{s}-seeds{seeds}/{size}.exr"


def test_resolution_one_grid_per_size_each_with_its_converged_reference():
    s = studies.load("resolution", dict(TINY, RES_SIZES="16x12 32x24"))
    assert [g.size for g in s.grids] == ["16x12", "32x24"]
    assert [g.root for g in s.grids] == ["/r/runs/cornell-16x12-s2-t1", "/r/runs/cornell-32x24-s2-t1"]
    assert [g.files["runs_csv"] for g in s.grids] == ["/r/resolution/runs-16x12.csv", "/r/resolution/runs-32x24.csv"]
    assert s.files["runs_csv"] == "/r/resolution/runs-{grid}.csv"  # the rules' wildcard
    # P_e of the reference: CONV_REF_FACTOR (20) x the largest P_e (4000)
    assert [g.ref for g in s.grids] == [f"/r/runs/cornell{CONVREF}/16x12.exr", f"/r/runs/cornell{CONVREF}/32x24.exr"]
    assert all(g.ref_converged and g.ref_fast == "" for g in s.grids)
    assert len(s.run_files) == 2 * 2 * 2 * 2 * 2 * 2  # sizes x seeds x P_e x n x methods x estimates


def test_resolution_size_alone_is_that_size_only_and_res_sizes_wins():
    assert [g.size for g in studies.load("resolution", dict(TINY, SIZE="40x30")).grids] == ["40x30"]
    both = studies.load("resolution", dict(TINY, SIZE="40x30", RES_SIZES="16x12 32x24"))
    assert [g.size for g in both.grids] == ["16x12", "32x24"]
    assert [g.size for g in studies.load("resolution", TINY).grids] == ["256x192", "512x384", "1024x768"]


def test_resolution_res_ref_pov_takes_povray_where_there_is_one():
    s = studies.load("resolution", dict(TINY, RES_REF="pov", RES_SIZES="256x192 40x30"))
    pov, ours = s.grids
    assert pov.ref == "reference/cornell/cornell-reference-256x192.exr" and not pov.ref_converged
    assert ours.ref == f"/r/runs/cornell{CONVREF}/40x30.exr" and ours.ref_converged
    with pytest.raises(studies.StudyError, match="RES_REF=x: ours or pov"):
        studies.load("resolution", dict(TINY, RES_REF="x"))


def test_refused_knobs_name_the_reason():
    with pytest.raises(studies.StudyError, match="^resolution: .*RES_REF=ours.*not REF="):
        studies.load("resolution", dict(TINY, REF="x.exr"))
    with pytest.raises(studies.StudyError, match='^scenes: .*give SCENES="a.scene b.scene", not SCENE= or REF='):
        studies.load("scenes", dict(TINY, SCENE="scenes/slabs.scene"))
    with pytest.raises(studies.StudyError, match="^rep-study: makes its own variants: leave TAG unset"):
        studies.load("rep-study", dict(TINY, TAG="x", REF="x.exr"))
    # control: the same studies without those knobs
    studies.load("scenes", TINY)
    studies.load("rep-study", dict(TINY, REF="x.exr"))


def test_reference_seeds_must_not_be_grid_seeds():
    with pytest.raises(studies.StudyError, match=r"CONV_REF_SEEDS=1 1000002: seed\(s\) \[1\] are the grid's"):
        studies.load("scenes", dict(TINY, CONV_REF_SEEDS="1 1000002", SCENES="scenes/cornell.scene"))
    s = studies.load("scenes", dict(TINY, CONV_REF_SEEDS="3 1000002", SCENES="scenes/cornell.scene"))  # SEEDS=2
    assert s.ref_seeds == {1, 2}


def test_scenes_glob_every_scene_but_the_furnace():
    s = studies.load("scenes", {"RESULTS": "/r"})
    want = sorted(f for f in os.listdir("scenes") if f.endswith(".scene") and f != "furnace.scene")
    assert [os.path.basename(g.scene) for g in s.grids] == want
    assert [g.name for g in s.grids] == [os.path.splitext(f)[0] for f in want]
    assert {g.size for g in s.grids} == {"512x384"} and {len(g.seeds) for g in s.grids} == {5}
    assert s.ref_scenes == {g.name: g.scene for g in s.grids}


def test_rep_study_blocks_table1_and_one_variant_per_rule():
    s = studies.load("rep-study", {"REF": "x.exr", "RESULTS": "/r", "REP_RULES": "every2 count500 shared"})
    (n0, f0, base), (n1, f1, variants) = s.blocks
    assert (n0, n1) == ("table1", "rep") and len(base) == 1
    assert f0["runs_csv"] == "/r/table1/runs.csv" and f1["runs_csv"] == "/r/rep-study/runs-rep-{grid}.csv"
    b = base[0]
    assert b.methods == ["conventional", "precomputed"] and len(b.seeds) == 5 and b.pm_args == ""
    assert [v.pm_args for v in variants] == ["--rep-every 2", "--rep-count 500", "--rep-tree shared"]
    assert [v.root for v in variants] == [f"/r/runs/cornell-1024x768-s2-t1-rep-{r}" for r in ("every2", "count500", "shared")]
    for v in variants:
        assert v.methods == ["precomputed"] and v.estimates == ["paper"] and len(v.seeds) == 3
        assert v.conv_root == b.root and v.conv_files == b.run_files and v.ref == "x.exr"
    # SEEDS given: every grid, the variants too
    s2 = studies.load("rep-study", {"REF": "x.exr", "SEEDS": "2", "REP_RULES": "shared"})
    assert [len(g.seeds) for g in s2.grids] == [2, 2]


def test_rep_study_unknown_rule_refused_before_any_render():
    with pytest.raises(studies.StudyError, match="rule 'every0' is not everyK, countN or shared"):
        studies.load("rep-study", dict(TINY, REF="x.exr", REP_RULES="every2 every0"))


def test_beyond_cases_times_variants():
    s = studies.load("beyond", {"RESULTS": "/r", "SCENES": "scenes/slabs.scene scenes/cornell.scene",
                                "SIZE": "32x24", "BEYOND_SIZES": "16x12 32x24", "BEYOND_TAUS": "0.1 0.2"})
    (_, _, bases), (_, _, variants) = s.blocks
    # every scene at SIZE, and cornell at each of BEYOND_SIZES, once each, sorted as name@size@scene
    assert [b.name for b in bases] == ["cornell-16x12", "cornell-32x24", "slabs-32x24"]
    assert [b.root for b in bases] == ["/r/runs/cornell-16x12-s2-t1-beyond", "/r/runs/cornell-32x24-s2-t1-beyond",
                                       "/r/runs/slabs-32x24-s2-t1-beyond"]
    names = ["lazy", "gated0.1", "lazygated0.1", "gated0.2", "lazygated0.2"]  # BEYOND_VARIANTS empty: from the taus
    assert [v.name for v in variants] == [f"{b.name}-{n}" for b in bases for n in names]
    v = {x.name: x for x in variants}
    assert v["slabs-32x24-lazy"].pm_args == "--rep-eval lazy"
    assert v["slabs-32x24-gated0.2"].pm_args == "--rep-gate plane-lookup --rep-gate-tau 0.2"
    assert v["cornell-16x12-lazygated0.1"].pm_args == "--rep-eval lazy --rep-gate plane-lookup --rep-gate-tau 0.1"
    assert v["cornell-16x12-lazy"].root == "/r/runs/cornell-16x12-s2-t1-beyond-lazy"
    assert all(x.conv_root == b.root for b in bases for x in variants if x.name.startswith(b.name + "-"))
    assert all(x.methods == ["precomputed"] for x in variants) and all(b.paired for b in bases)
    assert {x.ref for x in variants if x.name.startswith("slabs")} == {bases[2].ref} and bases[2].ref_converged
    # without cornell among SCENES: no BEYOND_SIZES case
    s2 = studies.load("beyond", {"SCENES": "scenes/slabs.scene", "SIZE": "32x24", "BEYOND_VARIANTS": "lazy"})
    assert [g.name for g in s2.grids] == ["slabs-32x24", "slabs-32x24-lazy"]
    with pytest.raises(studies.StudyError, match="variant 'fast' is not lazy, gatedT or lazygatedT"):
        studies.load("beyond", {"SCENES": "scenes/slabs.scene", "BEYOND_VARIANTS": "lazy fast"})


def test_reproducibility_three_runs_in_sequence():
    """Run a is Table 1's run root, b and busy their own, each after the one
    before (every render of it), busy with the busy loop; control: Table 1's
    grid waits for nothing and has no busy loop."""
    s = studies.load("reproducibility", {"RESULTS": "/r", "SIZE": "32x24", "SEEDS": "2", "REF": "x.exr"})
    a, b, busy = s.grids
    t = studies.load("table1", {"RESULTS": "/r", "SIZE": "32x24", "SEEDS": "2", "REF": "x.exr"}).grids[0]
    assert (a.name, b.name, busy.name) == ("a", "b", "busy") and a.root == t.root == "/r/runs/cornell-32x24-s2-t1"
    assert b.root == "/r/runs/cornell-32x24-s2-t1-repro-b" and busy.root.endswith("-repro-busy")
    assert b.files["runs_csv"] == "/r/reproducibility/runs-b.csv" and a.ref == b.ref == "x.exr"
    assert a.after == [] and b.after == a.run_files and busy.after == b.run_files and len(b.after) == 96
    assert "--busy-loop" in busy.launch_words("paper-p50000-n10/seed1")
    assert "--busy-loop" not in b.launch_words("paper-p50000-n10/seed1") and not t.busy_loop and t.after == []
    # no REF: the POV-Ray reference of 256x192, else our converged one at that size
    assert studies.load("reproducibility", {"SIZE": "256x192"}).grids[0].ref == \
        "reference/cornell/cornell-reference-256x192.exr"
    g = studies.load("reproducibility", {"SIZE": "40x30", "RESULTS": "/r"}).grids[0]
    assert g.ref_converged and g.ref.endswith("/40x30.exr")


def test_gather_cases_times_n_each_with_its_tag_and_reference():
    """gather: SCENES at SIZE, cornell also at GATHER_CORNELL_SIZES, one grid
    per N of GATHERS, a run root tagged gatherN, --gather N on both methods."""
    s = studies.load("gather", dict(TINY, SIZE="64x48", SCENES="scenes/cornell.scene scenes/caustic.scene",
                                    GATHERS="4 8", GATHER_CORNELL_SIZES="32x24 64x48"))
    assert [g.name for g in s.grids] == ["caustic-64x48-N4", "caustic-64x48-N8", "cornell-32x24-N4", "cornell-32x24-N8",
                                         "cornell-64x48-N4", "cornell-64x48-N8"]
    g = s.by_name["cornell-32x24-N8"]
    assert (g.scene, g.size, g.tag, g.pm_args) == ("scenes/cornell.scene", "32x24", "gather8", "--gather 8 --direct shadow-rays")
    assert g.root == "/r/runs/cornell-32x24-s2-t1-gather8"
    assert g.methods == ["conventional", "precomputed"] and g.paired
    assert g.ref == "/r/runs/cornell" + CONVREF + "/32x24.exr" and g.ref_converged
    assert g.files["runs_csv"] == "/r/gather/runs-cornell-32x24-N8.csv"
    # a scene other than cornell at SIZE only
    assert not [x for x in s.grids if x.scene == "scenes/caustic.scene" and x.size != "64x48"]
    for knob in ("SCENE", "TAG", "GATHER_GRIDS", "DIRECT_RUNS"):
        with pytest.raises(studies.StudyError, match="GATHER_CORNELL_SIZES"):
            studies.load("gather", dict(TINY, **{knob: "x"}))


def test_gather_one_repeat_for_the_heaviest_conventional_renders():
    """one_repeat: eye samples (64 x 48 x 2^2 = 12,288) x N x n at or above
    ONE_REPEAT_WORK: the conventional render runs --repeats 1; the
    precomputed one and the lighter cells TIME_REPEATS; control: a
    threshold above every cell leaves every render at TIME_REPEATS."""
    knobs = dict(TINY, SIZE="64x48", SCENES="scenes/cornell.scene", GATHERS="4", GATHER_CORNELL_SIZES="64x48",
                 ONE_REPEAT_WORK="983040", TIME_REPEATS="3")
    g = studies.load("gather", knobs).by_name["cornell-64x48-N4"]
    assert g.repeats("conventional", 20) == "1"        # 12,288 x 4 x 20 = 983,040: at it
    assert g.repeats("conventional", 19) == "3"        # below it
    assert g.repeats("precomputed", 20) == "3"
    cmd = g.launch_command(g.root, ["conventional", "precomputed"], "paper", "2000", "20", 1)
    assert "--repeats 3 --of 16" in cmd and f"--member-repeats {g.root} conventional 1" in cmd
    assert "precomputed 1" not in cmd.split("--member-repeats")[1]
    light = studies.load("gather", dict(knobs, ONE_REPEAT_WORK="1e12")).by_name["cornell-64x48-N4"]
    assert "--member-repeats" not in light.launch_command(light.root, ["conventional"], "paper", "2000", "20", 1)
    # a study without one_repeat: TIME_REPEATS everywhere
    t = studies.load("table1", dict(TINY, SIZE="64x48", TIME_REPEATS="3"))
    assert t.repeats("conventional", 10 ** 9) == "3"


def test_gather_direct_runs_are_the_scenes_studys_files():
    """related: direct: the scenes study loaded with gather's RESULTS, SIZE
    and SCENES: its runs.csv per scene, as `make scenes` writes them."""
    knobs = dict(TINY, SIZE="64x48", SCENES="scenes/cornell.scene scenes/caustic.scene")
    d = studies.load("gather", knobs).related("direct")
    scenes = studies.load("scenes", {"RESULTS": "/r", "SIZE": "64x48", "SCENES": knobs["SCENES"]})
    assert [(g.scene, g.size, g.files["runs_csv"]) for g in d.grids] == \
        [(g.scene, g.size, g.files["runs_csv"]) for g in scenes.grids] == \
        [("scenes/cornell.scene", "64x48", "/r/scenes/runs-cornell.csv"),
         ("scenes/caustic.scene", "64x48", "/r/scenes/runs-caustic.csv")]


def test_time_cpu_pins_timed_one_thread_renders():
    """TIME_CPU (default first) reaches the launcher of a timed study's
    one-thread renders as --cpu; an untimed study, or renders on several
    threads, are not pinned (--cpu none); a number passes through; a word
    that is no CPU is refused before any render."""
    def cpu(target, **knobs):
        words = studies.load(target, dict(TINY, REF="x.exr", **knobs)).grids[0].launch_words("paper-p2000-n10/seed1")
        return words[words.index("--cpu") + 1]
    assert cpu("table1") == "first" and cpu("table1", TIME_CPU="1") == "1"
    assert cpu("table1", THREADS="") == "none" and cpu("table1", THREADS="2") == "none"
    assert cpu("table1", TIME_CPU="none") == "none"
    assert cpu("bias") == "none"  # untimed (timed: false)
    with pytest.raises(studies.StudyError, match="TIME_CPU=fast: first"):
        cpu("table1", TIME_CPU="fast")
