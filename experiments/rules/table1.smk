# Table 1 (make reproduce-table): the renders -> runs.csv and cells.csv
# (analysis/collect.py) -> table1.{md,csv} (analysis/table.py) and
# equal-error.{md,csv,png} (analysis/equal_error.py).
from experiments.studies import shell_words

F = STUDY.files
TIMEARGS = ["--bootstrap", STUDY.knobs["BOOTSTRAP"], "--bootstrap-seed", STUDY.knobs["BOOTSTRAP_SEED"]]

def table1_renders(wildcards):
    """The study's renders; a study without a reference stops here, before any render."""
    STUDY.check_reference()
    return STUDY.run_files


rule table1_collect:
    input:
        table1_renders,
    output:
        runs=F["runs_csv"],
        cells=F["cells_csv"],
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.collect", "--runroot", STUDY.root,
            "--conv-runroot", STUDY.conv_root, "--scene", STUDY.scene, "--width", STUDY.width,
            "--height", STUDY.height, "--subpixels", STUDY.subpixels, "--threads", STUDY.threads_arg,
            "--tag", STUDY.tag, "--methods", " ".join(STUDY.methods), "--estimates", " ".join(STUDY.estimates),
            "--photons", " ".join(STUDY.photons), "--nns", " ".join(STUDY.nns),
            "--seeds", " ".join(map(str, STUDY.seeds)), "--ref", STUDY.ref, "--ref-fast", STUDY.ref_fast,
            "--runs-csv", F["runs_csv"], "--cells-csv", F["cells_csv"]]),
    shell:
        "{params.cmd}"

rule table1_table:
    input:
        runs=F["runs_csv"],
        cells=F["cells_csv"],
    output:
        F["table"] + ".md",
        F["table"] + ".csv",
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.table", "--runs-csv", F["runs_csv"],
            "--cells-csv", F["cells_csv"], "--paper", "experiments/paper-table1.csv", "--out", F["table"],
            "--equal-error", F["equal_error"] + ".md", "--pm", STUDY.pm, "--pm-args", STUDY.pm_args,
            "--runroot", STUDY.root] + TIMEARGS),
    shell:
        "{params.cmd}"

rule table1_equal_error:
    input:
        runs=F["runs_csv"],
    output:
        F["equal_error"] + ".md",
        F["equal_error"] + ".csv",
    params:
        cmd=shell_words([STUDY.python, "-m", "experiments.analysis.equal_error", "--runs-csv", F["runs_csv"],
            "--out", F["equal_error"], "--targets", STUDY.knobs["EE_TARGETS"], "--time", STUDY.knobs["TIME"]]
            + TIMEARGS + ["--pm", STUDY.pm]),
    shell:
        "{params.cmd}"

# the report
rule table1:
    input:
        F["table"] + ".md",
        F["equal_error"] + ".md",
