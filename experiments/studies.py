"""studies.py: a study of experiments/studies.yaml with the knobs of one
command line applied and checked: its grid, run layout, reference, analysis
files and the command lines of its renders and analysis steps. The
Snakefile (experiments/Snakefile) builds its rules from one Study.

    study = studies.load("table1", {"SIZE": "64x48", "SEEDS": "2"})

A knob given (SIZE, SEEDS, SCENE, PHOTONS, NNS, ...) overrides the study's
own value; a retired knob name is refused with the name that replaced it;
SIZE and SEEDS are checked before anything renders.
"""

import os
import re
import shlex

import yaml

from experiments.analysis import runs as layout

CONFIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "studies.yaml")
MAX_SIDE = 16384  # the renderer's --width and --height range


class StudyError(Exception):
    """A knob or a study that cannot run, with the reason."""


def read_config(path=CONFIG):
    with open(path, encoding="utf-8") as f:
        return yaml.safe_load(f)


def knob_text(value):
    """A knob's value as make would have it: a string (None is empty)."""
    return "" if value is None else str(value).strip()


def check_retired(given, retired):
    """Refuses every retired name among the knobs GIVEN."""
    for old in sorted(given):
        if old in retired:
            raise StudyError(f"{old} is gone: every study target reads {retired[old]} (e.g. make scenes SIZE=128x96 SEEDS=2)")


def parse_size(size):
    """(width, height) of WxH, checked."""
    m = re.fullmatch(r"([1-9][0-9]*)x([1-9][0-9]*)", size)
    if not m:
        raise StudyError(f"SIZE={size}: not WxH (e.g. 512x384)")
    w, h = int(m[1]), int(m[2])
    if w > MAX_SIDE or h > MAX_SIDE:
        raise StudyError(f"SIZE={size}: each side must be at most {MAX_SIDE}, the renderer's --width and --height range")
    return w, h


def parse_seeds(seeds):
    """The seeds 1..N of SEEDS=N, checked."""
    if not re.fullmatch(r"[0-9]+", seeds) or int(seeds) == 0:
        raise StudyError(f"SEEDS={seeds}: a positive number of seeds")
    return list(range(1, int(seeds) + 1))


def parse_seed(seed, knob):
    """The one seed of KNOB=SEED, checked."""
    if not re.fullmatch(r"[0-9]+", seed) or int(seed) == 0:
        raise StudyError(f"{knob}={seed}: a positive seed")
    return [int(seed)]


def pov_reference(size, scene, fast=False, top="."):
    """The POV-Ray reference EXR of SCENE at SIZE in reference/<scene>/, or
    "". Prefers, for the per-pixel metrics, the one rendered with the
    renders' own 2x2 subpixel rays (<scene>-reference-2x2-WxH.exr), then
    <scene>-reference-WxH.exr, then any other render of that size that is not
    direct-only, fast-preset, bounce-limited (-bK-), a negative control
    (nocaustic) or pbrt's. FAST: the fast preset of the same pixels and
    sampling as that reference (its error against it is the reference's
    floor), or ""."""
    name = os.path.splitext(os.path.basename(scene))[0]
    d = os.path.join("reference", name)
    exists = lambda f: os.path.isfile(os.path.join(top, d, f))
    two = f"{name}-reference-2x2-{size}.exr"
    if fast:
        f = f"{name}-fast-2x2-{size}.exr" if exists(two) else f"{name}-fast-{size}.exr"
        return os.path.join(d, f) if exists(f) else ""
    for f in (two, f"{name}-reference-{size}.exr"):
        if exists(f):
            return os.path.join(d, f)
    others = sorted(f for f in (os.listdir(os.path.join(top, d)) if os.path.isdir(os.path.join(top, d)) else [])
                    if f.startswith(name + "-") and size in f and f.endswith(".exr")
                    and not re.search(r"direct|fast|nocaustic|pbrt|-b[0-9]+-", f, re.I))
    return os.path.join(d, others[0]) if others else ""


