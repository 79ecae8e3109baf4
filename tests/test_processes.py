"""Tests of experiments/launch.py's --processes (the study knob
TIME_PROCESSES): each member of a group rendered in several processes, in
rounds whose order reverses (A B B A), its times the minima over every
repeat of every process, the group failing when two processes of one
render disagree in a bit of the image or in a work counter; of the gauge
(--gauge, TIME_GAUGE: a render whose least photon pass stays above its
group's least gets more processes, up to --max-processes); and of the
knob's way from studies.yaml to the launcher and to the dry run's
prediction (tests/test_prediction.py has the prediction's numbers).

Run by pytest from the repository root (`python3 -m pytest tests/`).
"""

import json
import stat

import pytest

from experiments import launch, studies

# a stand-in renderer: the Nth call (COUNTER) logs its method to ORDER_LOG
# and writes two repeats whose totals are TIMES[N] + 0.1 and TIMES[N];
# ODD_IMAGE=N / ODD_WORK=N: the Nth call's image / work counter differs;
# REFUSE=METHOD: that method exits 2; TRACES: the Nth call's least photon
# pass is TRACES[N] (else TIMES[N] / 10); TRACE_WORK=METHOD: that method's
# photon pass reports other work
FAKE_PM = """#!/usr/bin/python3
import json, os, sys
a = sys.argv[1:]
out, stats, method = a[a.index("-o") + 1], a[a.index("--stats") + 1], a[a.index("--method") + 1]
path = os.environ["COUNTER"]
n = (int(open(path).read()) if os.path.exists(path) else 0) + 1
open(path, "w").write(str(n))
open(os.environ["ORDER_LOG"], "a").write(method + "\\n")
if os.environ.get("REFUSE") == method:
    sys.stderr.write("refused: not applicable\\n")
    sys.exit(2)
t = float(os.environ["TIMES"].split()[n - 1])
odd = lambda key: os.environ.get(key) == str(n)
open(out, "w").write("other" if odd("ODD_IMAGE") else "image of " + method)
tr = float(os.environ["TRACES"].split()[n - 1]) if os.environ.get("TRACES") else t / 10
reps = {"trace": [tr + 0.01, tr], "total": [t + 0.1, t]}
rays = (2 if odd("ODD_WORK") else 1) + (10 if os.environ.get("TRACE_WORK") == method else 0)
json.dump({"status": "ok", "method": method, "time_s": {p: min(v) for p, v in reps.items()}, "repeats": 2,
           "time_s_cold": {p: v[0] for p, v in reps.items()}, "time_s_median": {p: sum(v) / 2 for p, v in reps.items()},
           "time_s_repeats": reps, "minor_faults_repeats": [100 * n, n], "work": {"trace": {"rays": rays}},
           "mean_radiance": [0.5, 0.5, 0.5]}, open(stats, "w"))
"""

CELL = "paper-p1000-n10"


def run_group(tmp_path, monkeypatch, processes, times, seed=1, extra=(), env=None):
    """One group (conventional, precomputed) at SEED with --processes
    PROCESSES, the fake renderer's totals TIMES; returns the exit code, the
    methods in the order they ran and the run root."""
    pm = tmp_path / "pm"
    pm.write_text(FAKE_PM)
    pm.chmod(pm.stat().st_mode | stat.S_IXUSR)
    for name in ("counter", "order"):
        if (tmp_path / name).exists():
            (tmp_path / name).unlink()
    monkeypatch.setenv("COUNTER", str(tmp_path / "counter"))
    monkeypatch.setenv("ORDER_LOG", str(tmp_path / "order"))
    monkeypatch.setenv("TIMES", " ".join(map(str, times)))
    for key in ("ODD_IMAGE", "ODD_WORK", "REFUSE", "TRACES", "TRACE_WORK"):
        monkeypatch.delenv(key, raising=False)
    for key, value in (env or {}).items():
        monkeypatch.setenv(key, value)
    root = tmp_path / "runs"
    rc = launch.main(["--pm", str(pm), "--scene", "s.scene", "--width", "8", "--height", "6", "--subpixels", "1",
                      "--repeats", "2", "--of", "2", "--stem", f"{CELL}/seed{seed}", "--processes", str(processes),
                      "--member", str(root), "conventional", "", "1", "--member", str(root), "precomputed", "", "2"]
                     + list(extra))
    order = (tmp_path / "order").read_text().split() if (tmp_path / "order").exists() else []
    return rc, order, root


