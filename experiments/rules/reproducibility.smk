# The reproducibility study (make reproducibility): the Table-1 grid twice,
# runs A and B, their renders interleaved (rules/render.smk, rule
# interleave), each analysed by rules/grid.smk, then how far the two runs'
# paired results lie apart (analysis/reproducibility.py).
include: "grid.smk"

A, B = STUDY.grids


rule reproducibility:
    input:
        [g.files[f] + ".md" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
    params:
        cmd=lambda wc: shell_words([STUDY.python, "-m", "experiments.analysis.reproducibility",
            "--table-a", A.files["table"] + ".csv", "--table-b", B.files["table"] + ".csv",
            "--runs-a", A.files["runs_csv"], "--runs-b", B.files["runs_csv"], "--goal-pp", STUDY.knobs["REPRO_GOAL_PP"],
            "--taskset", STUDY.taskset, "--ref", A.ref, "--equal-error-a", A.files["equal_error"] + ".csv",
            "--out", STUDY.files["out"]]),
    shell:
        "{params.cmd}"
