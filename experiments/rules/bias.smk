# The estimators' bias on the analytic scene (make estimator-bias): every
# render's mean radiance against the exact 1 (analysis/estimator_bias.py).
from experiments.studies import shell_words

rule bias:
    input:
        STUDY.run_files,
    output:
        STUDY.files["out"] + ".md",
        STUDY.files["out"] + ".csv",
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.estimator_bias", "--dir", STUDY.root,
            "--nns", " ".join(STUDY.nns), "--seeds", len(STUDY.seeds), "--photons", " ".join(STUDY.photons),
            "--size", STUDY.size, "--scene", STUDY.scene, "--out", STUDY.files["out"]]),
    shell:
        "{params.cmd}"
