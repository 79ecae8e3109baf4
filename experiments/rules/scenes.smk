# The cross-scene study (make scenes): the grid on every scene of SCENES,
# analysed per scene by rules/grid.smk, each against our converged
# reference of it (rules/reference.smk), then the per-scene summary and its
# figure (analysis/scenes.py).
include: "grid.smk"

K = STUDY.knobs


def scenes_cmd():
    words = [STUDY.python, "-m", "experiments.analysis.scenes"]
    for g in STUDY.grids:
        words += ["--scene", g.scene, g.files["table"] + ".csv", g.files["runs_csv"], g.files["equal_error"] + ".csv", g.ref]
    grid = (f"P_e in {{{K['PHOTONS']}}} x n in {{{K['NNS']}}} x {{{K['METHODS']}}} x estimates {{{K['ESTIMATES']}}}, "
            f"seeds 1..{K['SEEDS']}, threads: {K['THREADS'] or 'all'}")
    return shell_words(words + ["--cell", K["SCENES_CELL"], "--size", K["SIZE"], "--ref-photons", STUDY.conv_ref_photons(),
                                "--ref-nn", K["CONV_REF_NN"], "--ref-seed", K["CONV_REF_SEEDS"], "--grid", grid,
                                "--figures", STUDY.figures, "--out", STUDY.files["out"]])


rule scenes:
    input:
        [g.files[f] for g in STUDY.grids for f in ("runs_csv",)]
        + [g.files[f] + ".csv" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
        STUDY.files["figure"],
    params:
        cmd=lambda wc: scenes_cmd(),
    shell:
        "{params.cmd}"
