"""studies.py: a study of experiments/studies.yaml with the knobs of one
command line applied and checked: its grids (Grid: one grid of renders with
its run layout, reference, analysis files and render command lines), in
blocks (studies.yaml grids:: one grid per word of a knob, per case, or
both), and its report's files. The Snakefile (experiments/Snakefile) builds
its rules from one Study.

    study = studies.load("table1", {"SIZE": "64x48", "SEEDS": "2"})

A knob given (SIZE, SEEDS, SCENE, PHOTONS, NNS, ...) overrides the study's
own value; a retired knob name is refused with the name that replaced it;
SIZE, SEEDS, TIME_REPEATS, TIME_PROCESSES, TIME_PROCESSES_MAX, TIME_GAUGE and
TIME_CPU are checked before anything renders.
"""

import glob
import itertools
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


def parse_time_repeats(text):
    """TIME_REPEATS checked: "auto" or a positive count, as the renderer's
    --repeats takes it (1: a single timed run)."""
    if text == "auto" or re.fullmatch(r"[1-9][0-9]*", text):
        return text
    raise StudyError(f"TIME_REPEATS={text}: auto or a positive number of timed runs per render (1: a single timed run)")


def parse_time_cpu(text):
    """TIME_CPU checked: first, none, or a CPU number (launch.py --cpu; the
    launcher checks that the CPU is one it may run on)."""
    if text in ("first", "none") or re.fullmatch(r"[0-9]+", text):
        return text
    raise StudyError(f"TIME_CPU={text}: first (the lowest CPU the launcher may run on), none, or a CPU number")


def parse_time_processes(text):
    """TIME_PROCESSES checked: a positive number of processes per timed
    render (launch.py --processes; 1: one process)."""
    if re.fullmatch(r"[1-9][0-9]*", text):
        return text
    raise StudyError(f"TIME_PROCESSES={text}: a positive number of processes per timed render (1: one process)")


def parse_time_gauge(text, processes, most):
    """TIME_GAUGE and TIME_PROCESSES_MAX checked: a percentage in [0,
    1000) (launch.py --gauge; 0: no gauge) and a positive number of
    processes. Returns both as text, the maximum at least PROCESSES
    (TIME_PROCESSES: a maximum below it leaves the gauge no room)."""
    if not re.fullmatch(r"[0-9]+(\.[0-9]+)?", text) or float(text) >= 1000:
        raise StudyError(f"TIME_GAUGE={text}: a percentage in [0, 1000) (0: no gauge)")
    if not re.fullmatch(r"[1-9][0-9]*", most):
        raise StudyError(f"TIME_PROCESSES_MAX={most}: a positive number of processes per timed render")
    return text, str(max(int(most), int(processes)))


