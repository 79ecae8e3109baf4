# The resolution study (make resolution): the grid at every size of
# RES_SIZES, analysed per size by rules/grid.smk, then the cheapest settings
# per relMSE target at each size (analysis/resolution.py).
include: "grid.smk"

K = STUDY.knobs


def ref_desc(g):
    """The reference of grid G as the report names it."""
    if not g.ref_converged:
        return f"POV-Ray `{g.ref}`"
    why = ("no POV-Ray reference of this size in reference/" if K["RES_REF"] == "pov"
           else "RES_REF=ours: one kind of reference at every size")
    return (f"ours: corrected, --direct {K['CONV_REF_DIRECT']}, P_e={STUDY.conv_ref_photons()}, n={K['CONV_REF_NN']}, "
            f"mean of seeds {K['CONV_REF_SEEDS']} (no grid render uses them), same scene and settings, `{g.ref}` ({why})")


def resolution_cmd():
    g0 = STUDY.grids[0]
    words = [STUDY.python, "-m", "experiments.analysis.resolution"]
    for g in STUDY.grids:
        words += ["--size", g.size, g.files["table"] + ".csv", ref_desc(g)]
    for g in STUDY.grids:
        words += ["--ref-exr", g.size, g.ref, g.files["equal_error"] + ".csv"]
    grid = (f"P_e in {{{K['PHOTONS']}}} x n in {{{K['NNS']}}} x {{{K['METHODS']}}} x estimates {{{K['ESTIMATES']}}}, "
            f"seeds 1..{K['SEEDS']}, threads: {K['THREADS'] or 'all'}")
    return shell_words(words + ["--targets", K["RES_TARGETS"], "--time", K["TIME"], "--grid", grid,
                                "--out", STUDY.files["out"] + ".md"])


rule resolution:
    input:
        [g.files[f] + ".csv" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
    params:
        cmd=lambda wc: resolution_cmd(),
    shell:
        "{params.cmd}"
