#!/usr/bin/python3
"""launch.py: the render launcher. The one place that spells a render's
command line (command) and makes one render's files in the run layout
(experiments/analysis/runs.py); the Snakemake render rules
(experiments/rules/render.smk) call it.

    python3 -m experiments.launch --pm PM --scene SCENE --width W --height H \\
        --subpixels S --threads T --repeats R --of N --stem ESTIMATE-pP-nN/seedK \\
        --member ROOT METHOD "EXTRA ARGS" K [--member ...] [--member-repeats ROOT METHOD R ...] [--dump-reps] \\
        [--busy-loop] [--cpu first|N|none] [--processes P] [--gauge PCT --max-processes M]

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

With --processes P (the study knob TIME_PROCESSES) every member is rendered
in P processes, in rounds: each round runs every member once, the first
in the order above, each next one in the reverse of the one before (two
members, P = 2: A B B A), so that the methods compared alternate in time
and a drift of the machine over the group falls on each equally. The
renderer's repeats take the minimum within a process; the processes take
it across the machine's slower changes (a CPU's speed moving over
seconds and minutes), which repeats within one process cannot see. The
member's files are then those of one render: the first process's image
(every process's image must be the same bytes, and its work counters the
same, else the group fails: the renderer would not be deterministic), its
stats merged (merge_stats: time_s the minimum over every repeat of every
process, time_s_repeats all of them, time_s_processes each process's
minima), and a record whose cpu_s is the least process's, with
"processes", "cpu_s_processes" and "pair_pos_processes" (each process's
place in its round). A member of --member-repeats (a render long enough
to be timed once) runs in one process. With P = 1 the files are exactly
those of a single process.

With --gauge PCT (the study knob TIME_GAUGE) the photon pass is the
group's speed gauge: it is the same code doing the same work in every
member (their trace work counters must be equal, and the least of its
times at least GAUGE_MIN_S, 10 ms, else there is no gauge), so its least
time over all of a member's processes says whether that member ever ran
at the machine's best speed. After the P rounds, a member
whose least photon pass is more than PCT % above the least of the whole
group gets one more process, in further rounds (the order still
reversing), until none is or it has run in M processes (--max-processes,
the knob TIME_PROCESSES_MAX). On this project's machines a slow spell
(every phase 10-20% slower) lasts about three processes; rounds A B B A
then put both of B's processes inside it, and B's minimum is a slow one.
Each record says how many processes the gauge added ("gauge_added"; the
stats' "processes" counts them all).
"""

import argparse
import filecmp
import json
import os
import re
import signal
import statistics
import subprocess
import sys

from experiments.analysis import runs as layout

ESTIMATE_ARGS = {"paper": [], "corrected": ["--bias-correction"]}
# the shortest photon pass that gauges a speed: a shorter one (a test's or
# a preview's few thousand photons, about a millisecond) moves by more than
# the gauge's few percent between repeats of one process, and would add
# processes for nothing; every cell of the paper's grid at 1024x768 takes
# 28 ms or more
GAUGE_MIN_S = 0.01
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


