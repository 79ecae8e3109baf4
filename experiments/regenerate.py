#!/usr/bin/python3
"""regenerate.py: every study of results/ regenerated on one renderer, resumable.

Owns `make results`: the renderer pinned once per regeneration, every study
target run in order with it, each attempt logged, and the checks that every
render and every results file came from that one regeneration.

    python3 -m experiments.regenerate run --results DIR [--only T ...] [--why TEXT]
    python3 -m experiments.regenerate check --results DIR

run: on the first call, build/photonmap (made by make from a committed
clean tree: uncommitted changes are refused, as the binary records them) is copied to
DIR/runs/.renderer/photonmap with photonmap.commit beside it (the commit and
the binary's SHA-256); every later call uses that copy, and refuses (exit 1)
when the renderer's sources at HEAD differ from the pinned commit's, since
the renders made so far would then be an older binary's (remove DIR/runs to
start over); the build's flags are in every render's provenance, and check
finds them all one. Then each study target of TARGETS (or --only's) runs as
`make TARGET RESULTS=DIR PM=PIN`; the workflow engine renders only what is
missing, so an interrupted regeneration resumes where it stopped, and a
finished study costs its analysis only. Every attempt is a row of
DIR/regeneration-log.csv (started, ended, target, HEAD commit, the pinned
renderer, exit status, renders made, seconds, why), written before the
target runs and again when it ends, and DIR/regeneration-log.md is written
from it; a killed attempt stays "running" in the log with no end.

check: every render under DIR/runs (its stats file's provenance) was made by
the pinned commit from a clean tree, and every Markdown file under DIR names
a commit, the same one (report.commit's "commit `abc1234`", or a table's
"Commit: `abc1234`"; README.md and stability/stability.md are written by
hand and exempt); prints what differs and exits 1 when not.
"""

import argparse
import csv
import datetime
import glob
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import time

# the study targets in the order a regeneration runs them: Table 1 first
# (the main job), its rerun next (make reproducibility renders runs b and
# busy after Table 1's), the figures drawn from Table 1, then the other
# studies, the cost model, the benchmarks (bench's repeats.md reads the cost
# model calibrate writes), and the findings last (they read every other file)
TARGETS = ("reproduce-table", "reproducibility", "figures", "estimator-bias", "caustic", "rep-study", "resolution",
           "scenes", "beyond", "gather", "stability", "accel", "calibrate", "bench", "findings")
# the sources of the renderer, as git pathspecs: a change here is a new
# renderer (its Markdown documentation is not; the build's flags are in every
# render's provenance, and check() finds them all one)
PINNED_SOURCES = ("renderer", ":(exclude)renderer/*.md")
LOG_FIELDS = ("started", "ended", "target", "commit", "renderer", "status", "renders", "seconds", "why")
COMMIT_RE = re.compile(r"[Cc]ommit:?\s+`([0-9a-f]{7,40})`")
# Markdown under results/ written by hand, not by a study: they name no commit
HANDWRITTEN = ("README.md", os.path.join("stability", "stability.md"))


class RegenError(Exception):
    """A regeneration cannot go on (its message says why and what to do)."""


def git(*args):
    """git's stdout for ARGS, stripped; raises RegenError when git fails."""
    r = subprocess.run(["git", *args], capture_output=True, text=True)
    if r.returncode != 0:
        raise RegenError(f"git {' '.join(args)}: {r.stderr.strip()}")
    return r.stdout.strip()


def now():
    """The time now, UTC, ISO to the second."""
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def sha256(path):
    """The SHA-256 of the file PATH, hex."""
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def pin_dir(results):
    return os.path.join(results, "runs", ".renderer")


def read_pin(results):
    """{commit, sha256} of the pinned renderer of RESULTS, or None."""
    path = os.path.join(pin_dir(results), "photonmap.commit")
    if not os.path.exists(path):
        return None
    with open(path, encoding="utf-8") as f:
        words = dict(line.split(" ", 1) for line in f.read().splitlines() if " " in line)
    return {"commit": words.get("commit", ""), "sha256": words.get("sha256", "")}


