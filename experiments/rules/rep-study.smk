# The representative-rule study (make rep-study): Table 1's grid and one
# variant grid per rule of REP_RULES, each analysed by rules/grid.smk (the
# variants by its rules of the block rep), then the rules' slopes against
# the paper's (analysis/repstudy.py).
include: "grid.smk"

K = STUDY.knobs
BASE, VARIANTS = STUDY.blocks[0][2][0], STUDY.blocks[1][2]


rule rep_study:
    input:
        [g.files[f] + ".md" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
        STUDY.files["out"] + "-cells.csv",
        STUDY.files["out"] + "-rules.csv",
        STUDY.files["figure"],
    params:
        cmd=lambda wc: shell_words([STUDY.python, "-m", "experiments.analysis.repstudy", "--base-runs", BASE.files["runs_csv"]]
            + [w for g in VARIANTS for w in ("--variant", f"{g.name}={g.files['runs_csv']}")]
            + ["--paper", "experiments/paper-table1.csv", "--time", K["TIME"], "--out", STUDY.files["out"],
               "--figure", STUDY.files["figure"], "--bootstrap", K["BOOTSTRAP"], "--bootstrap-seed", K["BOOTSTRAP_SEED"]]),
    shell:
        "{params.cmd}"
