# The render rules: every record of the run layout
# (experiments/analysis/runs.py) is made by one of them, through the render
# launcher (experiments/launch.py). With both methods in the study, the two
# renders of one (cell, seed) are one job (rule pair), back to back, their
# order alternating with the seed, so that they are paired samples of one
# machine state; otherwise one render is one job (rule render). A grouped
# study renders one (cell, seed) of a case, every block's render, as one job
# (rule group), an interleaved one pair k of each of its grids (rule
# interleave). Renders
# whose times a study compares hold the resource `timed` (make passes
# --resources timed=1: one at a time; analysis jobs and the renders of an
# untimed study, `timed: false` in studies.yaml, run beside them). Jobs
# of the group `renders` are sent to a cluster together (--group-components).
import re
from experiments.studies import shell_words
from experiments.analysis import runs as layout

NONE = "(?!)"  # a root regex that matches nothing
GROUPED = STUDY.decl.get("grouped", False)
INTERLEAVED = STUDY.decl.get("interleaved", False)

def roots(paired):
    """The run roots of the study's grids that render both methods as one
    job (PAIRED) or one by one, as a regex (none in a grouped study)."""
    rs = [re.escape(g.root) for g in STUDY.grids if g.paired == paired and not (GROUPED or INTERLEAVED)]
    return "|".join(rs) if rs else NONE
PAIRED, SINGLE = roots(True), roots(False)

wildcard_constraints:
    estimate="[a-z]+",
    photons="[0-9]+",
    nn="[0-9]+",
    seed="[0-9]+",

rule pair:
    output:
        "{root}/conventional-{estimate}-p{photons}-n{nn}/seed{seed}.run.json",
        "{root}/precomputed-{estimate}-p{photons}-n{nn}/seed{seed}.run.json",
    input:
        lambda wc: STUDY.render_after,
    wildcard_constraints:
        root=PAIRED,
    resources:
        timed=STUDY.timed,
    group: "renders"
    params:
        cmd=lambda wc: STUDY.by_root[wc.root].launch_command(wc.root, ["conventional", "precomputed"], wc.estimate, wc.photons, wc.nn, wc.seed),
    shell:
        "{params.cmd}"

rule render:
    output:
        "{root}/{method}-{estimate}-p{photons}-n{nn}/seed{seed}.run.json",
    input:
        lambda wc: STUDY.render_after,
    wildcard_constraints:
        root=SINGLE,
        method="conventional|precomputed",
    resources:
        timed=STUDY.timed,
    group: "renders"
    params:
        cmd=lambda wc: STUDY.by_root[wc.root].launch_command(wc.root, [wc.method], wc.estimate, wc.photons, wc.nn, wc.seed),
    shell:
        "{params.cmd}"

# a grouped study (studies.yaml grouped: true): the renders of one (cell,
# seed) of a case, every method of the first block's grid, then the
# precomputed render of each grid compared with it (the variants), are one
# job, back to back, the order alternating with the seed (rule group)
if GROUPED:
    BASES = STUDY.blocks[0][2]
    MEMBERS = [(g.root[len(BASES[0].root):], g) for g in STUDY.grids if g not in BASES and g.conv_root == BASES[0].root]
    STEM = "{estimate}-p{photons}-n{nn}/seed{seed}.run.json"

    def group_command(wc):
        base = STUDY.by_root[wc.root]
        stem = f"{wc.estimate}-p{wc.photons}-n{wc.nn}/seed{wc.seed}"
        members = [(base, m) for m in base.methods] + [(STUDY.by_root[wc.root + sfx], "precomputed") for sfx, _ in MEMBERS]
        words = base.launch_words(stem)
        for g, m in members:
            words += g.member_words(g.root, m, wc.nn, base.position(f"{m}-{stem}"))
        return shell_words(words)

    rule group:
        output:
            [f"{{root}}/{m}-{STEM}" for m in BASES[0].methods] + [f"{{root}}{sfx}/precomputed-{STEM}" for sfx, _ in MEMBERS],
        wildcard_constraints:
            root="|".join(re.escape(g.root) for g in BASES),
        resources:
            timed=STUDY.timed,
        group: "renders"
        params:
            cmd=group_command,
        shell:
            "{params.cmd}"

# an interleaved study (studies.yaml interleaved: true; make
# reproducibility): its grids (runs A and B, both methods) render pair k of
# every run in one job, pair by pair, in the order of the blocks at odd k and
# reversed at even k (k: the pair's place in the grid's order, seeds
# outermost), each pair back to back as rule pair does, every render pinned
# with taskset -c REPRO_TASKSET (empty: not pinned)
if INTERLEAVED:
    RUNS = STUDY.grids
    PREFIX = os.path.commonprefix([g.root for g in RUNS])
    STEM = "{estimate}-p{photons}-n{nn}/seed{seed}.run.json"
    PAIRS = [n[len("x-"):] for n in layout.run_names(RUNS[0].photons, RUNS[0].nns, ["x"], RUNS[0].estimates, RUNS[0].seeds)]

    def interleave_command(wc):
        stem = f"{wc.estimate}-p{wc.photons}-n{wc.nn}/seed{wc.seed}"
        k = PAIRS.index(stem) + 1
        pin = ["taskset", "-c", STUDY.taskset] if STUDY.taskset else []
        cmds = []
        for g in (RUNS if k % 2 == 1 else RUNS[::-1]):
            launch = g.launch_command(g.root, ["conventional", "precomputed"], wc.estimate, wc.photons, wc.nn, wc.seed)
            cmds.append(f"echo {shell_words([f'reproducibility: run {g.name} pair {k}: {stem}'])} && "
                        + (shell_words(pin) + " " if pin else "") + launch)
        return " && ".join(cmds)

    rule interleave:
        output:
            [f"{{prefix}}{g.root[len(PREFIX):]}/{m}-{STEM}" for g in RUNS for m in ("conventional", "precomputed")],
        wildcard_constraints:
            prefix=re.escape(PREFIX),
        resources:
            timed=STUDY.timed,
        group: "renders"
        params:
            cmd=interleave_command,
        shell:
            "{params.cmd}"

# only the renders of the study and the references it renders (make estimator-bias-runs)
localrules: runs

rule runs:
    input:
        STUDY.run_files + sorted({g.ref for g in STUDY.grids if g.ref_converged}),
