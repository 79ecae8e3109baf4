"""Tests of experiments/launch.py's busy loop (--busy-loop, make
reproducibility's third run): it runs for the whole group and is ended
after it, whether the group finishes or fails, and each record says so;
and of its CPU pinning (--cpu, the study knob TIME_CPU): every render on
the one CPU, the record naming it, the busy loop on another.
The launcher's --repeats is tested in tests/test_time_repeats.py.

Run by pytest from the repository root (`python3 -m pytest tests/`).
"""

import json
import os
import stat
import time

import pytest


from experiments import launch

FAKE_PM = """#!/bin/sh
# a stand-in renderer: fails when FAIL is set, else writes an image and a stats file
out=""; stats=""
while [ $# -gt 0 ]; do
  case "$1" in -o) out="$2"; shift ;; --stats) stats="$2"; shift ;; esac
  shift
done
[ -n "$FAIL" ] && exit 1
: > "$out"
printf '{"time_s": {"total": 0.5}}\\n' > "$stats"
"""


class FakeLoop:
    """Stands in for the busy process: records its kill."""

    def __init__(self, log):
        self.log = log
        log.append("started")

    def kill(self):
        self.log.append("killed")

    def wait(self):
        self.log.append("waited")


def launch_group(tmp_path, busy):
    pm = tmp_path / "pm"
    pm.write_text(FAKE_PM)
    pm.chmod(pm.stat().st_mode | stat.S_IXUSR)
    root = tmp_path / "runs"
    args = ["--pm", str(pm), "--scene", "s.scene", "--width", "8", "--height", "6", "--subpixels", "1",
            "--repeats", "1", "--of", "2", "--stem", "paper-p1000-n10/seed1",
            "--member", str(root), "conventional", "", "1", "--member", str(root), "precomputed", "", "2"]
    return launch.main(args + (["--busy-loop"] if busy else [])), root


def test_busy_loop_spans_the_group(tmp_path, monkeypatch):
    """With --busy-loop one loop starts before the group and is killed after
    it, and both records say busy_loop 1; control: without it, no loop and
    busy_loop 0."""
    log = []
    monkeypatch.setattr(launch, "busy_loop", lambda avoid=None: FakeLoop(log))
    rc, root = launch_group(tmp_path, True)
    assert rc == 0 and log == ["started", "killed", "waited"]
    for m in ("conventional", "precomputed"):
        assert json.loads((root / f"{m}-paper-p1000-n10" / "seed1.run.json").read_text())["busy_loop"] == 1
    log.clear()
    rc, root = launch_group(tmp_path, False)
    assert rc == 0 and log == []
    assert json.loads((root / "precomputed-paper-p1000-n10" / "seed1.run.json").read_text())["busy_loop"] == 0


def test_busy_loop_ends_when_the_group_fails(tmp_path, monkeypatch):
    """A failing render still ends the loop, and leaves no record."""
    log = []
    monkeypatch.setattr(launch, "busy_loop", lambda avoid=None: FakeLoop(log))
    monkeypatch.setenv("FAIL", "1")
    rc, root = launch_group(tmp_path, True)
    assert rc == 1 and log == ["started", "killed", "waited"]
    assert not list(root.glob("*/*.run.json"))


def test_busy_loop_spins():
    """The real loop is a running process that uses CPU, and kill ends it."""
    p = launch.busy_loop()
    try:
        time.sleep(0.3)
        assert p.poll() is None
        with open(f"/proc/{p.pid}/stat") as f:
            utime = int(f.read().split()[13])
        assert utime > 0
    finally:
        p.kill()
        p.wait()
    assert p.poll() is not None



AFFINITY_PM = FAKE_PM.replace('[ -n "$FAIL" ] && exit 1',
                              '[ -n "$FAIL" ] && exit 1\ngrep Cpus_allowed_list /proc/self/status >> "$AFFINITY_LOG"')


def launch_pinned(tmp_path, monkeypatch, cpu):
    """One group of two renders with --cpu CPU; returns the exit code, the
    renderer's CPU lists as it saw them and the records' cpu fields."""
    pm = tmp_path / "pm"
    pm.write_text(AFFINITY_PM)
    pm.chmod(pm.stat().st_mode | stat.S_IXUSR)
    log = tmp_path / "affinity.log"
    if log.exists():
        log.unlink()
    monkeypatch.setenv("AFFINITY_LOG", str(log))
    root = tmp_path / "runs"
    rc = launch.main(["--pm", str(pm), "--scene", "s.scene", "--width", "8", "--height", "6", "--subpixels", "1",
                      "--repeats", "1", "--of", "2", "--stem", "paper-p1000-n10/seed1", "--cpu", cpu,
                      "--member", str(root), "conventional", "", "1", "--member", str(root), "precomputed", "", "2"])
    seen = [line.split()[-1] for line in log.read_text().splitlines()] if log.exists() else []
    cpus = [json.loads((root / f"{m}-paper-p1000-n10" / "seed1.run.json").read_text())["cpu"]
            for m in ("conventional", "precomputed")]
    return rc, seen, cpus


def test_cpu_first_pins_every_render(tmp_path, monkeypatch):
    """--cpu first: both renders run on the lowest CPU the launcher may use
    and their records name it; control: --cpu none leaves them every CPU
    (when there is more than one) and the records say null."""
    first = min(os.sched_getaffinity(0))
    rc, seen, cpus = launch_pinned(tmp_path, monkeypatch, "first")
    assert rc == 0 and seen == [str(first)] * 2 and cpus == [first, first]
    rc, seen, cpus = launch_pinned(tmp_path, monkeypatch, "none")
    assert rc == 0 and cpus == [None, None] and len(seen) == 2
    if len(os.sched_getaffinity(0)) > 1:
        assert seen[0] != str(first)


def test_cpu_outside_the_set_is_refused(tmp_path, monkeypatch, capsys):
    """A CPU the launcher may not run on, or a word that is no CPU, is
    refused before any render (exit 2, the allowed CPUs named)."""
    for bad in (str(max(os.sched_getaffinity(0)) + 1000), "fast"):
        try:
            launch_pinned(tmp_path, monkeypatch, bad)
        except SystemExit as e:
            assert e.code == 2
        else:
            raise AssertionError(f"--cpu {bad} was not refused")
    err = capsys.readouterr().err
    assert "not a CPU this process may run on" in err and "first, none, or a CPU number" in err
    assert not list((tmp_path / "runs").glob("*/*.run.json"))


def test_busy_loop_runs_on_another_cpu():
    """The busy loop beside a render pinned to a CPU runs on another one
    (where there is one); control: without a CPU to avoid it may use all."""
    allowed = os.sched_getaffinity(0)
    if len(allowed) < 2:
        pytest.skip("one CPU: no other for the busy loop")
    first = min(allowed)
    for avoid, want in ((first, lambda got: first not in got and len(got) == 1), (None, lambda got: got == allowed)):
        p = launch.busy_loop(avoid)
        try:
            time.sleep(0.1)
            got = os.sched_getaffinity(p.pid)
        finally:
            p.kill()
            p.wait()
        assert want(got), (avoid, got)
