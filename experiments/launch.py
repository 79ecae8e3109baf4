#!/usr/bin/python3
"""launch.py: the render launcher. The one place that spells a render's
command line (command) and makes one render's files in the run layout
(experiments/analysis/runs.py); the Snakemake render rules
(experiments/rules/render.smk) call it.

    python3 -m experiments.launch --pm PM --scene SCENE --width W --height H \\
        --subpixels S --threads T --repeats R --of N --stem ESTIMATE-pP-nN/seedK \\
        --member ROOT METHOD "EXTRA ARGS" K [--member ...] [--member-repeats ROOT METHOD R ...] [--dump-reps] \\
        [--busy-loop] [--cpu first|N|none]

renders every member (the render ROOT/METHOD-ESTIMATE-pP-nN/seedK with the
extra renderer options EXTRA ARGS, run K of the study's N) back to back,
each timed with the renderer's --repeats R (auto, or a count; 1: a single
timed run; the times the analysis reads are the repeats' minima; a
member of --member-repeats: its own R instead): a
group of renders of one (cell, seed) whose times are compared is run as one
job so that they are paired samples of one machine state. The order
alternates with the seed: odd seeds in the order given, even seeds
reversed, so that a linear drift within a group (a machine warming up, a
neighbour starting) falls on every member's mean position equally; each
record says its place in the group (pair_pos: 1..N; 0 for a render run
alone). The records of all members are removed first, and when a render
fails or the group is interrupted the records this group made are removed
again: a group is finished only when every member's record exists.

One render writes, in ROOT/CELL/: seedK.exr (the image), seedK.stats.json
(the renderer's --stats), seedK.err (its stderr), with --dump-reps
seedK.reps.csv (the representatives, renderer's --dump-reps) and, last,
seedK.run.json:
exit status, user/system CPU seconds from /usr/bin/time -f "%U %S", the
1-minute load average when the render started, its place in the group, the
command, and for a refused render (exit 2: the renderer rejects the
combination, e.g. --bias-correction with --rep-every 1) its message.
Everything is written to a temporary name and renamed, so a killed render
leaves no result. Any other failure exits 1 and records nothing. Prints one
progress line per render ("run K/N METHOD ESTIMATE P_e=.. n=.. seed ..").
With --busy-loop a process spinning in a loop (busy_loop) runs from before
the group's first render until after its last, the load of a neighbour on
another core (make reproducibility's third run); each record says so
("busy_loop": 1).

With --cpu first (or a CPU number) every render runs pinned to that CPU
(first: the lowest CPU this process may run on; the study knob TIME_CPU,
for timed one-thread renders) and the busy loop to another one where there
is one; each record names the CPU ("cpu": N, or null unpinned). On a
shared machine the CPUs need not be equally fast: on this project's
two-core machines one ran the same render slower than the other for
minutes at a time, so an unpinned render's time depended on where the
scheduler put it.
"""

import argparse
import os
import re
import signal
import subprocess
import sys

from experiments.analysis import runs as layout

ESTIMATE_ARGS = {"paper": [], "corrected": ["--bias-correction"]}
STEM = re.compile(r"(?P<estimate>[a-z]+)-p(?P<photons>[0-9]+)-n(?P<nn>[0-9]+)/seed(?P<seed>[0-9]+)")


class LaunchError(Exception):
    """A render failed (exit other than 0 and 2) or its name is not in the layout."""


def check_repeats(repeats):
    """REPEATS as the renderer's --repeats takes it: "auto" or a positive count."""
    text = str(repeats)
    if text == "auto" or re.fullmatch(r"[1-9][0-9]*", text):
        return text
    raise LaunchError(f"--repeats {text}: auto or a positive number of timed runs (1: a single timed run)")


def command(pm, scene, method, estimate, photons, nn, seed, width, height, subpixels, threads, extra, out_base,
            repeats, dump_reps=False):
    """The renderer's command line of one render, as a list of words:
    the image to OUT_BASE.exr, the stats to OUT_BASE.json and, with
    DUMP_REPS, the representatives to OUT_BASE.reps.csv; timed with
    --repeats REPEATS."""
    if estimate not in ESTIMATE_ARGS:
        raise LaunchError(f"estimate '{estimate}' is neither paper nor corrected")
    return ([pm, "render", scene, "--method", method, "--photons", str(photons), "--nn", str(nn), "--seed", str(seed),
             "--width", str(width), "--height", str(height), "--subpixels", str(subpixels), "--threads", str(threads),
             "--repeats", check_repeats(repeats)]
            + extra.split() + ESTIMATE_ARGS[estimate] + ["-o", out_base + ".exr", "--stats", out_base + ".json", "--quiet"]
            + (["--dump-reps", out_base + ".reps.csv"] if dump_reps else []))


