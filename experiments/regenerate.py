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

A regeneration can outlive its machine: the renders (DIR/runs) are not
committed, so a new machine pins its own copy, and a study whose last
attempt in the committed log ended ok on a pin with the same renderer
sources (landed: regenerated and committed from another machine) is
skipped, not rendered again (--only renders it again). The regeneration is
one renderer's sources, not one pin.

check: every render under DIR/runs (its stats file's provenance) was made by
the pinned renderer's sources from a clean tree; every study target's last
attempt in the log ended ok on those sources; every Markdown file under DIR
names a commit, and the files of one study directory the same one
(report.commit's "commit `abc1234`", or a table's "Commit: `abc1234`";
README.md and stability/stability.md are written by hand and exempt);
prints what differs and exits 1 when not.
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
    """The folder under RESULTS that holds the pinned renderer: RESULTS/runs/.renderer."""
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


def same_renderer(a, b):
    """True when commits A and B (full or abbreviated hashes) hold the same
    renderer sources (PINNED_SOURCES); False when they differ or git does
    not know either commit."""
    if a and b and (a.startswith(b) or b.startswith(a)):  # one commit, abbreviated or not
        return True
    r = subprocess.run(["git", "diff", "--quiet", a, b, "--", *PINNED_SOURCES], capture_output=True)
    return r.returncode == 0


def last_rows(rows):
    """{target: the log's last row of that target} over ROWS."""
    return {r["target"]: r for r in rows}


def landed(rows, commit, same=None):
    """The targets of ROWS whose last attempt ended ok on a pin other than
    COMMIT of the same renderer sources (SAME): studies an earlier machine
    regenerated and committed, whose renders this machine does not hold.
    Returns {target: that row}."""
    same = same or same_renderer
    return {t: r for t, r in last_rows(rows).items()
            if r["status"] == "ok" and not commit.startswith(r["renderer"]) and same(r["renderer"], commit)}


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


def run(results, targets, why, make_args=(), skip_landed=True):
    """Every target of TARGETS with the pinned renderer, logged; with
    SKIP_LANDED, not those landed() by an earlier pin of the same renderer
    sources (rendering them again would replace committed results with a
    second machine's). Returns 0 when every target succeeded, else the first
    failing target's status."""
    binary, commit = pin(results)
    rows = read_log(results)
    if skip_landed:
        done = landed(rows, commit)
        for target in [t for t in targets if t in done]:
            r = done[target]
            print(f"regenerate: {target} skipped: committed by {r['renderer']} on {r['ended']}, the same renderer "
                  f"sources (RESULTS_ONLY={target} renders it again)", flush=True)
        targets = [t for t in targets if t not in done]
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


def check(results, same=None):
    """The problems of a regeneration of RESULTS as sentences (empty: none):
    renders by other renderer sources than the pinned commit's (SAME
    compares two commits' sources) or from a dirty tree, or built with
    several sets of flags; with a log, every study target whose last attempt
    did not end ok on the regeneration's renderer sources (the pinned
    commit's, or the log's last renderer where RESULTS/runs is absent, as in
    a clone); and a study directory whose Markdown files name different
    commits (each study's files are written by one analysis; studies
    regenerated on different machines may name different ones)."""
    same = same or same_renderer
    problems = []
    rows = read_log(results)
    p = read_pin(results)
    pinned = p["commit"] if p else (rows[-1]["renderer"] if rows else None)
    renders = render_commits(results)
    if p:
        for (commit, tree, _), n in sorted(renders.items()):
            if not same(commit, pinned) or tree != "clean":
                problems.append(f"{n} render(s) under {results}/runs by commit {commit} ({tree} tree), "
                                f"not the renderer of the pinned {pinned[:12]} (clean)")
        flags = sorted({f for _, _, f in renders})
        if len(flags) > 1:
            problems.append(f"the renders under {results}/runs were built with {len(flags)} sets of flags: "
                            + "; ".join(flags))
    elif renders:
        problems.append(f"{results}/runs holds renders but no pinned renderer ({pin_dir(results)})")
    if rows:
        last = last_rows(rows)
        for target in TARGETS:
            r = last.get(target)
            if r is None:
                problems.append(f"{target}: no attempt in the log")
            elif r["status"] != "ok":
                problems.append(f"{target}: its last attempt ({r['started']}) did not end ok ({r['status']})")
            elif not same(r["renderer"], pinned):
                problems.append(f"{target}: rendered by {r['renderer']}, whose renderer sources differ from "
                                f"the regeneration's ({pinned[:12]})")
    files = file_commits(results)
    unnamed = files.pop(None, [])
    if unnamed:
        problems.append(f"{len(unnamed)} results file(s) name no commit: " + ", ".join(unnamed[:6])
                        + (" ..." if len(unnamed) > 6 else ""))
    by_dir = {}
    for c, fs in files.items():
        for f in fs:
            by_dir.setdefault(os.path.dirname(f).split(os.sep)[0] or ".", {}).setdefault(c, []).append(f)
    for folder, commits in sorted(by_dir.items()):
        if len(commits) > 1:
            problems.append(f"the results files of {folder}/ name {len(commits)} commits: "
                            + "; ".join(f"{c}: {', '.join(fs[:4])}{' ...' if len(fs) > 4 else ''}"
                                        for c, fs in sorted(commits.items())))
    return problems


def main(argv=None):
    """Command line: see the module docstring (run or check). Returns run's status, or check's: 0
    without a problem, 1 with any (each printed on stderr); 1 on a RegenError; an --only target that is
    not a study target is a usage error (exit 2)."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run", help="run every study target with the pinned renderer, logged")
    r.add_argument("--results", required=True)
    r.add_argument("--only", nargs="*", default=None, help="these targets only (in TARGETS' order)")
    r.add_argument("--why", default="", help="why this attempt runs (the log's last column)")
    r.add_argument("make_args", nargs="*", help="NAME=VALUE given to every target's make")
    c = sub.add_parser("check", help="every study on one renderer's sources; each study's files naming one commit")
    c.add_argument("--results", required=True)
    s = ap.parse_args(argv)
    try:
        if s.cmd == "check":
            problems = check(s.results)
            for line in problems:
                print(f"regenerate check: {line}", file=sys.stderr)
            if not problems:
                print(f"regenerate check: {s.results}: every study on one renderer's sources, every render by it, "
                      "each study's files naming one commit")
            return 1 if problems else 0
        targets = list(TARGETS)
        if s.only is not None:
            unknown = [t for t in s.only if t not in TARGETS]
            if unknown:
                ap.error(f"--only {' '.join(unknown)}: not a study target ({' '.join(TARGETS)})")
            targets = [t for t in TARGETS if t in s.only]
        return run(s.results, targets, s.why or "regeneration", s.make_args, skip_landed=s.only is None)
    except RegenError as e:
        print(f"regenerate: {e}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
