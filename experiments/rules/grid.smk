# The analysis of a grid study (Table 1 and its variants): the renders ->
# runs.csv and cells.csv (analysis/collect.py) -> the table .{md,csv}
# (analysis/table.py) and the speed-up at equal error .{md,csv,png}
# (analysis/equal_error.py); the files are the study's (studies.yaml:
# runs_csv, cells_csv, table, equal_error).
from experiments.studies import shell_words

F = STUDY.files

# with CLUSTER=slurm the renders go to the cluster; the analysis stays here
localrules: collect, table, equal_error
TIMEARGS = ["--bootstrap", STUDY.knobs["BOOTSTRAP"], "--bootstrap-seed", STUDY.knobs["BOOTSTRAP_SEED"]]

def grid_renders(wildcards):
    """The study's renders; a study without a reference stops here, before any render."""
    STUDY.check_reference()
    return STUDY.run_files


rule collect:
    input:
        grid_renders,
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

rule table:
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

rule equal_error:
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