class Study:
    """One study with its knobs applied (attributes named after the knobs,
    lower case) and everything derived from them."""

    def __init__(self, sid, decl, knobs):
        self.id, self.target = sid, decl["target"]
        k = {name: knob_text(v) for name, v in knobs.items()}
        self.knobs = k
        self.results, self.pm, self.python = k["RESULTS"], k["PM"], k["PYTHON"]
        self.scene, self.size, self.subpixels = k["SCENE"], k["SIZE"], int(k["SUBPIXELS"])
        self.width, self.height = parse_size(self.size)
        # a study of one render names the knobs of its P_e, n and seed (grid:)
        grid = decl.get("grid") or {}
        self.seeds = parse_seed(k[grid["seed"]], grid["seed"]) if "seed" in grid else parse_seeds(k["SEEDS"])
        self.photons, self.nns = k[grid.get("photons", "PHOTONS")].split(), k[grid.get("nns", "NNS")].split()
        self.dump_reps = bool(decl.get("dump_reps", False))
        self.methods, self.estimates = k["METHODS"].split(), k["ESTIMATES"].split()
        self.threads = k["THREADS"]
        self.threads_arg = self.threads or "0"
        self.tag, self.pm_args = k["TAG"], k["PM_ARGS"]
        name = os.path.splitext(os.path.basename(self.scene))[0]
        self.root = (os.path.join(self.results, decl["root"].format(name=name, size=self.size, subpixels=self.subpixels))
                     if decl.get("root") else
                     layout.run_root(self.results, self.scene, self.size, self.subpixels, self.threads, self.tag))
        self.timed = 1 if decl.get("timed", True) else 0
        self.conv_root = k["CONV_RUNROOT"] or self.root
        self.run_names = layout.run_names(self.photons, self.nns, self.methods, self.estimates, self.seeds)
        self.run_files = [layout.record_path(self.root, n) for n in self.run_names]
        # both methods: the two renders of one (cell, seed) are one job, back to back
        self.paired = sorted(set(self.methods) & {"conventional", "precomputed"}) == ["conventional", "precomputed"]
        self.ref, self.ref_fast = k["REF"], k["REF_FAST"]
        if decl.get("reference") == "pov" and not self.ref:
            self.ref = pov_reference(self.size, self.scene)
            self.ref_fast = pov_reference(self.size, self.scene, fast=True) if decl.get("pov_floor", True) else ""
        self.no_ref = decl.get("no_reference", "no reference").format(scene=self.scene, size=self.size, name=name)
        self.figures = k.get("FIGURES") or os.path.join(self.results, "figures")
        tag = f"-{self.tag}" if self.tag else ""
        self.files = {}
        for key, f in decl["files"].items():
            f = f.format(tag=tag, figures=self.figures)
            self.files[key] = f if f.startswith(self.figures) else os.path.join(self.results, f)

    def check_reference(self):
        """Refuses a study whose analysis has no reference (before any render)."""
        if not self.ref:
            raise StudyError(f"{self.target}: {self.no_ref}")

    def position(self, name):
        """The place (1..N) of the render NAME in the study's run list."""
        return self.run_names.index(name) + 1

    def launch_command(self, root, methods, estimate, photons, nn, seed):
        """The shell command rendering METHODS of one (cell, seed) back to back
        (experiments/launch.py)."""
        stem = f"{estimate}-p{photons}-n{nn}/seed{seed}"
        words = [self.python, "-m", "experiments.launch", "--pm", self.pm, "--scene", self.scene,
                 "--width", self.width, "--height", self.height, "--subpixels", self.subpixels,
                 "--threads", self.threads_arg, "--of", len(self.run_names), "--stem", stem]
        for m in methods:
            name = f"{layout.cell_name(m, estimate, photons, nn)}/seed{seed}"
            words += ["--member", root, m, self.pm_args, self.position(name)]
        return shell_words(words + (["--dump-reps"] if self.dump_reps else []))


def shell_words(words):
    """WORDS as one shell command line, each word quoted as needed."""
    return " ".join(shlex.quote(str(w)) for w in words)


def load(sid, given, path=CONFIG):
    """The study SID with the knobs GIVEN (a dict NAME: value, e.g. from make's
    command line) applied over its own and the common defaults."""
    conf = read_config(path)
    check_retired(given, conf["retired"])
    if sid not in conf["studies"]:
        raise StudyError(f"no study '{sid}' in {path} (studies: {' '.join(conf['studies'])})")
    decl = conf["studies"][sid]
    knobs = dict(conf["defaults"])
    knobs.update(decl.get("knobs") or {})
    knobs.update({name: v for name, v in given.items() if name in knobs})
    knobs.update(decl.get("fixed") or {})
    return Study(sid, decl, knobs)


def main(argv=None):
    """python3 -m experiments.studies list-runs STUDY [NAME=VALUE ...]: every
    render's record path of STUDY with those knobs (VALUE as make's front
    door passes it: a YAML string), one per line, in the study's run order.
    Exit 2 with the reason for a knob or study that cannot run."""
    import sys
    args = sys.argv[1:] if argv is None else argv
    if len(args) < 2 or args[0] != "list-runs":
        print("usage: python3 -m experiments.studies list-runs STUDY [NAME=VALUE ...]", file=sys.stderr)
        return 2
    given = {}
    for a in args[2:]:
        name, _, value = a.partition("=")
        given[name] = knob_text(yaml.safe_load(value)) if value else ""
    try:
        study = load(args[1], given)
    except StudyError as e:
        print(f"studies: {e}", file=sys.stderr)
        return 2
    print("\n".join(study.run_files))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
