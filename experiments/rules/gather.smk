# The final-gathering study (make gather; issue 37, items 7-9): both methods
# with --gather N over P_e x n x N on every grid of GATHER_GRIDS
# ("SCENE@WxH=REF ...": make gather derives it, each grid with its converged
# reference). One sub-grid per (scene, size, N), a grid study of its own
# (studies.Study with SCENE, SIZE, REF, TAG gatherN and PM_ARGS "--gather N
# --direct shadow-rays"), so its renders live in a run root of their own and
# collect.py reads them as any grid's. Both methods of one (cell, seed) are
# one job (paired samples), each render timed with --repeats auto, except
# the conventional renders of the cells whose photon work (eye samples x N x
# n) reaches ONE_REPEAT_WORK: --repeats 1. Then per sub-grid runs.csv
# (analysis/collect.py) and the report over all of them (analysis/gather.py).
import re

from experiments import studies
from experiments.studies import shell_words
from experiments.analysis import runs as layout

F = STUDY.files
K = STUDY.knobs
GATHER_DIR = os.path.dirname(F["out"])


def gather_grids():
    """[(scene, size, reference)] of GATHER_GRIDS, checked."""
    out = []
    for word in K["GATHER_GRIDS"].split():
        m = re.fullmatch(r"(.+)@([1-9][0-9]*x[1-9][0-9]*)=(.+)", word)
        if not m:
            raise studies.StudyError(f"GATHER_GRIDS: '{word}' is not SCENE@WxH=REFERENCE.exr")
        out.append(m.groups())
    if not out:
        raise studies.StudyError("gather: GATHER_GRIDS is empty: run it as `make gather` (it names every grid and its reference)")
    return out


SUBS = {}  # gid (scene-WxH-N<n>) -> (sub-study, N)
for _scene, _size, _ref in gather_grids():
    for _n in K["GATHERS"].split():
        _sub = studies.Study(STUDY.id, studies.read_config()["studies"][STUDY.id],
                             dict(K, SCENE=_scene, SIZE=_size, REF=_ref, TAG=f"gather{_n}",
                                  PM_ARGS=f"--gather {_n} --direct shadow-rays"))
        SUBS[f"{os.path.splitext(os.path.basename(_scene))[0]}-{_size}-N{_n}"] = (_sub, int(_n))
ROOTS = {sub.root: (sub, n) for sub, n in SUBS.values()}


def gather_launch(wc):
    """Both methods of one (cell, seed) of a sub-grid, back to back (experiments/launch.py)."""
    sub, n = ROOTS[wc.groot]
    work = sub.width * sub.height * sub.subpixels ** 2 * n * int(wc.nn)
    words = [sub.python, "-m", "experiments.launch", "--pm", sub.pm, "--scene", sub.scene, "--width", sub.width,
             "--height", sub.height, "--subpixels", sub.subpixels, "--threads", sub.threads_arg,
             "--of", len(sub.run_names), "--stem", f"{wc.estimate}-p{wc.photons}-n{wc.nn}/seed{wc.seed}"]
    for m in ("conventional", "precomputed"):
        once = m == "conventional" and work >= float(K["ONE_REPEAT_WORK"])
        name = f"{layout.cell_name(m, wc.estimate, wc.photons, wc.nn)}/seed{wc.seed}"
        words += ["--member", wc.groot, m, f"{sub.pm_args} --repeats {1 if once else 'auto'}", sub.position(name)]
    return shell_words(words)


localrules: gather_collect, gather

rule gather_pair:
    output:
        "{groot}/conventional-{estimate}-p{photons}-n{nn}/seed{seed}.run.json",
        "{groot}/precomputed-{estimate}-p{photons}-n{nn}/seed{seed}.run.json",
    wildcard_constraints:
        groot="|".join(re.escape(r) for r in ROOTS),
    resources:
        timed=STUDY.timed,
    group: "renders"
    params:
        cmd=gather_launch,
    shell:
        "{params.cmd}"


def collect_command(wc):
    sub, _ = SUBS[wc.gid]
    return shell_words([sub.python, "-m", "experiments.analysis.collect", "--runroot", sub.root,
        "--conv-runroot", sub.conv_root, "--scene", sub.scene, "--width", sub.width, "--height", sub.height,
        "--subpixels", sub.subpixels, "--threads", sub.threads_arg, "--tag", sub.tag,
        "--methods", " ".join(sub.methods), "--estimates", " ".join(sub.estimates),
        "--photons", " ".join(sub.photons), "--nns", " ".join(sub.nns), "--seeds", " ".join(map(str, sub.seeds)),
        "--ref", sub.ref, "--ref-fast", "", "--runs-csv", f"{GATHER_DIR}/runs-{wc.gid}.csv",
        "--cells-csv", f"{GATHER_DIR}/cells-{wc.gid}.csv"])


rule gather_collect:
    input:
        lambda wc: SUBS[wc.gid][0].run_files,
    output:
        runs=GATHER_DIR + "/runs-{gid}.csv",
        cells=GATHER_DIR + "/cells-{gid}.csv",
    wildcard_constraints:
        gid="|".join(re.escape(g) for g in SUBS),
    params:
        cmd=collect_command,
    shell:
        "{params.cmd}"


def direct_args():
    """--direct SCENE SIZE RUNS_CSV of DIRECT_RUNS ("SCENE@WxH=RUNS_CSV ...")."""
    words = []
    for word in K["DIRECT_RUNS"].split():
        m = re.fullmatch(r"(.+)@([1-9][0-9]*x[1-9][0-9]*)=(.+)", word)
        if not m:
            raise studies.StudyError(f"DIRECT_RUNS: '{word}' is not SCENE@WxH=RUNS_CSV")
        words += ["--direct", *m.groups()]
    return words


rule gather:
    input:
        [f"{GATHER_DIR}/runs-{g}.csv" for g in SUBS],
    output:
        F["out"] + ".md",
        F["out"] + ".csv",
        F["figure"],
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.gather"]
            + [w for g, (sub, n) in SUBS.items() for w in ("--grid", sub.scene, sub.size, n, f"{GATHER_DIR}/runs-{g}.csv")]
            + direct_args() + ["--time", K["TIME"], "--out", F["out"], "--figure", F["figure"],
            "--bootstrap", K["BOOTSTRAP"], "--bootstrap-seed", K["BOOTSTRAP_SEED"], "--pm", STUDY.pm]),
    shell:
        "{params.cmd}"
