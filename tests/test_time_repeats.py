"""Tests of the study knob TIME_REPEATS (experiments/studies.py) and the
render launcher's --repeats (experiments/launch.py): every timed render's
command line carries the knob's --repeats (default auto), an untimed study's
renders carry --repeats 1, a value other than auto or a positive count is
refused with the reason, and REPEATS stays a retired name for SEEDS. The
launcher is run end to end with a stand-in renderer that records the words
it was given, so the test fails when the option does not reach the render."""

import json
import os
import shlex
import stat
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))
from experiments import launch, studies  # noqa: E402


def words_after(cmd, flag):
    """The words following each FLAG in the shell command line CMD."""
    w = shlex.split(cmd)
    return [w[i + 1] for i, x in enumerate(w) if x == flag]


def test_default_is_auto_for_timed_studies():
    s = studies.load("table1", {"SIZE": "64x48", "SEEDS": "2"})
    cmd = s.launch_command(s.root, ["conventional", "precomputed"], "paper", "50000", "10", 1)
    assert words_after(cmd, "--repeats") == ["auto"]


@pytest.mark.parametrize("value", ["1", "3", "12", "auto"])
def test_knob_reaches_every_timed_render(value):
    for sid in ("table1", "caustic"):
        s = studies.load(sid, {"TIME_REPEATS": value})
        cmd = s.launch_command(s.root, ["precomputed"], "corrected", "100000", "100", 2)
        assert words_after(cmd, "--repeats") == [value], (sid, cmd)


def test_untimed_study_renders_once():
    """estimator-bias (timed: false) compares no times: one run per render,
    whatever TIME_REPEATS says."""
    s = studies.load("bias", {"TIME_REPEATS": "7"})
    assert not s.timed
    cmd = s.launch_command(s.root, ["conventional"], "paper", "50000", "5", 1)
    assert words_after(cmd, "--repeats") == ["1"]


@pytest.mark.parametrize("bad", ["0", "-1", "2.5", "fast", "", "auto3", "03x"])
def test_bad_value_refused(bad):
    with pytest.raises(studies.StudyError, match=r"TIME_REPEATS=.*auto or a positive number"):
        studies.load("table1", {"TIME_REPEATS": bad})


def test_repeats_stays_retired():
    with pytest.raises(studies.StudyError, match="REPEATS is gone.*SEEDS"):
        studies.load("table1", {"REPEATS": "3"})


def test_launch_command_carries_repeats():
    cmd = launch.command("pm", "s.scene", "precomputed", "paper", 1000, 10, 1, 8, 6, 1, "1", "", "out", "4")
    assert cmd[cmd.index("--repeats") + 1] == "4"
    with pytest.raises(launch.LaunchError, match="auto or a positive number"):
        launch.command("pm", "s.scene", "precomputed", "paper", 1000, 10, 1, 8, 6, 1, "1", "", "out", "0")


FAKE_PM = """#!/bin/sh
# a stand-in renderer: records its words, writes an image and a stats file
out=""; stats=""
printf '%s\\n' "$@" > "$ARGV_LOG"
while [ $# -gt 0 ]; do
  case "$1" in -o) out="$2"; shift ;; --stats) stats="$2"; shift ;; esac
  shift
done
: > "$out"
printf '{"time_s": {"total": 0.5}}\\n' > "$stats"
"""


def run_launcher(tmp_path, monkeypatch, repeats):
    pm = tmp_path / "pm"
    pm.write_text(FAKE_PM)
    pm.chmod(pm.stat().st_mode | stat.S_IXUSR)
    log = tmp_path / "argv"
    monkeypatch.setenv("ARGV_LOG", str(log))
    root = tmp_path / "runs"
    args = ["--pm", str(pm), "--scene", "s.scene", "--width", "8", "--height", "6", "--subpixels", "1",
            "--of", "1", "--stem", "paper-p1000-n10/seed1", "--member", str(root), "precomputed", "", "1"]
    if repeats is not None:
        args = ["--repeats", repeats] + args
    rc = launch.main(args)
    return rc, (log.read_text().split("\n") if log.exists() else []), root


def test_launcher_passes_repeats_to_the_renderer(tmp_path, monkeypatch, capsys):
    rc, argv, root = run_launcher(tmp_path, monkeypatch, "5")
    assert rc == 0
    assert argv[argv.index("--repeats") + 1] == "5"
    rec = json.loads((root / "precomputed-paper-p1000-n10" / "seed1.run.json").read_text())
    assert "--repeats 5" in rec["command"]


@pytest.mark.parametrize("bad", ["0", "many", None])
def test_launcher_refuses_bad_or_missing_repeats(tmp_path, monkeypatch, capsys, bad):
    """A bad value, or none (the study's TIME_REPEATS is the one default),
    exits 2 before anything renders."""
    with pytest.raises(SystemExit) as e:
        run_launcher(tmp_path, monkeypatch, bad)
    assert e.value.code == 2
    assert not (tmp_path / "argv").exists()
    if bad is not None:
        assert "auto or a positive number" in capsys.readouterr().err


def test_phase_sums_are_minima_of_sums():
    """collect.py's sums of phases: the minimum over repeats of each repeat's
    sum, not the sum of per-phase minima (which is smaller here: the
    minima come from different repeats)."""
    from experiments.analysis import collect
    st = {"time_s": {"precompute": 1.0, "render": 2.0},
          "time_s_repeats": {"precompute": [1.0, 1.5, 3.0], "render": [2.5, 2.0, 2.1]}}
    assert collect.repeat_min(st, ("precompute", "render")) == 3.5
    # one timed run (no repeats recorded): the sum
    assert collect.repeat_min({"time_s": {"trace": 0.25, "build": 0.5}}, ("trace", "build")) == 0.75


def test_launcher_member_repeats_override_one_member(tmp_path, monkeypatch, capsys):
    """--member-repeats ROOT METHOD R: that member renders with --repeats R,
    whatever --repeats says; one naming no member is refused (exit 2)."""
    root = tmp_path / "runs"
    rc, argv, _ = run_launcher(tmp_path, monkeypatch, "5")
    assert argv[argv.index("--repeats") + 1] == "5"  # control: without it, --repeats
    monkeypatch.setattr(sys, "argv", ["launch"])
    pm = tmp_path / "pm"
    base = ["--pm", str(pm), "--scene", "s.scene", "--width", "8", "--height", "6", "--subpixels", "1", "--repeats", "5",
            "--of", "1", "--stem", "paper-p1000-n10/seed1", "--member", str(root), "precomputed", "", "1"]
    assert launch.main(base + ["--member-repeats", str(root), "precomputed", "1"]) == 0
    argv = (tmp_path / "argv").read_text().split("\n")
    assert argv[argv.index("--repeats") + 1] == "1"
    with pytest.raises(SystemExit) as e:
        launch.main(base + ["--member-repeats", str(root), "conventional", "1"])
    assert e.value.code == 2 and "no such --member" in capsys.readouterr().err
