"""Unit tests of experiments/regenerate.py (`make results`): the pinned
renderer, the log, and the check that every render and every results file
came from one regeneration.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test`); each check has its negative control.
"""

import hashlib
import json
import os
import shutil
import subprocess
import tempfile

import pytest

from experiments import regenerate


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def fake_results(d, commit="abcdef123456", render_commits=(("abcdef123456", "clean"),), md_commits=("abcdef1",),
                 flags=("-O2",)):
    """A results directory with a pinned renderer of COMMIT, one render per
    RENDER_COMMITS and one Markdown file per MD_COMMITS."""
    binary = os.path.join(d, "runs", ".renderer", "photonmap")
    write(binary, "binary")
    sha = hashlib.sha256(b"binary").hexdigest()
    write(binary + ".commit", f"commit {commit}0000\nsha256 {sha}\npinned now\n")
    for i, (c, tree) in enumerate(render_commits):
        write(os.path.join(d, "runs", "g", f"seed{i}.stats.json"),
              json.dumps({"provenance": {"commit": c, "tree": tree, "flags": flags[i % len(flags)]}}))
    for i, c in enumerate(md_commits):
        write(os.path.join(d, f"study{i}", "x.md"), f"Machine: x; commit `{c}`; 2026-12-05.\n")


def test_check_one_regeneration():
    """No problem when every render is the pinned commit's from a clean tree
    and every file names one commit; controls: a render by another commit, a
    dirty build, two commits among the files: each named."""
    with tempfile.TemporaryDirectory() as d:
        fake_results(d)
        assert regenerate.check(d) == []
    with tempfile.TemporaryDirectory() as d:
        fake_results(d, render_commits=(("abcdef123456", "clean"), ("0123456789ab", "clean")))
        (p,) = regenerate.check(d)
        assert "1 render(s)" in p and "0123456789ab" in p
    with tempfile.TemporaryDirectory() as d:
        fake_results(d, render_commits=(("abcdef123456", "dirty"),))
        assert "dirty" in regenerate.check(d)[0]
    with tempfile.TemporaryDirectory() as d:
        fake_results(d, render_commits=(("abcdef123456", "clean"),) * 2, flags=("-O2", "-O0"))
        (p,) = regenerate.check(d)
        assert "2 sets of flags" in p
    with tempfile.TemporaryDirectory() as d:
        # studies regenerated on different machines name different commits,
        # each study one (no problem); two commits in one study's files are
        fake_results(d, md_commits=("abcdef1", "abcdef1", "9999999"))
        assert regenerate.check(d) == []
        write(os.path.join(d, "study2", "y.md"), "commit `abcdef1`\n")
        (p,) = regenerate.check(d)
        assert "study2/ name 2 commits" in p and "9999999: study2/x.md" in p and "study0" not in p
    with tempfile.TemporaryDirectory() as d:
        # a table's "Commit: `...`" counts; a study's file naming none is a
        # problem; the hand-written README.md is exempt
        fake_results(d)
        write(os.path.join(d, "study0", "t.md"), "- Commit: `abcdef1` when the table was written\n")
        write(os.path.join(d, "README.md"), "# results\n")
        assert regenerate.check(d) == []
        write(os.path.join(d, "study0", "t.md"), "- Commit: `9999999` when the table was written\n")
        assert "9999999: study0/t.md" in regenerate.check(d)[0]
        write(os.path.join(d, "study0", "t.md"), "no provenance\n")
        (p,) = regenerate.check(d)
        assert "1 results file(s) name no commit: study0/t.md" in p


# two pins of the same renderer sources (two machines), and one of other sources
SAME_SOURCES = {"abcdef1", "1111111"}


def same(a, b):
    """same_renderer of the tests: abcdef1... and 1111111... hold the same sources."""
    return a[:7] == b[:7] or {a[:7], b[:7]} == SAME_SOURCES


def log_row(target, renderer, status="ok", ended="t1"):
    return {"started": "t0", "ended": ended, "target": target, "commit": "c", "renderer": renderer,
            "status": status, "renders": "1", "seconds": "1", "why": ""}


