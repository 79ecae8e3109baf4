# The figures of the paper's grid (make figures): Figure 2's render (the
# study's one render, rules/render.smk, with --dump-reps) and the PNGs of
# analysis/figures.py drawn from it and from Table 1's files (the study
# table1 with the same knobs; they are read, not made: `make
# reproduce-table` first).
from experiments import studies as studymod
from experiments.studies import shell_words

F = STUDY.files
K = STUDY.knobs
T1 = studymod.load("table1", {k: v for k, v in config.items() if k != "STUDY"}).files
FIG2_RUN = STUDY.run_files[0][:-len(".run.json")]

localrules: figures

rule figures:
    input:
        STUDY.run_files,
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.figures", "--table", T1["table"] + ".csv",
            "--runs", T1["runs_csv"], "--cells-csv", T1["cells_csv"], "--ref", K["FIG_REF"],
            "--cells", K["FIG3_CELLS"], "--paper-cells", K["FIG3_PAPER_CELLS"], "--seed", K["FIG_SEED"],
            "--crop", K["FIG3_CROP"], "--crop-at", K["FIG3_CROP_AT"], "--error-block", K["FIG_ERROR_BLOCK"],
            "--time", K["TIME"], "--fig2-run", FIG2_RUN, "--fig2-plane", K["FIG2_PLANE"],
            "--fig2-window", K["FIG2_WINDOW"], "--scene", STUDY.scene, "--pm", STUDY.pm,
            "--rep-study-cells", F["rep_study_cells"], "--equal-error", T1["equal_error"] + ".csv",
            "--glance-cell", K["GLANCE_CELL"], "--out", STUDY.figures]),
    shell:
        "{params.cmd}"
