# The study beyond the paper's rule (make beyond): per case the grid of both
# methods (block paper) and one grid per variant (block variant), analysed by
# rules/grid.smk, their renders grouped per (cell, seed) (rules/render.smk,
# rule group), then every variant against the paper's rule at equal error
# (analysis/beyond.py).
include: "grid.smk"

K = STUDY.knobs
BASES, VARIANTS = STUDY.blocks[0][2], STUDY.blocks[1][2]


def beyond_cmd():
    words = [STUDY.python, "-m", "experiments.analysis.beyond"]
    for b in BASES:
        words += ["--case", b.name, os.path.splitext(os.path.basename(b.scene))[0], b.size, b.ref,
                  "--variant", b.name, "paper", "", b.files["runs_csv"]]
        for v in (v for v in VARIANTS if v.conv_root == b.root):
            words += ["--variant", b.name, v.name[len(b.name) + 1:], v.pm_args, v.files["runs_csv"]]
    settings = (f'make beyond SIZE={K["SIZE"]} SEEDS={K["SEEDS"]} PHOTONS="{K["PHOTONS"]}" NNS="{K["NNS"]}" '
                f'ESTIMATES="{K["ESTIMATES"]}" BEYOND_SIZES="{K["BEYOND_SIZES"]}" BEYOND_TAUS="{K["BEYOND_TAUS"]}" '
                f'BEYOND_GATE={K["BEYOND_GATE"]} CONV_REF_PHOTONS={K["CONV_REF_PHOTONS"]} '
                f'CONV_REF_FACTOR={K["CONV_REF_FACTOR"]} CONV_REF_NN={K["CONV_REF_NN"]} '
                f'CONV_REF_SEEDS="{K["CONV_REF_SEEDS"]}" THREADS={K["THREADS"]} TIME={K["TIME"]} BOOTSTRAP={K["BOOTSTRAP"]}')
    return shell_words(words + ["--time", K["TIME"], "--bootstrap", K["BOOTSTRAP"], "--bootstrap-seed", K["BOOTSTRAP_SEED"],
                                "--pm", STUDY.pm, "--gate", K["BEYOND_GATE"], "--settings", settings,
                                "--out", STUDY.files["out"], "--figure", STUDY.files["figure"]])


rule beyond:
    input:
        [g.files[f] + ".md" for g in STUDY.grids for f in ("table", "equal_error")],
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
        STUDY.files["figure"],
    params:
        cmd=lambda wc: beyond_cmd(),
    shell:
        "{params.cmd}"