def scene_key(scene):
    """The first 12 hex digits of the SHA-256 of SCENE's content: a scene's
    name in the paths of a study of that one scene (evaluate)."""
    import hashlib
    with open(scene, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()[:12]


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


class Grid:
    """One grid of renders of a study (every P_e x n x method x estimate x
    seed on one scene at one size) with its run layout, reference and
    analysis files; attributes named after the knobs, lower case. NAME: the
    grid's name in its files' {grid} (a study of one grid: "")."""

    def __init__(self, study, decl, k, name="", files=None, conv=None, root=None, block=None):
        self.study, self.name = study, name
        self.knobs = k
        self.results, self.pm, self.python = k["RESULTS"], k["PM"], k["PYTHON"]
        self.scene, self.size, self.subpixels = k["SCENE"], k["SIZE"], int(k["SUBPIXELS"])
        self.width, self.height = parse_size(self.size)
        # a study of one render names the knobs of its P_e, n and seed (render_knobs:)
        rk = decl.get("render_knobs") or {}
        self.seeds = parse_seed(k[rk["SEED"]], rk["SEED"]) if "SEED" in rk else parse_seeds(k["SEEDS"])
        self.photons, self.nns = k[rk.get("PHOTONS", "PHOTONS")].split(), k[rk.get("NNS", "NNS")].split()
        self.dump_reps = bool(decl.get("dump_reps", False))
        self.methods, self.estimates = k["METHODS"].split(), k["ESTIMATES"].split()
        self.threads = k["THREADS"]
        self.threads_arg = self.threads or "0"
        self.tag, self.pm_args = k["TAG"], k["PM_ARGS"]
        scene_name = os.path.splitext(os.path.basename(self.scene))[0]
        root = root or decl.get("root")
        if root:
            root = root.format(name=scene_name, size=self.size, subpixels=self.subpixels, out=study.out,
                               value=k.get("VALUE", ""), key=scene_key(self.scene) if "{key}" in root else "",
                               threads=layout.threads_label(self.threads))
        self.root = ((root if study.out and root.startswith(study.out) else os.path.join(self.results, root))
                     if root else
                     layout.run_root(self.results, self.scene, self.size, self.subpixels, self.threads, self.tag))
        # a study whose times are not compared renders once
        self.time_repeats = parse_time_repeats(k["TIME_REPEATS"]) if decl.get("timed", True) else "1"
        # TIME_PROCESSES: the processes each timed render runs in (launch.py --processes)
        self.time_processes = parse_time_processes(k["TIME_PROCESSES"]) if decl.get("timed", True) else "1"
        # TIME_GAUGE, TIME_PROCESSES_MAX: the photon pass as the group's speed gauge (launch.py --gauge)
        self.time_gauge, self.time_processes_max = (parse_time_gauge(k["TIME_GAUGE"], self.time_processes,
                                                                     k["TIME_PROCESSES_MAX"])
                                                    if decl.get("timed", True) else ("0", "1"))
        # TIME_CPU: the CPU its timed one-thread renders are pinned to (launch.py --cpu)
        self.time_cpu = parse_time_cpu(k["TIME_CPU"]) if decl.get("timed", True) and self.threads == "1" else "none"
        # studies.yaml one_repeat: the renders whose work reaches a knob's value run once
        self.one_repeat = (block or {}).get("one_repeat") or decl.get("one_repeat")
        # the conventional renders compared with: CONV_RUNROOT, the grid CONV's, or its own
        self.conv_root = k["CONV_RUNROOT"] or (conv.root if conv else self.root)
        self.conv_files = conv.run_files if conv else []
        self.run_names = layout.run_names(self.photons, self.nns, self.methods, self.estimates, self.seeds)
        self.run_files = [layout.record_path(self.root, n) for n in self.run_names]
        self.after = []  # records every render of the grid waits for (a sequential study: the grid before)
        # BUSY_LOOP: a busy loop runs beside each of the grid's render jobs (launch.py --busy-loop)
        self.busy_loop = k.get("BUSY_LOOP", "") not in ("", "0")
        # both methods: the two renders of one (cell, seed) are one job, back to back
        self.paired = sorted(set(self.methods) & {"conventional", "precomputed"}) == ["conventional", "precomputed"]
        self.ref, self.ref_fast = k["REF"], k["REF_FAST"]
        self.ref_converged = False  # the reference is ours (study.converged_ref), made by rules/reference.smk
        kind = reference_kind(decl.get("reference"), k)
        if kind in ("pov", "pov_or_converged") and not self.ref:
            self.ref = pov_reference(self.size, self.scene)
            self.ref_fast = pov_reference(self.size, self.scene, fast=True) if decl.get("pov_floor", True) else ""
        if kind == "converged" or (kind == "pov_or_converged" and not self.ref):
            self.ref, self.ref_fast = study.converged_ref(self.scene, self.size, self.seeds), ""
            self.ref_converged = True
        self.no_ref = decl.get("no_reference", "no reference").format(scene=self.scene, size=self.size, name=scene_name)
        self.files = {key: f.format(grid=name) for key, f in (files or study.files).items()}

    def check_reference(self):
        """Refuses a grid whose analysis has no reference (before any render)."""
        if not self.ref:
            raise StudyError(f"{self.study.target}: {self.no_ref}")

    def position(self, name):
        """The place (1..N) of the render NAME in the grid's run list."""
        return self.run_names.index(name) + 1

    def once(self, method, nn):
        """Whether the grid's render of METHOD at n = NN is timed once: the
        block's one_repeat (studies.yaml: {methods, factor, at}) says its
        work, eye samples (width x height x subpixels^2) x n x the knob
        FACTOR's value, reaches the knob AT's value for one of its METHODS."""
        once = self.one_repeat
        if not once or method not in once["methods"]:
            return False
        work = self.width * self.height * self.subpixels ** 2 * int(nn) * float(self.knobs[once["factor"]])
        return work >= float(self.knobs[once["at"]])

    def repeats(self, method, nn):
        """The --repeats of the grid's render of METHOD at n = NN: 1 where it
        is timed once (once), else TIME_REPEATS."""
        return "1" if self.once(method, nn) else self.time_repeats

    def processes(self, method, nn):
        """The processes the grid's render of METHOD at n = NN runs in: 1
        where it is timed once (once), else TIME_PROCESSES."""
        return 1 if self.once(method, nn) else int(self.time_processes)

    def launch_words(self, stem):
        """The launcher's words common to every job of the grid rendering the
        renders STEM (ESTIMATE-pP-nN/seedK) of one (cell, seed): the members
        (member_words) follow (experiments/launch.py)."""
        return [self.python, "-m", "experiments.launch", "--cpu", self.time_cpu, "--processes", self.time_processes,
                "--gauge", self.time_gauge, "--max-processes", self.time_processes_max,
                "--pm", self.pm, "--scene", self.scene,
                "--width", self.width, "--height", self.height, "--subpixels", self.subpixels,
                "--threads", self.threads_arg, "--repeats", self.time_repeats, "--of", len(self.run_names),
                "--stem", stem] + (["--busy-loop"] if self.busy_loop else [])

    def member_words(self, root, method, nn, k):
        """The launcher's words of one member: the render of METHOD at n = NN
        into ROOT with the grid's renderer options, run K of the study's, and
        --member-repeats ROOT METHOD 1 where it is timed once (once: one
        repeat, in one process)."""
        words = ["--member", root, method, self.pm_args, k]
        return words + (["--member-repeats", root, method, "1"] if self.once(method, nn) else [])

    def launch_command(self, root, methods, estimate, photons, nn, seed):
        """The shell command rendering METHODS of one (cell, seed) back to back
        (experiments/launch.py)."""
        stem = f"{estimate}-p{photons}-n{nn}/seed{seed}"
        words = self.launch_words(stem)
        for m in methods:
            words += self.member_words(root, m, nn, self.position(f"{layout.cell_name(m, estimate, photons, nn)}/seed{seed}"))
        return shell_words(words + (["--dump-reps"] if self.dump_reps else []))


def reference_kind(decl_ref, knobs):
    """A study's kind of reference: pov (REF, else the POV-Ray one),
    converged (ours), pov_or_converged (the POV-Ray one where there is one,
    else ours), or None; a mapping {KNOB: {value: kind}} picks it by a knob."""
    if not isinstance(decl_ref, dict):
        return decl_ref
    (knob, kinds), = decl_ref.items()
    value = knob_text(knobs[knob])
    if value not in kinds:
        raise StudyError(f"{knob}={value}: {' or '.join(kinds)}")
    return kinds[value]


def knob_words(k, knob, exclude=()):
    """The words of the knob KNOB's value, a word with * a glob (sorted, less EXCLUDE)."""
    out = []
    for w in k[knob].split():
        out += [f for f in sorted(glob.glob(w)) if f not in exclude] if "*" in w else [w]
    return out


def grid_values(block, k, given):
    """The values of a block's knob OVER: one grid per word, given to the
    grid as the knob KNOB; KNOB given alone, without OVER: that value only.
    A block without OVER: one value, ""."""
    if not block.get("over"):
        return [""]
    if block["knob"] in given and block["over"] not in given:
        return [k[block["knob"]]]
    if not k[block["over"]] and block.get("over_default"):
        return default_words(block["over_default"], k)
    return knob_words(k, block["over"], block.get("exclude") or [])


def default_words(spec, k):
    """The words of OVER_DEFAULT (for an empty OVER): each item a word, or
    {each: KNOB, words: [..]}: those words with {} the KNOB's each word."""
    out = []
    for item in spec:
        if isinstance(item, dict):
            out += [w.format(x) for x in k[item["each"]].split() for w in item["words"]]
        else:
            out.append(item)
    return out


def block_cases(block, k):
    """The cases of a block (studies.yaml cases:): [(name, knob settings)],
    the union of the products of the listed knobs' words (only: the scenes
    of that name), sorted by the block's SORT; a block without cases: one
    case without settings."""
    if not block.get("cases"):
        return [("", {})]
    cases = {}
    for entry in block["cases"]:
        axes = [(knob, knob_words(k, src, block.get("exclude") or [])) for knob, src in entry.items() if knob != "only"]
        for combo in itertools.product(*[words for _, words in axes]):
            st = dict(zip([knob for knob, _ in axes], combo))
            name = os.path.splitext(os.path.basename(st.get("SCENE", k["SCENE"])))[0]
            if entry.get("only") in (None, name):
                fmt = dict(k, **st, name=name)
                cases[block["sort"].format(**fmt)] = (block["case_name"].format(**fmt), st)
    return [cases[key] for key in sorted(cases)]


def grid_name(block, case, value):
    """A grid's name in its files' {grid}: its case's name and its value
    (the scene's name for SCENE; as the block's value_name spells it, e.g.
    "N{value}") joined by -, or the block's name."""
    if block.get("over"):
        value = os.path.splitext(os.path.basename(value))[0] if block.get("knob") == "SCENE" else value
        value = block.get("value_name", "{value}").format(value=value)
    return "-".join(x for x in (case, value) if x) or block.get("name", "")


def value_args(block, value, target, k):
    """The renderer options of a grid's VALUE by the block's ARGS table
    (regex: options, {0}.. its groups, {KNOB} a knob's value); a value no
    regex matches is refused."""
    for regex, options in (block.get("args") or {}).items():
        m = re.fullmatch(regex, value)
        if m:
            return options.format(*m.groups(), **k)
    if block.get("args"):
        raise StudyError(f"{target}: " + block.get("bad_value", "'{value}': no options for it").format(value=value))
    return ""


class Study:
    """One study with its knobs applied: its grids (Grid) and its report's
    files. A study of one grid reads as that grid too (study.root,
    study.run_files, ...)."""

    def __init__(self, sid, decl, knobs, given=()):
        self.id, self.target, self.decl = sid, decl["target"], decl
        k = {name: knob_text(v) for name, v in knobs.items()}
        self.knobs, self.given = k, set(given)
        self.results, self.pm, self.python = k["RESULTS"], k["PM"], k["PYTHON"]
        self.timed = 1 if decl.get("timed", True) else 0
        self.figures = k.get("FIGURES") or os.path.join(self.results, "figures")
        # a study whose files live in a directory of their own (studies.yaml
        # out: under RESULTS, {name} the scene's name), unless OUT is given
        scene_name = os.path.splitext(os.path.basename(k["SCENE"]))[0]
        self.out = (k.get("OUT") or os.path.join(self.results, decl["out"].format(name=scene_name))) if decl.get("out") else ""
        self.files = self.block_files(decl["files"])
        self.render_after = []  # files every render of the study waits for (evaluate: the references' check)
        self.ref_scenes = {}  # name -> scene file of every converged reference
        self.ref_seeds = set()  # the seeds of every grid judged against one
        # the blocks of grids (studies.yaml grids:, default one grid of the
        # study's own knobs): (block name, its files with {grid}, its grids)
        self.blocks, by_block = [], {}
        for b in decl.get("grids") or [{}]:
            files = self.block_files(b["files"]) if b.get("files") else self.files
            grids = []
            for case, settings in block_cases(b, k):
                for value in grid_values(b, k, given):
                    kk = dict(k)
                    kk.update({n: knob_text(v) for n, v in (b.get("knobs") or {}).items() if n not in given})
                    kk.update(settings)
                    if b.get("over"):
                        kk[b["knob"]] = value
                    conv = by_block[b["conv"]][len(grids) // len(grid_values(b, k, given))] if b.get("conv") else None
                    args = value_args(b, value, self.target, kk)
                    kk.update({n: knob_text(v).format(value=value, args=args) for n, v in (b.get("fixed") or {}).items()})
                    kk.update({n: knob_text(v) for n, v in ((b.get("per_value") or {}).get(value) or {}).items()})
                    kk["VALUE"] = value
                    grids.append(Grid(self, decl, kk, grid_name(b, case, value), files, conv, b.get("root"), b))
            by_block[b.get("name", "")] = grids
            self.blocks.append((b.get("name", ""), files, grids))
        self.grids = [g for _, _, gs in self.blocks for g in gs]
        self.by_name = {g.name: g for g in self.grids}
        self.by_root = {g.root: g for g in self.grids}
        self.run_files = [f for g in self.grids for f in g.run_files]
        # sequential: true: each grid renders after every render of the one before
        if decl.get("sequential"):
            for before, g in zip(self.grids, self.grids[1:]):
                g.after = before.run_files

    def block_files(self, files):
        """FILES (key: path under RESULTS or in FIGURES) with {tag} and
        {figures} filled in; {grid} stays for the rules' wildcard."""
        tag = f"-{self.knobs['TAG']}" if self.knobs["TAG"] else ""
        out = {}
        for key, f in files.items():
            f = f.format(tag=tag, figures=self.figures, grid="{grid}", out=self.out)
            mine = f.startswith(self.figures) or (self.out and f.startswith(self.out))
            out[key] = f if mine else os.path.join(self.results, f)
        return out

    def __getattr__(self, attr):
        """A study of one grid: the grid's attribute."""
        grids = self.__dict__.get("grids")
        if grids and len(grids) == 1 and not attr.startswith("_"):
            return getattr(grids[0], attr)
        raise AttributeError(attr)

    def grid(self, wildcards, block=0):
        """The grid of a rule's job on the block BLOCK (index): by its {grid}
        wildcard, else the block's only one."""
        grids = self.blocks[block][2]
        return grids[0] if len(grids) == 1 else self.by_name[wildcards.get("grid", "")]

    def related(self, name):
        """The study another one of the study's results comes from
        (studies.yaml related: NAME: {study, knobs}), loaded with this
        study's values of the knobs KNOBS."""
        rel = self.decl["related"][name]
        return load(rel["study"], {n: self.knobs[n] for n in rel["knobs"]})

    def conv_ref_photons(self):
        """P_e of our converged reference: CONV_REF_PHOTONS, or CONV_REF_FACTOR
        times the largest P_e of the study's PHOTONS."""
        k = self.knobs
        if k["CONV_REF_PHOTONS"]:
            return k["CONV_REF_PHOTONS"]
        p = max(float(x) for x in k["PHOTONS"].split()) * float(k["CONV_REF_FACTOR"])
        return str(int(p)) if p == int(p) else "%.6g" % p

    def conv_ref_seeds(self):
        return self.knobs["CONV_REF_SEEDS"].split()

    def converged_ref(self, scene, size, grid_seeds=()):
        """Our converged reference of SCENE at SIZE (rules/reference.smk makes
        it); GRID_SEEDS, the seeds of the grid it judges, are refused among
        CONV_REF_SEEDS (before any render)."""
        k = self.knobs
        both = sorted(set(map(int, grid_seeds)) & {int(s) for s in self.conv_ref_seeds() if s.isdigit()})
        if both:
            raise StudyError(f"{self.target}: CONV_REF_SEEDS={k['CONV_REF_SEEDS']}: seed(s) {both} are the grid's: "
                             "the reference would share photon paths with the renders it judges")
        name = os.path.splitext(os.path.basename(scene))[0]
        if self.ref_scenes.setdefault(name, scene) != scene:
            raise StudyError(f"{self.target}: two scenes named {name} ({self.ref_scenes[name]}, {scene}): "
                             "their converged references would share one file")
        self.ref_seeds.update(grid_seeds)
        return layout.converged_ref(self.results, scene, size, self.conv_ref_photons(), k["CONV_REF_NN"],
                                    k["CONV_REF_DIRECT"], k["SUBPIXELS"], self.conv_ref_seeds())


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
    refused = decl.get("refused") or {}
    bad = sorted(set(refused.get("knobs", [])) & set(given), key=refused.get("knobs", []).index)
    if bad:
        raise StudyError(f"{decl['target']}: {refused['why']}".replace("{knob}", bad[0]))
    for knob, why in (decl.get("required") or {}).items():
        if knob not in given:
            raise StudyError(f"{decl['target']}: {why}")
        if not os.path.isfile(knob_text(given[knob])):
            raise StudyError(f"{decl['target']}: {knob}={knob_text(given[knob])}: no such file")
    return Study(sid, decl, knobs, given)


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
        try:
            given[name] = knob_text(yaml.safe_load(value)) if value else ""
        except yaml.YAMLError as e:
            print(f"studies: {name}={value}: not a value ({' '.join(str(e).split())})", file=sys.stderr)
            return 2
    try:
        study = load(args[1], given)
    except StudyError as e:
        print(f"studies: {e}", file=sys.stderr)
        return 2
    print("\n".join(study.run_files))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
