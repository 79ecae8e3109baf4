# The render rules: every record of the run layout
# (experiments/analysis/runs.py) is made by one of them, through the render
# launcher (experiments/launch.py). With both methods in the study, the two
# renders of one (cell, seed) are one job (rule pair), back to back, their
# order alternating with the seed, so that they are paired samples of one
# machine state; otherwise one render is one job (rule render). A grouped
# study renders one (cell, seed) of a case, every block's render, as one job
# (rule group). In a sequential study (studies.yaml sequential: true) a
# grid's renders wait for every render of the grid before it. Renders
# whose times a study compares hold the resource `timed` (make passes
# --resources timed=1: one at a time; analysis jobs and the renders of an
# untimed study, `timed: false` in studies.yaml, run beside them). Jobs
# of the group `renders` are sent to a cluster together (--group-components).
import re
from experiments.studies import shell_words
from experiments.analysis import runs as layout

NONE = "(?!)"  # a root regex that matches nothing
GROUPED = STUDY.decl.get("grouped", False)

def roots(paired):
    """The run roots of the study's grids that render both methods as one
    job (PAIRED) or one by one, as a regex (none in a grouped study)."""
    rs = [re.escape(g.root) for g in STUDY.grids if g.paired == paired and not GROUPED]
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
        lambda wc: STUDY.render_after + STUDY.by_root[wc.root].after,
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
        lambda wc: STUDY.render_after + STUDY.by_root[wc.root].after,
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

# only the renders of the study and the references it renders (make estimator-bias-runs)
localrules: runs

rule runs:
    input:
        STUDY.run_files + sorted({g.ref for g in STUDY.grids if g.ref_converged}),
