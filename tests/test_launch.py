"""Tests of experiments/launch.py's busy loop (--busy-loop, make
reproducibility's third run): it runs for the whole group and is ended
after it, whether the group finishes or fails, and each record says so.
The launcher's --repeats is tested in tests/test_time_repeats.py.

Run by pytest from the repository root (`python3 -m pytest tests/`).
"""

import json
import stat
import time


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
    monkeypatch.setattr(launch, "busy_loop", lambda: FakeLoop(log))
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
    monkeypatch.setattr(launch, "busy_loop", lambda: FakeLoop(log))
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

