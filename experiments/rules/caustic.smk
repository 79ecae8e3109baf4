# The caustic study (make caustic): the grid on the caustic scene, analysed
# by rules/grid.smk, then the error in the caustic window over seeds and its
# figure (analysis/caustic.py).
include: "grid.smk"

rule caustic:
    input:
        F["runs_csv"],
        F["table"] + ".md",
        F["equal_error"] + ".md",
    output:
        F["out"] + ".md",
        F["out"] + ".csv",
        F["figure"],
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.caustic", "--runs", F["runs_csv"], "--ref", STUDY.ref,
            "--window", STUDY.knobs["CAUSTIC_WINDOW"], "--window-at", STUDY.knobs["CAUSTIC_WINDOW_AT"],
            "--cells", STUDY.knobs["FIG3_CELLS"], "--out", F["out"], "--figure", F["figure"]]),
    shell:
        "{params.cmd}"