def resolve_cpu(spec):
    """The CPU of --cpu SPEC: None for "none", the lowest CPU this process
    may run on for "first", else the number, which must be one of them."""
    if spec == "none":
        return None
    allowed = sorted(os.sched_getaffinity(0))
    if spec == "first":
        return allowed[0]
    if not re.fullmatch(r"[0-9]+", str(spec)):
        raise LaunchError(f"--cpu {spec}: first, none, or a CPU number")
    if int(spec) not in allowed:
        raise LaunchError(f"--cpu {spec}: not a CPU this process may run on ({', '.join(map(str, allowed))})")
    return int(spec)


def pinned(cpu):
    """A preexec_fn that pins the child to CPU (None: leaves it as it is)."""
    if cpu is None:
        return None
    return lambda: os.sched_setaffinity(0, {cpu})


def json_str(text):
    """TEXT as a JSON string (backslash and quote escaped; control
    characters were removed before)."""
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def one_line(text):
    """The renderer's stderr as one line: tabs and newlines as spaces, other
    control characters dropped, no trailing spaces."""
    text = text.replace("\t", " ").replace("\n", " ")
    return re.sub(r"[\x00-\x08\x0b-\x1f]", "", text).rstrip(" ")


def write_record(base, exit_code, user, sys_s, cpu, load, pair_pos, message, cmd, busy=False, pin=None):
    """The run record, written last (temporary name, then renamed)."""
    text = (f'{{\n  "exit": {exit_code},\n  "user_s": {user},\n  "sys_s": {sys_s},\n  "cpu_s": {cpu},\n'
            f'  "loadavg_1min": {load},\n  "pair_pos": {pair_pos},\n  "busy_loop": {int(busy)},\n'
            f'  "cpu": {"null" if pin is None else pin},\n'
            f'  "message": {json_str(message)},\n'
            f'  "command": {json_str(" ".join(cmd))}\n}}\n')
    with open(base + ".tmp.run", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(base + ".tmp.run", base + ".run.json")


def remove_tmp(base):
    d, stem = os.path.split(base)
    for name in os.listdir(d) if os.path.isdir(d) else []:
        if name.startswith(stem + ".tmp."):
            os.remove(os.path.join(d, name))


def render(s, root, method, estimate, photons, nn, seed, extra, pair_pos, k, repeats, pin=None):
    """One render of the settings S (argparse namespace: pm, scene, width,
    height, subpixels, threads, of) into ROOT, timed with --repeats REPEATS,
    pinned to CPU PIN (None: not pinned); prints its progress line.
    Returns 0 (rendered) or 2 (refused, recorded); raises LaunchError on
    any other failure (nothing recorded)."""
    label = f"run {k}/{s.of} {method} {estimate} P_e={photons} n={nn} seed {seed}"
    base = layout.run_base(root, method, estimate, photons, nn, seed)
    os.makedirs(os.path.dirname(base), exist_ok=True)
    remove_tmp(base)
    for ext in (".exr", ".stats.json", ".err", ".reps.csv"):
        if os.path.exists(base + ext):
            os.remove(base + ext)
    cmd = command(s.pm, s.scene, method, estimate, photons, nn, seed, s.width, s.height, s.subpixels, s.threads,
                  extra, base + ".tmp", repeats, s.dump_reps)
    with open("/proc/loadavg", encoding="ascii") as f:
        load = f.read().split()[0]
    with open(base + ".tmp.err", "wb") as err:
        rc = subprocess.call(["/usr/bin/time", "-f", "%U %S", "-o", base + ".tmp.time"] + cmd, stderr=err,
                             preexec_fn=pinned(pin))
    with open(base + ".tmp.err", encoding="utf-8", errors="replace") as f:
        msg = one_line(f.read())
    if rc == 0:
        with open(base + ".tmp.time", encoding="ascii") as f:
            user, sys_s = f.read().splitlines()[-1].split()
        os.replace(base + ".tmp.exr", base + ".exr")
        os.replace(base + ".tmp.json", base + ".stats.json")
        os.replace(base + ".tmp.err", base + ".err")
        if s.dump_reps:
            os.replace(base + ".tmp.reps.csv", base + ".reps.csv")
        os.remove(base + ".tmp.time")
        cpu = "%.2f" % (float(user) + float(sys_s))
        write_record(base, 0, user, sys_s, cpu, load, pair_pos, "", cmd, s.busy_loop, pin)
        total = "%.2f" % layout.load_json(base + ".stats.json")["time_s"]["total"]
        print(f"{label}: total {total} s, cpu {cpu} s", flush=True)
        return 0
    if rc == 2:  # refused: the combination does not apply; recorded so that it is not retried
        os.replace(base + ".tmp.err", base + ".err")
        remove_tmp(base)
        write_record(base, 2, "null", "null", "null", load, pair_pos, msg, cmd, s.busy_loop, pin)
        print(f"{label}: not applicable (the renderer refused it, exit 2): {msg}", flush=True)
        return 2
    remove_tmp(base)
    raise LaunchError(f"{label} failed (exit {rc}): {' '.join(cmd)}\nlaunch.py: {msg}")


def busy_loop(avoid=None):
    """A process spinning in a loop until killed (the caller's to end), on
    a CPU other than AVOID where this process may run on another."""
    others = sorted(os.sched_getaffinity(0) - {avoid}) if avoid is not None else []
    return subprocess.Popen([sys.executable, "-c", "while True:\n    pass"],
                            preexec_fn=pinned(others[0] if others else None))


def run_group(s, members, repeats=None):
    """Every member (root, method, extra, k) of the stem s.stem, back to back,
    in the order alternating with the seed, each timed with s.repeats or its
    own of REPEATS ({(root, method): repeats}); all records or none."""
    m = STEM.fullmatch(s.stem)
    if not m:
        raise LaunchError(f"'{s.stem}': not ESTIMATE-pPHOTONS-nNN/seedK")
    estimate, photons, nn, seed = m["estimate"], int(m["photons"]), int(m["nn"]), int(m["seed"])
    records = [layout.run_base(root, method, estimate, photons, nn, seed) + ".run.json" for root, method, _, _ in members]
    order = list(range(len(members)))
    if len(members) > 1 and seed % 2 == 0:
        order.reverse()
    for r in records:
        if os.path.exists(r):
            os.remove(r)
    done = False
    pin = resolve_cpu(s.cpu)
    busy = busy_loop(pin) if s.busy_loop else None
    try:
        for pos, i in enumerate(order, 1):
            root, method, extra, k = members[i]
            render(s, root, method, estimate, photons, nn, seed, extra, pos if len(members) > 1 else 0, k,
                   (repeats or {}).get((root, method), s.repeats), pin)
        done = True
    finally:
        if busy:
            busy.kill()
            busy.wait()
        if not done:  # the group unfinished: none of its records stays
            for r in records:
                if os.path.exists(r):
                    os.remove(r)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pm", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    ap.add_argument("--subpixels", type=int, required=True)
    ap.add_argument("--threads", default="1", help="--threads of the renderer (0: all cores)")
    ap.add_argument("--repeats", required=True,
                    help="--repeats of the renderer: auto, or a count (1: a single timed run); a study's TIME_REPEATS")
    ap.add_argument("--of", type=int, required=True, help="the number of renders of the study (progress lines)")
    ap.add_argument("--stem", required=True, help="ESTIMATE-pPHOTONS-nNN/seedK")
    ap.add_argument("--dump-reps", action="store_true", help="each render's representatives to seedK.reps.csv")
    ap.add_argument("--busy-loop", action="store_true", help="a busy loop runs beside the group's renders")
    ap.add_argument("--cpu", default="none",
                    help="pin every render to this CPU: first (the lowest this process may use), a number, or none")
    ap.add_argument("--member", nargs=4, action="append", required=True, metavar=("ROOT", "METHOD", "ARGS", "K"))
    ap.add_argument("--member-repeats", nargs=3, action="append", default=[], metavar=("ROOT", "METHOD", "R"),
                    help="the member ROOT METHOD's --repeats instead of --repeats (e.g. 1 for a long render)")
    s = ap.parse_args(argv)
    members = [(root, method, extra, int(k)) for root, method, extra, k in s.member]
    try:
        check_repeats(s.repeats)
        resolve_cpu(s.cpu)
        own = {(root, method): check_repeats(r) for root, method, r in s.member_repeats}
        for key in own:
            if key not in {(root, method) for root, method, _, _ in members}:
                raise LaunchError(f"--member-repeats {' '.join(key)}: no such --member")
    except LaunchError as e:
        ap.error(str(e))

    def stop(signum, frame):
        raise SystemExit(1)
    for sig in (signal.SIGTERM, signal.SIGHUP):
        signal.signal(sig, stop)
    try:
        run_group(s, members, own)
    except LaunchError as e:
        print(f"launch.py: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
