# The analysis of a grid study (Table 1 and its variants), once per grid of
# the study (the wildcard {grid} of its files; a block of one grid has none):
# the renders -> runs.csv and cells.csv (analysis/collect.py) -> the table
# .{md,csv} (analysis/table.py) and the speed-up at equal error .{md,csv,png}
# (analysis/equal_error.py); the files are the study's (studies.yaml:
# runs_csv, cells_csv, table, equal_error).
from experiments.studies import shell_words

F = STUDY.files

TIMEARGS = ["--bootstrap", STUDY.knobs["BOOTSTRAP"], "--bootstrap-seed", STUDY.knobs["BOOTSTRAP_SEED"]]

if any(len(grids) > 1 for _, _, grids in STUDY.blocks):
    wildcard_constraints:
        grid="|".join(re.escape(g.name) for g in STUDY.grids),


def grid_renders(block):
    """The input function of a block's collect: the grid's renders, the
    conventional renders it is compared with and its reference when it is
    ours; a grid without a reference stops here, before any render."""
    def renders(wildcards):
        g = STUDY.grid(wildcards, block)
        g.check_reference()
        return g.run_files + g.conv_files + ([g.ref] if g.ref_converged else [])
    return renders


def collect_cmd(block):
    def cmd(wildcards):
        g = STUDY.grid(wildcards, block)
        return shell_words([g.python, "-m", "experiments.analysis.collect", "--runroot", g.root,
            "--conv-runroot", g.conv_root, "--scene", g.scene, "--width", g.width,
            "--height", g.height, "--subpixels", g.subpixels, "--threads", g.threads_arg,
            "--tag", g.tag, "--methods", " ".join(g.methods), "--estimates", " ".join(g.estimates),
            "--photons", " ".join(g.photons), "--nns", " ".join(g.nns),
            "--seeds", " ".join(map(str, g.seeds)), "--ref", g.ref, "--ref-fast", g.ref_fast,
            "--runs-csv", g.files["runs_csv"], "--cells-csv", g.files["cells_csv"]])
    return cmd


def table_cmd(block):
    def cmd(wildcards):
        g = STUDY.grid(wildcards, block)
        return shell_words([g.python, "-m", "experiments.analysis.table", "--runs-csv", g.files["runs_csv"],
            "--cells-csv", g.files["cells_csv"], "--paper", "experiments/paper-table1.csv", "--out", g.files["table"],
            "--equal-error", g.files["equal_error"] + ".md", "--pm", g.pm, "--pm-args", g.pm_args,
            "--runroot", g.root] + TIMEARGS)
    return cmd


def equal_error_cmd(block):
    def cmd(wildcards):
        g = STUDY.grid(wildcards, block)
        return shell_words([g.python, "-m", "experiments.analysis.equal_error", "--runs-csv", g.files["runs_csv"],
            "--out", g.files["equal_error"], "--targets", STUDY.knobs["EE_TARGETS"], "--time", STUDY.knobs["TIME"]]
            + TIMEARGS + ["--pm", g.pm])
    return cmd


# one set of the three rules per block of grids (its files' pattern): the
# first block's rules are collect, table and equal_error, the block NAME's
# collect_NAME, table_NAME and equal_error_NAME
for BLOCK, (BNAME, BF, _) in enumerate(STUDY.blocks):
    SFX = f"_{BNAME}" if BLOCK else ""

    # with CLUSTER=slurm the renders go to the cluster; the analysis stays
    # here (the localrules directive, for names made here)
    workflow.localrules("collect" + SFX, "table" + SFX, "equal_error" + SFX)

    rule:
        name: "collect" + SFX
        input:
            grid_renders(BLOCK),
        output:
            runs=BF["runs_csv"],
            cells=BF["cells_csv"],
        params:
            cmd=collect_cmd(BLOCK),
        shell:
            "{params.cmd}"

    rule:
        name: "table" + SFX
        input:
            runs=BF["runs_csv"],
            cells=BF["cells_csv"],
        output:
            BF["table"] + ".md",
            BF["table"] + ".csv",
        params:
            cmd=table_cmd(BLOCK),
        shell:
            "{params.cmd}"

    rule:
        name: "equal_error" + SFX
        input:
            runs=BF["runs_csv"],
        output:
            BF["equal_error"] + ".md",
            BF["equal_error"] + ".csv",
        params:
            cmd=equal_error_cmd(BLOCK),
        shell:
            "{params.cmd}"