def files(root, method, seed=1):
    d = root / f"{method}-{CELL}"
    return (json.loads((d / f"seed{seed}.stats.json").read_text()), json.loads((d / f"seed{seed}.run.json").read_text()))


def test_rounds_reverse_and_times_are_minima_over_processes(tmp_path, monkeypatch):
    """P = 2, seed 1: conventional, precomputed, precomputed, conventional;
    each render's time_s is the least repeat of both processes (the second
    conventional process, 0.7, is faster than its first, 0.9), every repeat
    is kept in the order run (its page faults too), the cold time is the
    first process's first repeat; the record's cpu_s is the least process's and it names each
    process's place. Control: seed 2 starts with precomputed."""
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [0.9, 0.5, 0.6, 0.7])
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed", "conventional"]
    st, rec = files(root, "conventional")
    assert st["time_s"] == {"trace": pytest.approx(0.07), "total": pytest.approx(0.7)}
    assert st["time_s_repeats"]["total"] == pytest.approx([1.0, 0.9, 0.8, 0.7])
    assert st["repeats"] == 4 and st["processes"] == 2
    assert st["time_s_cold"]["total"] == pytest.approx(1.0)
    assert st["time_s_median"]["total"] == pytest.approx(0.85)
    assert st["time_s_processes"]["total"] == pytest.approx([0.9, 0.7])
    assert st["minor_faults_repeats"] == [100, 1, 400, 4]  # every repeat's, in the order run
    assert rec["processes"] == 2 and rec["pair_pos_processes"] == [1, 2] and rec["pair_pos"] == 1
    assert rec["cpu_s"] == min(rec["cpu_s_processes"]) and len(rec["cpu_s_processes"]) == 2
    st, rec = files(root, "precomputed")
    assert st["time_s"]["total"] == pytest.approx(0.5) and rec["pair_pos_processes"] == [2, 1]
    assert (root / f"conventional-{CELL}" / "seed1.exr").read_text() == "image of conventional"
    # a key a line, as the renderer writes (tests/slurm.test.sh compares stats but for the time_s* lines)
    lines = (root / f"conventional-{CELL}" / "seed1.stats.json").read_text().splitlines()
    assert any(l.startswith('  "time_s": {"trace": ') and l.endswith('"total": 0.7},') for l in lines)
    assert len(lines) == len(st) + 2
    assert not list(root.glob("*/*.tmp*")), "temporary files left"
    rc, order, _ = run_group(tmp_path, monkeypatch, 2, [0.9, 0.5, 0.6, 0.7], seed=2)
    assert rc == 0 and order == ["precomputed", "conventional", "conventional", "precomputed"]


def test_three_processes_alternate(tmp_path, monkeypatch):
    rc, order, root = run_group(tmp_path, monkeypatch, 3, [1, 1, 1, 1, 1, 1])
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed", "conventional", "conventional", "precomputed"]
    assert files(root, "precomputed")[0]["repeats"] == 6


def test_one_process_keeps_the_renderers_file(tmp_path, monkeypatch):
    """P = 1: the renderer's stats file itself (not rewritten), no
    processes key in the stats or the record."""
    rc, order, root = run_group(tmp_path, monkeypatch, 1, [0.9, 0.5])
    assert rc == 0 and order == ["conventional", "precomputed"]
    st, rec = files(root, "conventional")
    assert "processes" not in st and "processes" not in rec and st["repeats"] == 2
    assert (root / f"conventional-{CELL}" / "seed1.stats.json").read_text().startswith('{"status": "ok"')