def write_record(base, exit_code, user, sys_s, cpu, load, pair_pos, message, cmd, busy=False, pin=None, extra=None):
    """The run record, written last (temporary name, then renamed); EXTRA:
    more keys and their values (JSON), after "cpu"."""
    text = (f'{{\n  "exit": {exit_code},\n  "user_s": {user},\n  "sys_s": {sys_s},\n  "cpu_s": {cpu},\n'
            f'  "loadavg_1min": {load},\n  "pair_pos": {pair_pos},\n  "busy_loop": {int(busy)},\n'
            f'  "cpu": {"null" if pin is None else pin},\n'
            + "".join(f'  "{k}": {json.dumps(v)},\n' for k, v in (extra or {}).items()) +
            f'  "message": {json_str(message)},\n'
            f'  "command": {json_str(" ".join(cmd))}\n}}\n')
    with open(base + ".tmp.run", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(base + ".tmp.run", base + ".run.json")


def remove_tmp(base):
    """Removes the temporary files of the render at BASE (BASE.tmp.* and
    each process's BASE.tmpI.*)."""
    d, stem = os.path.split(base)
    for name in os.listdir(d) if os.path.isdir(d) else []:
        if re.match(re.escape(stem) + r"\.tmp[0-9]*\.", name):
            os.remove(os.path.join(d, name))


def run_process(out_base, cmd, pin):
    """One renderer process of CMD, writing OUT_BASE.exr, .json (and
    .reps.csv), its stderr to OUT_BASE.err and /usr/bin/time's CPU seconds
    to OUT_BASE.time, pinned to CPU PIN. Returns a dict: rc, user, sys
    (strings; None unless rc is 0), msg (its stderr as one line), load (the
    1-minute load average at its start), out (OUT_BASE)."""
    with open("/proc/loadavg", encoding="ascii") as f:
        load = f.read().split()[0]
    with open(out_base + ".err", "wb") as err:
        rc = subprocess.call(["/usr/bin/time", "-f", "%U %S", "-o", out_base + ".time"] + cmd, stderr=err,
                             preexec_fn=pinned(pin))
    with open(out_base + ".err", encoding="utf-8", errors="replace") as f:
        msg = one_line(f.read())
    user = sys_s = None
    if rc == 0:
        with open(out_base + ".time", encoding="ascii") as f:
            user, sys_s = f.read().splitlines()[-1].split()
    return {"rc": rc, "user": user, "sys": sys_s, "msg": msg, "load": load, "out": out_base}


def merge_stats(paths, label):
    """The stats of one render timed in several processes (PATHS, the
    processes' stats files in the order they ran) as one: the first
    process's, with time_s the minimum over every repeat of every process
    (per phase, and the total the least repeat total), time_s_repeats every
    repeat in the order run, repeats their number, time_s_median their
    median, time_s_cold the first process's first repeat, processes and
    time_s_processes (each process's minima), and minor_faults_repeats
    every repeat's page faults in the order run (where every process
    reports them). Raises LaunchError when a
    process's work counters or mean radiance differ from the first's (the
    renderer would not be deterministic)."""
    docs = [layout.load_json(p) for p in paths]
    first = docs[0]
    for i, d in enumerate(docs[1:], 2):
        for key in ("work", "mean_radiance", "gather_work"):
            if d.get(key) != first.get(key):
                raise LaunchError(f"{label}: process {i} of {len(docs)} reports another {key} than process 1: "
                                  "the same render is not deterministic")
    phases = list(first["time_s"])
    reps = {p: [v for d in docs for v in (d.get("time_s_repeats") or {}).get(p, [d["time_s"][p]])] for p in phases}
    out = dict(first)
    out["time_s"] = {p: min(reps[p]) for p in phases}
    out["repeats"] = len(reps["total"])
    out["time_s_cold"] = first.get("time_s_cold", first["time_s"])
    out["time_s_median"] = {p: float(statistics.median(reps[p])) for p in phases}
    out["time_s_repeats"] = reps
    out["processes"] = len(docs)
    out["time_s_processes"] = {p: [d["time_s"][p] for d in docs] for p in phases}
    if all("minor_faults_repeats" in d for d in docs):
        out["minor_faults_repeats"] = [v for d in docs for v in d["minor_faults_repeats"]]
    else:
        out.pop("minor_faults_repeats", None)
    return out


class Render:
    """One member's render: its command, output base and the processes run
    so far (run_process's dicts), made by start(), run by run(), written
    by finish()."""

    def __init__(self, s, root, method, estimate, photons, nn, seed, extra, k, repeats, processes):
        self.s, self.method, self.k, self.processes = s, method, k, processes
        self.label = f"run {k}/{s.of} {method} {estimate} P_e={photons} n={nn} seed {seed}"
        self.base = layout.run_base(root, method, estimate, photons, nn, seed)
        self.extra, self.repeats, self.estimate, self.photons, self.nn, self.seed = \
            extra, repeats, estimate, photons, nn, seed
        self.done, self.pos = [], []
        self.planned = processes  # the processes the rounds run; the gauge may add to self.processes

    def out_base(self, i):
        """The temporary base of process I (0-based): BASE.tmp with one
        process (the command a record names), BASE.tmpI+1 with several."""
        return self.base + (".tmp" if self.processes == 1 else f".tmp{i + 1}")

    def start(self):
        """Removes the member's files of an earlier run."""
        os.makedirs(os.path.dirname(self.base), exist_ok=True)
        remove_tmp(self.base)
        for ext in (".exr", ".stats.json", ".err", ".reps.csv"):
            if os.path.exists(self.base + ext):
                os.remove(self.base + ext)

    def command(self, i):
        s = self.s
        return command(s.pm, s.scene, self.method, self.estimate, self.photons, self.nn, self.seed, s.width, s.height,
                       s.subpixels, s.threads, self.extra, self.out_base(i), self.repeats, s.dump_reps)

    def wants(self):
        """Whether another process is to run: fewer than PROCESSES so far,
        and none refused."""
        return len(self.done) < self.processes and not any(p["rc"] == 2 for p in self.done)

    def run(self, pos, pin):
        """Runs the next process at place POS of its round, pinned to PIN;
        prints its progress line. Raises LaunchError on a failure other than
        a refusal (exit 2) or a refusal after a rendered process."""
        i = len(self.done)
        p = run_process(self.out_base(i), self.command(i), pin)
        of = f" (process {i + 1}/{self.processes})" if self.processes > 1 else ""
        if i >= self.planned:
            of = f" (process {i + 1}, added by the gauge)"
        if p["rc"] not in (0, 2) or (p["rc"] == 2 and i > 0):
            raise LaunchError(f"{self.label}{of} failed (exit {p['rc']}): {' '.join(self.command(i))}\n"
                              f"launch.py: {p['msg']}")
        self.done.append(p)
        self.pos.append(pos)
        if p["rc"] == 0:
            total = "%.2f" % layout.load_json(p["out"] + ".json")["time_s"]["total"]
            cpu = "%.2f" % (float(p["user"]) + float(p["sys"]))
            print(f"{self.label}{of}: total {total} s, cpu {cpu} s", flush=True)
        else:
            print(f"{self.label}: not applicable (the renderer refused it, exit 2): {p['msg']}", flush=True)

    def finish(self, pin):
        """Writes the member's files from its processes (one: renamed; several:
        the first's image and stderr, the stats merged, merge_stats, after
        checking that every process made the same image) and, last, its
        record. Returns 0 (rendered) or 2 (refused)."""
        s, base, first = self.s, self.base, self.done[0]
        cmd = self.command(0)
        if first["rc"] == 2:  # refused: the combination does not apply; recorded so that it is not retried
            os.replace(first["out"] + ".err", base + ".err")
            remove_tmp(base)
            write_record(base, 2, "null", "null", "null", first["load"], self.pos[0], first["msg"], cmd,
                         s.busy_loop, pin)
            return 2
        for i, p in enumerate(self.done[1:], 2):
            if not filecmp.cmp(first["out"] + ".exr", p["out"] + ".exr", shallow=False):
                raise LaunchError(f"{self.label}: process {i} of {len(self.done)} made another image than process 1: "
                                  "the same render is not deterministic")
        if len(self.done) > 1:
            merged = merge_stats([p["out"] + ".json" for p in self.done], self.label)
            with open(base + ".tmp.merged", "w", encoding="utf-8") as f:  # a key a line, as the renderer writes
                f.write("{\n" + ",\n".join(f"  {json.dumps(k)}: {json.dumps(v)}" for k, v in merged.items()) + "\n}\n")
            os.replace(base + ".tmp.merged", base + ".stats.json")
        else:
            os.replace(first["out"] + ".json", base + ".stats.json")
        os.replace(first["out"] + ".exr", base + ".exr")
        os.replace(first["out"] + ".err", base + ".err")
        if s.dump_reps:
            os.replace(first["out"] + ".reps.csv", base + ".reps.csv")
        cpus = [round(float(p["user"]) + float(p["sys"]), 2) for p in self.done]
        best = self.done[cpus.index(min(cpus))]
        remove_tmp(base)
        extra = {} if len(self.done) == 1 else {"processes": len(self.done), "cpu_s_processes": cpus,
                                                  "pair_pos_processes": self.pos}
        if s.gauge:
            extra["gauge_added"] = len(self.done) - self.planned
        write_record(base, 0, best["user"], best["sys"], "%.2f" % min(cpus), first["load"], self.pos[0], "", cmd,
                     s.busy_loop, pin, extra)
        return 0


def gauge_slow(renders, pct):
    """The members of RENDERS (the group) whose least photon pass over all
    their processes is more than PCT % above the group's least: among the
    members rendered in several processes, all rendered (exit 0), at least
    two, with equal trace work counters, the group's least photon pass at
    least GAUGE_MIN_S; [] where there is no such gauge."""
    gauged = [r for r in renders if r.planned > 1]
    if len(gauged) < 2 or any(p["rc"] != 0 for r in gauged for p in r.done):
        return []
    docs = {r: [layout.load_json(p["out"] + ".json") for p in r.done] for r in gauged}
    works = [d.get("work", {}).get("trace") for r in gauged for d in docs[r]]
    if works[0] is None or any(w != works[0] for w in works):
        return []
    least = {r: min(d["time_s"]["trace"] for d in docs[r]) for r in gauged}
    best = min(least.values())
    if best < GAUGE_MIN_S:
        return []
    return [r for r in gauged if least[r] > best * (1 + pct / 100)]


def busy_loop(avoid=None):
    """A process spinning in a loop until killed (the caller's to end), on
    a CPU other than AVOID where this process may run on another."""
    others = sorted(os.sched_getaffinity(0) - {avoid}) if avoid is not None else []
    return subprocess.Popen([sys.executable, "-c", "while True:\n    pass"],
                            preexec_fn=pinned(others[0] if others else None))


def run_group(s, members, repeats=None):
    """Every member (root, method, extra, k) of the stem s.stem, each in
    s.processes processes (a member with its own of REPEATS ({(root,
    method): repeats}): one), in rounds: every member once per round, the
    first round in the order alternating with the seed, each next round in
    the reverse of the one before; each timed with s.repeats or its own
    repeats. All records or none."""
    m = STEM.fullmatch(s.stem)
    if not m:
        raise LaunchError(f"'{s.stem}': not ESTIMATE-pPHOTONS-nNN/seedK")
    estimate, photons, nn, seed = m["estimate"], int(m["photons"]), int(m["nn"]), int(m["seed"])
    own = repeats or {}
    renders = [Render(s, root, method, estimate, photons, nn, seed, extra, k, own.get((root, method), s.repeats),
                      1 if (root, method) in own else s.processes)
               for root, method, extra, k in members]
    records = [r.base + ".run.json" for r in renders]
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
        for r in renders:
            r.start()
        while any(r.wants() for r in renders):
            for pos, i in enumerate(order, 1):
                if renders[i].wants():
                    renders[i].run(pos if len(members) > 1 else 0, pin)
            order.reverse()
        while s.gauge:  # the gauge: another round for the members that never ran at the group's best speed
            slow = [r for r in gauge_slow(renders, s.gauge) if len(r.done) < s.max_processes]
            if not slow:
                break
            for pos, i in enumerate(order, 1):
                if renders[i] in slow:
                    renders[i].processes += 1
                    renders[i].run(pos, pin)
            order.reverse()
        for r in renders:
            r.finish(pin)
        done = True
    finally:
        if busy:
            busy.kill()
            busy.wait()
        if not done:  # the group unfinished: none of its records stays, nor a temporary file
            for r in renders:
                remove_tmp(r.base)
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
    ap.add_argument("--processes", type=int, default=1,
                    help="each member rendered in this many processes, in alternating rounds (a study's TIME_PROCESSES)")
    ap.add_argument("--gauge", type=float, default=0,
                    help="another process for a member whose least photon pass is more than this %% above the group's"
                         " least (a study's TIME_GAUGE; 0: none)")
    ap.add_argument("--max-processes", type=int, default=None,
                    help="the most processes the gauge may bring a member to (a study's TIME_PROCESSES_MAX;"
                         " default: --processes)")
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
        if s.processes < 1:
            raise LaunchError(f"--processes {s.processes}: a positive number of processes per render")
        if s.max_processes is None:
            s.max_processes = s.processes
        if s.max_processes < s.processes:
            raise LaunchError(f"--max-processes {s.max_processes}: at least --processes ({s.processes})")
        if not 0 <= s.gauge < 1000:
            raise LaunchError(f"--gauge {s.gauge:g}: a percentage in [0, 1000) (0: no gauge)")
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