def pin(results, build="build"):
    """The pinned renderer of RESULTS: (path, commit), pinning build/photonmap
    (made by make) at HEAD on the first call. Raises RegenError when the
    renderer's sources have uncommitted changes (first call) or differ from
    the pinned commit's (later calls), or the pinned copy was altered."""
    binary = os.path.join(pin_dir(results), "photonmap")
    p = read_pin(results)
    if p:
        if not os.path.exists(binary) or sha256(binary) != p["sha256"]:
            raise RegenError(f"{binary}: missing or not the binary pinned ({p['sha256'][:12]}): remove "
                             f"{os.path.join(results, 'runs')} to start the regeneration over")
        changed = git("diff", "--name-only", p["commit"], "HEAD", "--", *PINNED_SOURCES)
        if changed:
            raise RegenError(f"the renderer changed since this regeneration began at {p['commit'][:12]} "
                             f"({', '.join(changed.split())}): the renders made so far are an older binary's; "
                             f"remove {os.path.join(results, 'runs')} to start over on the new one")
        return binary, p["commit"]
    dirty = git("status", "--porcelain", "--untracked-files=no", "--", ".", ":!results")
    if dirty:
        raise RegenError("uncommitted changes (" + ", ".join(line[3:] for line in dirty.splitlines()[:5])
                         + "): a regeneration pins a renderer built from a clean commit (its stats say so); "
                         "commit them first")
    r = subprocess.run(["make", "--no-print-directory", "all"])
    if r.returncode != 0:
        raise RegenError("make all failed: no renderer to pin")
    head = git("rev-parse", "HEAD")
    os.makedirs(pin_dir(results), exist_ok=True)
    tmp = binary + ".tmp"
    shutil.copy2(os.path.join(build, "photonmap"), tmp)
    os.replace(tmp, binary)
    text = f"commit {head}\nsha256 {sha256(binary)}\npinned {now()}\n"
    with open(binary + ".commit.tmp", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(binary + ".commit.tmp", binary + ".commit")
    return binary, head


def read_log(results):
    """The rows of RESULTS/regeneration-log.csv (a list of dicts; empty when none)."""
    path = os.path.join(results, "regeneration-log.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def write_log(results, rows):
    """RESULTS/regeneration-log.csv and .md from ROWS, each through a temporary name."""
    path = os.path.join(results, "regeneration-log.csv")
    with open(path + ".tmp", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, LOG_FIELDS)
        w.writeheader()
        w.writerows(rows)
    os.replace(path + ".tmp", path)
    lines = ["# The regeneration's log", "",
             "Every attempt of `make results` at each study target, the failed, interrupted and superseded ones "
             "included, in the order they ran (written by experiments/regenerate.py; a row without an end is an "
             "attempt that was killed). The renderer is the pinned binary's commit; renders: the records the "
             "attempt made.", "",
             "| started | ended | target | commit | renderer | status | renders | seconds | why |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join(str(r.get(k, "")).replace("|", "/") for k in LOG_FIELDS) + " |")
    lines += totals_lines(rows)
    md = os.path.join(results, "regeneration-log.md")
    with open(md + ".tmp", "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(md + ".tmp", md)


def totals_lines(rows):
    """Markdown lines of the log's totals per pinned renderer, in the order
    the renderers first ran: the finished attempts (ok or failed), their
    renders and seconds, and the unfinished ones (no end: killed, or the
    one running now; their time is not counted); [] for an empty log."""
    by = {}
    for r in rows:
        t = by.setdefault(r["renderer"], {"done": 0, "renders": 0, "seconds": 0, "open": 0})
        if r.get("ended"):
            t["done"] += 1
            t["renders"] += int(r["renders"] or 0)
            t["seconds"] += int(r["seconds"] or 0)
        else:
            t["open"] += 1
    if not by:
        return []
    out = ["", "## Totals", "",
           "Per pinned renderer (the last one is the regeneration's; the earlier ones' renders are superseded):", ""]
    for ren, t in by.items():
        parts = ([f"{t['done']} finished attempt(s), {t['renders']} renders, {t['seconds']} s "
                  f"({t['seconds'] / 3600:.1f} h)"] if t["done"] else [])
        parts += ([f"{t['open']} unfinished attempt(s) (killed, or running now), their time not counted"]
                  if t["open"] else [])
        out.append(f"- `{ren[:7]}`: " + "; ".join(parts) + ".")
    return out


def count_records_since(results, t0):
    """The run records under RESULTS/runs written at or after T0 (seconds since the epoch)."""
    n = 0
    for path in glob.glob(os.path.join(results, "runs", "**", "*.run.json"), recursive=True):
        try:
            n += os.path.getmtime(path) >= t0
        except OSError:
            pass
    return n


def run(results, targets, why, make_args=()):
    """Every target of TARGETS with the pinned renderer, logged. Returns 0
    when every target succeeded, else the first failing target's status."""
    binary, commit = pin(results)
    rows = read_log(results)
    for target in targets:
        head = git("rev-parse", "HEAD")  # the code this target runs (it may move between targets)
        row = {"started": now(), "ended": "", "target": target, "commit": head[:12], "renderer": commit[:12],
               "status": "running", "renders": "", "seconds": "", "why": why}
        rows.append(row)
        write_log(results, rows)
        t0 = time.time()
        print(f"regenerate: {target} (renderer {commit[:12]}, {row['started']})", flush=True)
        r = subprocess.run(["make", "--no-print-directory", target, f"RESULTS={results}", f"PM={binary}", *make_args])
        row.update(ended=now(), status="ok" if r.returncode == 0 else f"exit {r.returncode}",
                   renders=count_records_since(results, t0), seconds=f"{time.time() - t0:.0f}")
        write_log(results, rows)
        if r.returncode != 0:
            print(f"regenerate: {target} failed (exit {r.returncode}); rerun `make results` to resume", file=sys.stderr)
            return r.returncode
    return 0


def render_commits(results):
    """{(commit, tree, flags): count} over the stats files of every render under RESULTS/runs."""
    out = {}
    for path in glob.glob(os.path.join(results, "runs", "**", "*.stats.json"), recursive=True):
        try:
            with open(path, encoding="utf-8") as f:
                prov = json.load(f).get("provenance") or {}
        except (OSError, ValueError):
            prov = {}
        key = (prov.get("commit", "unknown"), prov.get("tree", "unknown"), prov.get("flags", "unknown"))
        out[key] = out.get(key, 0) + 1
    return out


def file_commits(results):
    """{commit: [Markdown files under RESULTS naming it]} ("commit `abc1234`" or
    "Commit: `abc1234`"), with the files that name none under the key None;
    the run layout, the log and the HANDWRITTEN files are not results files."""
    out = {}
    for path in sorted(glob.glob(os.path.join(results, "**", "*.md"), recursive=True)):
        rel = os.path.relpath(path, results)
        if rel.startswith("runs" + os.sep) or rel.startswith("regeneration-log") or rel in HANDWRITTEN:
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            found = {c[:7] for c in COMMIT_RE.findall(f.read())}
        for c in found or {None}:
            out.setdefault(c, []).append(rel)
    return out


def check(results):
    """The problems of a regeneration of RESULTS as sentences (empty: none):
    renders by another commit or a dirty tree than the pinned one, and
    Markdown files naming different commits."""
    problems = []
    p = read_pin(results)
    renders = render_commits(results)
    if p:
        for (commit, tree, _), n in sorted(renders.items()):
            if not p["commit"].startswith(commit) or tree != "clean":
                problems.append(f"{n} render(s) under {results}/runs by commit {commit} ({tree} tree), "
                                f"not the pinned {p['commit'][:12]} (clean)")
        flags = sorted({f for _, _, f in renders})
        if len(flags) > 1:
            problems.append(f"the renders under {results}/runs were built with {len(flags)} sets of flags: "
                            + "; ".join(flags))
    elif renders:
        problems.append(f"{results}/runs holds renders but no pinned renderer ({pin_dir(results)})")
    files = file_commits(results)
    unnamed = files.pop(None, [])
    if unnamed:
        problems.append(f"{len(unnamed)} results file(s) name no commit: " + ", ".join(unnamed[:6])
                        + (" ..." if len(unnamed) > 6 else ""))
    if len(files) > 1:
        problems.append("the results files name " + str(len(files)) + " commits: "
                        + "; ".join(f"{c}: {', '.join(fs[:4])}{' ...' if len(fs) > 4 else ''}"
                                    for c, fs in sorted(files.items())))
    return problems


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run every study target with the pinned renderer, logged")
    r.add_argument("--results", required=True)
    r.add_argument("--only", nargs="*", default=None, help="these targets only (in TARGETS' order)")
    r.add_argument("--why", default="", help="why this attempt runs (the log's last column)")
    r.add_argument("make_args", nargs="*", help="NAME=VALUE given to every target's make")
    c = sub.add_parser("check", help="every render by the pinned renderer; every results file naming one commit")
    c.add_argument("--results", required=True)
    s = ap.parse_args(argv)
    try:
        if s.cmd == "check":
            problems = check(s.results)
            for line in problems:
                print(f"regenerate check: {line}", file=sys.stderr)
            if not problems:
                print(f"regenerate check: {s.results}: every render by the pinned renderer, every file one commit")
            return 1 if problems else 0
        targets = list(TARGETS)
        if s.only is not None:
            unknown = [t for t in s.only if t not in TARGETS]
            if unknown:
                ap.error(f"--only {' '.join(unknown)}: not a study target ({' '.join(TARGETS)})")
            targets = [t for t in TARGETS if t in s.only]
        return run(s.results, targets, s.why or "regeneration", s.make_args)
    except RegenError as e:
        print(f"regenerate: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
