# The reproducibility study (make reproducibility): the Table-1 grid three
# times, one run after another (studies.yaml sequential: true): run a
# (Table 1's own renders), run b, run busy (a busy loop beside every
# render), each analysed by rules/grid.smk, then how far the runs' paired
# results lie apart (analysis/reproducibility.py).
include: "grid.smk"

RUNS = {g.name: g for g in STUDY.grids}
A, B = RUNS["a"], RUNS["b"]
BUSY = RUNS.get("busy")


rule reproducibility:
    input:
        [g.files[f] + ".md" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
    params:
        cmd=lambda wc: shell_words([STUDY.python, "-m", "experiments.analysis.reproducibility",
            "--table-a", A.files["table"] + ".csv", "--table-b", B.files["table"] + ".csv",
            "--runs-a", A.files["runs_csv"], "--runs-b", B.files["runs_csv"]]
            + (["--table-busy", BUSY.files["table"] + ".csv", "--runs-busy", BUSY.files["runs_csv"]] if BUSY else [])
            + ["--goal-pp", STUDY.knobs["REPRO_GOAL_PP"], "--max-pp", STUDY.knobs["REPRO_MAX_PP"],
            "--busy-goal-pp", STUDY.knobs["REPRO_BUSY_GOAL_PP"], "--drift", STUDY.knobs["REPRO_DRIFT"],
            "--gauge", STUDY.knobs["TIME_GAUGE"],
            "--ref", A.ref, "--equal-error-a", A.files["equal_error"] + ".csv",
            "--out", STUDY.files["out"]]),
    shell:
        "{params.cmd}"