@pytest.mark.parametrize("key", ["ODD_IMAGE", "ODD_WORK"])
def test_processes_that_disagree_fail_the_group(tmp_path, monkeypatch, capsys, key):
    """The third process (precomputed's second) makes another image, or
    another work counter: the group fails (exit 1) naming the render, and
    leaves neither a record nor a temporary file. Control: the same run
    with the odd call beyond the last process passes."""
    rc, _, root = run_group(tmp_path, monkeypatch, 2, [1, 1, 1, 1], env={key: "3"})
    assert rc == 1
    assert "precomputed" in capsys.readouterr().err
    assert not list(root.glob("*/*.run.json")) and not list(root.glob("*/*.tmp*"))
    rc, _, root = run_group(tmp_path, monkeypatch, 2, [1, 1, 1, 1], env={key: "5"})
    assert rc == 0 and len(list(root.glob("*/*.run.json"))) == 2


def test_refused_and_once_timed_members_run_once(tmp_path, monkeypatch):
    """A member the renderer refuses (exit 2) is asked once and recorded as
    refused, the other runs in both processes; a member of --member-repeats
    (timed once) runs in one process."""
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [1, 1, 1, 1], env={"REFUSE": "conventional"})
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed"]
    assert json.loads((root / f"conventional-{CELL}" / "seed1.run.json").read_text())["exit"] == 2
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [1, 1, 1, 1],
                                extra=["--member-repeats", str(tmp_path / "runs"), "conventional", "1"])
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed"]
    assert "processes" not in files(root, "conventional")[1]


GAUGE = ["--gauge", "4", "--max-processes", "4"]


def test_gauge_adds_a_process_to_the_member_that_never_ran_at_best_speed(tmp_path, monkeypatch):
    """Seed 1, A B B A: precomputed's photon passes (0.12, 0.12) are 20%
    above conventional's least (0.10): precomputed runs once more (0.10)
    and then nothing more; its time is the least over its three processes,
    its record says the gauge added one, conventional's none."""
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [1, 0.9, 0.8, 1, 0.5], extra=GAUGE,
                                env={"TRACES": "0.10 0.12 0.12 0.11 0.10"})
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed", "conventional", "precomputed"]
    st, rec = files(root, "precomputed")
    assert st["processes"] == 3 and st["time_s"]["trace"] == pytest.approx(0.10)
    assert st["time_s"]["total"] == pytest.approx(0.5) and rec["processes"] == 3
    assert rec["gauge_added"] == 1 and rec["pair_pos_processes"] == [2, 1, 2]
    st, rec = files(root, "conventional")
    assert st["processes"] == 2 and rec["gauge_added"] == 0
    assert not list(root.glob("*/*.tmp*")), "temporary files left"


def test_gauge_stops_at_max_processes(tmp_path, monkeypatch):
    """Precomputed's photon pass stays 20% slower: it runs until it has run
    in --max-processes 4, and the group still finishes."""
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [1] * 8, extra=GAUGE,
                                env={"TRACES": "0.10 0.12 0.12 0.10 0.12 0.12 0.12 0.12"})
    assert rc == 0 and order == ["conventional", "precomputed", "precomputed", "conventional",
                                 "precomputed", "precomputed"]
    assert files(root, "precomputed")[1]["gauge_added"] == 2


@pytest.mark.parametrize("case", ["inside", "off", "other_work", "no_cap_room", "too_short"])
def test_gauge_controls_add_nothing(tmp_path, monkeypatch, case):
    """No process is added when the slower member's least photon pass is
    within 4% of the group's (0.1035 against 0.10), when the gauge is off
    (--gauge 0, 20% slower), when the members' photon passes do different
    work (no gauge), when --max-processes leaves no room, or when the
    group's least photon pass is shorter than GAUGE_MIN_S (20% slower)."""
    extra = {"inside": GAUGE, "off": ["--gauge", "0", "--max-processes", "4"], "other_work": GAUGE,
             "no_cap_room": ["--gauge", "4", "--max-processes", "2"], "too_short": GAUGE}[case]
    traces = {"inside": "0.10 0.1035 0.1035 0.10",
              "too_short": " ".join(str(x * launch.GAUGE_MIN_S) for x in (0.9, 1.08, 1.08, 0.9))
              }.get(case, "0.10 0.12 0.12 0.10")
    env = {"TRACES": traces + " 0.10 0.10", **({"TRACE_WORK": "precomputed"} if case == "other_work" else {})}
    rc, order, root = run_group(tmp_path, monkeypatch, 2, [1] * 6, extra=extra, env=env)
    assert rc == 0 and len(order) == 4
    assert files(root, "precomputed")[0]["processes"] == 2


