"""Shared pieces of the Markdown reports: provenance and number formatting.

Owns what every generated Markdown file states about where its numbers come
from (machine, cores, load average, commit, pinned renderer) and how a value,
an interval or a missing value is printed, so that table1.md,
equal-error.md and resolution.md say these things the same way. Also the
error exit every analysis script uses, the one CSV reader (columns checked
by name) and the one name of the time a study compares (TIME_LABEL: cpu_s
or total_s, the make variable TIME and every script's --time).
"""

import datetime
import math
import os
import subprocess
import sys

import pandas as pd

# the time a study compares: the runs.csv column and what it is
TIME_LABEL = {"cpu_s": "CPU seconds of the process (user + system, /usr/bin/time)",
              "total_s": "wall-clock seconds of the render (the stats JSON's time_s.total)"}


# exit statuses: a runtime failure (a file a step before did not make, I/O),
# and bad input (a file that is there but not what it must be, an option's
# value)
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


def die(where, what, code=EXIT_FAILURE):
    """Print 'WHERE: WHAT' on stderr and exit CODE (EXIT_FAILURE, or
    EXIT_BAD_INPUT for input that is there but malformed)."""
    print(f"{where}: {what}", file=sys.stderr)
    sys.exit(code)


def read_csv(path, need, where, hint="", comment=None):
    """The CSV at PATH as a pandas frame, its columns NEED checked by name.
    A missing file exits EXIT_FAILURE with 'WHERE: PATH: missing (HINT)'
    (HINT says what makes it); an unreadable or malformed one, or one that
    lacks a column, exits EXIT_BAD_INPUT naming the file and the cause."""
    if not os.path.isfile(path):
        die(where, f"{path}: missing" + (f" ({hint})" if hint else ""))
    try:
        frame = pd.read_csv(path, comment=comment)
    except (UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as e:
        die(where, f"{path}: not a CSV ({e})", EXIT_BAD_INPUT)
    except OSError as e:
        die(where, f"{path}: {e}")
    missing = [c for c in need if c not in frame.columns]
    if missing:
        die(where, f"{path}: no column(s) {', '.join(missing)}", EXIT_BAD_INPUT)
    return frame


def isnum(x):
    """True for a finite number (not None, not NaN, not a string)."""
    try:
        return x is not None and math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def fmt(x, digits=3):
    """X with DIGITS significant digits, or 'n/a' when it is not a number."""
    if not isnum(x):
        return "n/a"
    x = float(x)
    if x == 0:
        return "0"
    return f"{x:.{digits}g}" if 1e-4 <= abs(x) < 1e6 else f"{x:.{digits - 1}e}"


def fmt_fixed(x, decimals=2):
    """X with DECIMALS decimals, or 'n/a'."""
    return f"{float(x):.{decimals}f}" if isnum(x) else "n/a"


def fmt_pm(mean, half, digits=3):
    """'mean ± half' (half: a 95% half-width), or the mean alone if half is
    unknown, or 'n/a'."""
    if not isnum(mean):
        return "n/a"
    if not isnum(half):
        return fmt(mean, digits)
    return f"{fmt(mean, digits)} ± {fmt(half, 2)}"


def fmt_range(mid, lo, hi, fixed=None):
    """'mid (lo-hi)' for a median with its range (min-max); the median
    alone when the range is unknown; 'n/a'."""
    f = (lambda v: fmt_fixed(v, fixed)) if fixed is not None else fmt
    if not isnum(mid):
        return "n/a"
    if not (isnum(lo) and isnum(hi)):
        return f(mid)
    return f"{f(mid)} ({f(lo)}-{f(hi)})"


def fmt_ci(mid, lo, hi, fixed=None):
    """'mid [lo, hi]' for a value with its 95% interval; the value alone when
    the interval is unknown; 'n/a'."""
    f = (lambda v: fmt_fixed(v, fixed)) if fixed is not None else fmt
    if not isnum(mid):
        return "n/a"
    return f(mid) + (f" {fmt_interval(lo, hi, fixed)}" if isnum(lo) and isnum(hi) else "")


def fmt_count(mid, lo, hi):
    """A median count with its range: '5', or '4 (3-5)' when they differ."""
    if not isnum(mid):
        return "n/a"
    return f"{mid:g}" if lo == hi else f"{mid:g} ({lo:g}-{hi:g})"


def fmt_interval(lo, hi, fixed=None):
    """'[lo, hi]' or 'n/a'."""
    f = (lambda v: fmt_fixed(v, fixed)) if fixed is not None else fmt
    if not (isnum(lo) and isnum(hi)):
        return "n/a"
    return f"[{f(lo)}, {f(hi)}]"


def md_table(header, rows, align=None):
    """A Markdown table as a list of lines; ALIGN: one of 'l'/'r' per column
    (default: first column left, the rest right)."""
    align = align or ["l"] + ["r"] * (len(header) - 1)
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---" if a == "l" else "---:" for a in align) + "|"]
    for r in rows:
        lines.append("| " + " | ".join(str(c) for c in r) + " |")
    return lines


def _run(cmd):
    """stdout of CMD stripped, or '' when it fails."""
    try:
        return subprocess.run(cmd, capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return ""


def machine():
    """'CPU model, N cores (nproc)' of this machine."""
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores (`nproc`)"


def loadavg_now():
    """The 1, 5 and 15 minute load averages now, as 'a b c'."""
    try:
        with open("/proc/loadavg", encoding="utf-8") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "unknown"


def commit():
    """'`abc1234`' of HEAD, with a note when tracked files other than the
    results (results/, the outputs being written) were modified."""
    head = _run(["git", "rev-parse", "--short", "HEAD"]) or "unknown"
    dirty = _run(["git", "status", "--porcelain", "--untracked-files=no", "--", ".", ":!results"])
    return f"`{head}`" + (" (the working tree had uncommitted changes)" if dirty else "")


def renderer_note(pm):
    """Provenance of the renderer binary PM: its PM.commit file if a pinned
    copy has one, else that it is the working tree's build."""
    if pm and os.path.isfile(pm + ".commit"):
        with open(pm + ".commit", encoding="utf-8") as f:
            return f"`{pm}`, a copy of build/photonmap built from: " + " ".join(f.read().split())
    return f"`{pm}` (built from the commit above)"


def today():
    """Today's date (UTC), ISO."""
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")


def write_atomic(path, text):
    """Write TEXT to PATH through a temporary name and a rename."""
    d = os.path.dirname(path)
    if d:
        os.makedirs(d, exist_ok=True)
    tmp = f"{path}.tmp.{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def write_csv_atomic(frame, path, float_format="%.6g"):
    """Write a pandas FRAME as CSV to PATH through a temporary name."""
    d = os.path.dirname(path)
    if d:
        os.makedirs(d, exist_ok=True)
    tmp = f"{path}.tmp.{os.getpid()}"
    frame.to_csv(tmp, index=False, float_format=float_format, na_rep="")
    os.replace(tmp, path)