def test_check_log_every_target_on_the_renderer():
    """With a log, every study target's last attempt must have ended ok on
    the regeneration's renderer sources; a target landed from another pin of
    the same sources counts. Controls: a target with no attempt, one whose
    last attempt failed after an ok one, one by other sources: each named."""
    with tempfile.TemporaryDirectory() as d:
        fake_results(d)
        rows = [log_row(t, "111111111111" if i % 2 else "abcdef123456") for i, t in enumerate(regenerate.TARGETS)]
        regenerate.write_log(d, rows)
        assert regenerate.check(d, same=same) == []
        regenerate.write_log(d, rows[1:])
        (p,) = regenerate.check(d, same=same)
        assert p == f"{regenerate.TARGETS[0]}: no attempt in the log"
        regenerate.write_log(d, rows + [log_row("caustic", "abcdef123456", status="exit 1")])
        (p,) = regenerate.check(d, same=same)
        assert p.startswith("caustic: its last attempt") and "exit 1" in p
        regenerate.write_log(d, rows + [log_row("gather", "2222222")])
        (p,) = regenerate.check(d, same=same)
        assert p.startswith("gather: rendered by 2222222") and "differ" in p
        # without runs/ (a clone) the log's last renderer is the regeneration's
        shutil.rmtree(os.path.join(d, "runs"))
        regenerate.write_log(d, rows + [log_row("findings", "2222222")])
        problems = regenerate.check(d, same=same)
        assert len(problems) == len(regenerate.TARGETS) - 1 and all("differ" in p for p in problems)


def test_landed_targets():
    """landed(): a target whose last attempt ended ok on another pin of the
    same renderer sources; not one of this pin (it resumes here), of other
    sources, failed, or killed after an ok attempt."""
    rows = [log_row("reproduce-table", "111111111111"), log_row("figures", "abcdef123456"),
            log_row("caustic", "2222222"), log_row("scenes", "111111111111", status="exit 1"),
            log_row("gather", "111111111111"), log_row("gather", "111111111111", status="running", ended="")]
    assert list(regenerate.landed(rows, "abcdef1234560000", same=same)) == ["reproduce-table"]


def test_run_skips_landed_targets(monkeypatch, capsys):
    """make results on a new machine skips the studies landed from another
    pin of the same renderer and runs the rest; --only runs them again."""
    with tempfile.TemporaryDirectory() as d:
        regenerate.write_log(d, [log_row("reproduce-table", "111111111111")])
        ran = []
        monkeypatch.setattr(regenerate, "pin", lambda results: ("pm", "abcdef1234560000"))
        monkeypatch.setattr(regenerate, "git", lambda *a: "headcommit00")
        monkeypatch.setattr(regenerate, "same_renderer", same)
        monkeypatch.setattr(regenerate.subprocess, "run",
                            lambda cmd, **kw: ran.append(cmd[2]) or subprocess.CompletedProcess(cmd, 0))
        assert regenerate.run(d, ["reproduce-table", "figures"], "why") == 0
        assert ran == ["figures"] and "reproduce-table skipped" in capsys.readouterr().out
        assert regenerate.run(d, ["reproduce-table"], "why", skip_landed=False) == 0
        assert ran == ["figures", "reproduce-table"]


def git(d, *args):
    subprocess.run(["git", "-C", d, *args], check=True, capture_output=True)