def test_bad_gauge_refused(tmp_path, monkeypatch, capsys):
    for extra, text in ((["--gauge", "-1"], "--gauge -1"), (["--max-processes", "1"], "--max-processes 1")):
        with pytest.raises(SystemExit) as e:
            run_group(tmp_path, monkeypatch, 2, [1], extra=extra)
        assert e.value.code == 2 and text in capsys.readouterr().err


def test_bad_processes_refused(tmp_path, monkeypatch, capsys):
    with pytest.raises(SystemExit) as e:
        run_group(tmp_path, monkeypatch, 0, [1])
    assert e.value.code == 2 and "--processes 0" in capsys.readouterr().err


def words(study, **knobs):
    g = studies.load(study, knobs).grids[0]
    return g, g.launch_words("paper-p1000-n10/seed1")


def test_knob_reaches_the_launcher():
    """TIME_PROCESSES (default 2) is every timed study's --processes; an
    untimed study renders in one process; a bad value is refused."""
    _, w = words("table1")
    assert w[w.index("--processes") + 1] == "2"
    _, w = words("table1", TIME_PROCESSES="3")
    assert w[w.index("--processes") + 1] == "3"
    _, w = words("bias", TIME_PROCESSES="3")
    assert w[w.index("--processes") + 1] == "1"
    for bad in ("0", "two", "-1"):
        with pytest.raises(studies.StudyError, match="TIME_PROCESSES=.*positive number of processes"):
            words("table1", TIME_PROCESSES=bad)


def test_gauge_knobs_reach_the_launcher():
    """TIME_GAUGE (default 4) and TIME_PROCESSES_MAX (default 4) are every
    timed study's --gauge and --max-processes (never below
    TIME_PROCESSES: no room); an untimed study has no gauge; a bad value
    is refused."""
    _, w = words("table1")
    assert w[w.index("--gauge") + 1] == "4" and w[w.index("--max-processes") + 1] == "4"
    _, w = words("table1", TIME_GAUGE="2.5", TIME_PROCESSES_MAX="6")
    assert w[w.index("--gauge") + 1] == "2.5" and w[w.index("--max-processes") + 1] == "6"
    _, w = words("bias")
    assert w[w.index("--gauge") + 1] == "0" and w[w.index("--max-processes") + 1] == "1"
    for bad in ("-1", "four", "1000"):
        with pytest.raises(studies.StudyError, match="TIME_GAUGE="):
            words("table1", TIME_GAUGE=bad)
    _, w = words("table1", TIME_PROCESSES="9")
    assert w[w.index("--max-processes") + 1] == "9"
    for bad in ("0", "x"):
        with pytest.raises(studies.StudyError, match="TIME_PROCESSES_MAX=.*positive number of processes"):
            words("table1", TIME_PROCESSES_MAX=bad)


def test_once_timed_renders_run_in_one_process():
    """gather's one_repeat renders (12,288 eye samples x N = 4 x n at or
    above 983,040: n >= 20): one process (--member-repeats ... 1), even
    when TIME_REPEATS is 1; the lighter ones and precomputed's
    TIME_PROCESSES."""
    g = studies.load("gather", {"SIZE": "64x48", "SEEDS": "2", "PHOTONS": "2000", "NNS": "10 20",
                                "SCENES": "scenes/cornell.scene", "GATHERS": "4", "GATHER_CORNELL_SIZES": "64x48",
                                "ONE_REPEAT_WORK": "983040", "TIME_REPEATS": "1"}).by_name["cornell-64x48-N4"]
    assert g.processes("conventional", 20) == 1 and g.processes("precomputed", 20) == 2
    assert g.processes("conventional", 19) == 2
    assert g.member_words(g.root, "conventional", 20, 1)[-4:] == ["--member-repeats", g.root, "conventional", "1"]
    assert "--member-repeats" not in g.member_words(g.root, "conventional", 19, 1)
