# The final-gathering study (make gather; issue 37, items 7-9): per case (a
# scene at a size) one grid per N of GATHERS (studies.yaml gather: both
# methods with --gather N, a run root tagged gatherN, the conventional
# renders of the heaviest cells run once), analysed by rules/grid.smk, each
# against the converged reference of its case (rules/reference.smk), then
# the report over every grid (analysis/gather.py, told each case's reference
# for its own error), with the runs of the map
# seen directly on the same scene and size where the scenes study has them
# (studies.yaml related: direct).
include: "grid.smk"

localrules: gather

K = STUDY.knobs
DIRECT = STUDY.related("direct")


def gather_cmd():
    words = [STUDY.python, "-m", "experiments.analysis.gather"]
    for g in STUDY.grids:
        words += ["--grid", g.scene, g.size, g.knobs["GATHER"], g.files["runs_csv"]]
    for scene, size, ref in dict.fromkeys((g.scene, g.size, g.ref) for g in STUDY.grids):
        words += ["--ref", scene, size, ref]
    for d in DIRECT.grids:
        words += ["--direct", d.scene, d.size, d.files["runs_csv"]]
    return shell_words(words + ["--time", K["TIME"], "--out", STUDY.files["out"], "--figure", STUDY.files["figure"],
                                "--bootstrap", K["BOOTSTRAP"], "--bootstrap-seed", K["BOOTSTRAP_SEED"], "--pm", STUDY.pm])


rule gather:
    input:
        [g.files["runs_csv"] for g in STUDY.grids],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
        STUDY.files["figure"],
    params:
        cmd=lambda wc: gather_cmd(),
    shell:
        "{params.cmd}"