def test_pin_refuses_a_changed_renderer(monkeypatch):
    """A pinned regeneration goes on while the renderer's sources are the
    pinned commit's (a change elsewhere, or to renderer/'s Markdown, is fine)
    and stops, naming the file,
    once they differ; control: an altered pinned binary is refused too."""
    with tempfile.TemporaryDirectory() as d:
        git(d, "init", "-q")
        git(d, "config", "user.email", "t@t")
        git(d, "config", "user.name", "t")
        write(os.path.join(d, "renderer", "a.c"), "int a;\n")
        write(os.path.join(d, "README.md"), "x\n")
        git(d, "add", ".")
        git(d, "commit", "-q", "-m", "one")
        head = subprocess.run(["git", "-C", d, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
        res = os.path.join(d, "res")
        fake_results(res, commit=head[:-4])  # fake_results appends 0000: write the full hash instead
        binary = os.path.join(res, "runs", ".renderer", "photonmap")
        sha = hashlib.sha256(b"binary").hexdigest()
        write(binary + ".commit", f"commit {head}\nsha256 {sha}\n")
        monkeypatch.chdir(d)
        assert regenerate.pin(res) == (binary, head)
        write(os.path.join(d, "README.md"), "y\n")
        write(os.path.join(d, "Makefile"), "all:\n")
        write(os.path.join(d, "renderer", "README.md"), "the renderer's documentation\n")
        git(d, "add", ".")
        git(d, "commit", "-q", "-m", "docs and the Makefile")
        assert regenerate.pin(res) == (binary, head)
        write(os.path.join(d, "renderer", "a.c"), "int b;\n")
        git(d, "commit", "-q", "-am", "renderer")
        with pytest.raises(regenerate.RegenError, match=r"renderer changed since .*renderer/a\.c"):
            regenerate.pin(res)
        git(d, "reset", "-q", "--hard", "HEAD~1")
        write(binary, "other")
        with pytest.raises(regenerate.RegenError, match="not the binary pinned"):
            regenerate.pin(res)


def test_log_rows_round_trip():
    """The log's rows read back as written, and its Markdown has one row per attempt."""
    with tempfile.TemporaryDirectory() as d:
        rows = [{"started": "t0", "ended": "", "target": "reproduce-table", "commit": "c", "renderer": "r",
                 "status": "running", "renders": "", "seconds": "", "why": "a | b"}]
        regenerate.write_log(d, rows)
        assert regenerate.read_log(d) == rows
        with open(os.path.join(d, "regeneration-log.md"), encoding="utf-8") as f:
            md = f.read()
        assert md.count("| reproduce-table |") == 1 and "a / b" in md
        # the totals per renderer: a killed attempt counts no time (control)
        rows += [{"started": "t1", "ended": "t2", "target": "figures", "commit": "c", "renderer": "r2",
                  "status": "ok", "renders": "3", "seconds": "7200", "why": ""},
                 {"started": "t3", "ended": "t4", "target": "caustic", "commit": "c", "renderer": "r2",
                  "status": "ok", "renders": "2", "seconds": "1800", "why": ""}]
        regenerate.write_log(d, rows)
        with open(os.path.join(d, "regeneration-log.md"), encoding="utf-8") as f:
            md = f.read()
        assert "- `r`: 1 unfinished attempt(s) (killed, or running now), their time not counted." in md
        assert "- `r2`: 2 finished attempt(s), 5 renders, 9000 s (2.5 h)." in md


def test_committed_results_are_one_regeneration():
    """results/ as committed: when its log records every study target
    finished on one renderer's sources (pinned on one machine or several),
    every study's files name one commit and every render present was made
    by that renderer; skipped until then."""
    rows = regenerate.read_log("results")
    pin = rows[-1]["renderer"] if rows else None  # the last attempt's renderer: the regeneration's
    done = {t for t, r in regenerate.last_rows(rows).items()
            if r["status"] == "ok" and regenerate.same_renderer(r["renderer"], pin)}
    if not rows or set(regenerate.TARGETS) - done:
        pytest.skip("results/ holds no finished regeneration yet (results/regeneration-log.csv)")
    problems = [p for p in regenerate.check("results") if "render(s)" not in p or os.path.isdir("results/runs")]
    assert problems == []


def test_targets_order_calibrate_before_bench():
    """bench's repeats.md reads the cost model calibrate writes, and the
    findings read every file: calibrate runs before bench, findings last
    (control: the check sees a swapped order)."""
    def ordered(t):
        return t.index("calibrate") < t.index("bench") and t[-1] == "findings"
    assert ordered(regenerate.TARGETS)
    swapped = list(regenerate.TARGETS)
    i, j = swapped.index("calibrate"), swapped.index("bench")
    swapped[i], swapped[j] = swapped[j], swapped[i]
    assert not ordered(swapped)
