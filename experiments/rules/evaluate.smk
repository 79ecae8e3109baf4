# make evaluate SCENE=my.scene: does the precomputed method pay on one scene?
# Five stages, one progress line each ("evaluate: [k/5] ..."), every file
# under OUT (studies.yaml, evaluate):
#   1 pilot      OUT/pilot/pilot.json: one render at the grid's middle P_e
#                and n; stops (exit 2) where a study would be meaningless
#                (analysis/evaluate.py pilot)
#   2 POV-Ray    OUT/pov/{reference,fast}.exr by the committed references'
#                rule (evaluate-pov.sh: 2W x 2H, 2x2 box), the rectangle
#                thickness from the geometry (OUT/pov/thickness.json) or the
#                scene refused; cached in EVAL_CACHE by the exported SDL's hash
#   3 reference  our converged reference (analysis/reference.py; CONV_REF_*)
#                in OUT/reference/KEY-pP-nN-DIRECT-seedsS/WxH.exr, checked
#                against POV-Ray (OUT/crosscheck.json), at 2 bounces where the
#                full-bounce check fails
#   4 grid       both methods (block grid), EVAL_VARIANTS (block variant) and
#                final gathering, both methods with --gather N for each N of
#                EVAL_GATHERS (block gather), analysed by rules/grid.smk; no
#                render before the check of 3; then final gathering against
#                the map seen directly (analysis/gather.py: OUT/gather/gather.
#                {md,csv,png}, the equal-error speed-up and the best
#                configuration per relMSE target over every mode)
#   5 report     OUT/report.md and its images
# `make evaluate-references`: stages 1-3 only (rule evaluate_references).
import sys

from experiments import studies as studymod
from experiments.studies import shell_words

K = STUDY.knobs
OUT = STUDY.out
SCENE, POV_SCENE = K["SCENE"], K["EVAL_POV_SCENE"] or K["SCENE"]
G = STUDY.by_name["grid"]
KEY = studymod.scene_key(SCENE)
SIZE, W, H = G.size, G.width, G.height


def mid(words):
    """The middle of the numbers WORDS (the lower of the two middles)."""
    w = sorted(words, key=float)
    return w[(len(w) + 1) // 2 - 1]


P_MID, N_MID = mid(G.photons), mid(G.nns)
REF_P = STUDY.conv_ref_photons()
REF_SEEDS = K["CONV_REF_SEEDS"].split()
_both = sorted(set(G.seeds) & {int(s) for s in REF_SEEDS if s.isdigit()})
if _both:
    print(f"evaluate: CONV_REF_SEEDS={K['CONV_REF_SEEDS']}: seed(s) {_both} are the grid's: the reference would "
          "share photon paths with the renders it judges", file=sys.stderr)
    sys.exit(1)
REF_DIR = f"{OUT}/reference/{KEY}-p{REF_P}-n{K['CONV_REF_NN']}-{K['CONV_REF_DIRECT']}-seeds{'_'.join(REF_SEEDS)}"
EREF, EREF_B2 = f"{REF_DIR}/{SIZE}.exr", f"{REF_DIR}/b2-{SIZE}.exr"
for _g in STUDY.grids:  # every grid against our reference, made below
    _g.ref, _g.ref_fast, _g.ref_converged = EREF, "", True
CROSSCHECK = f"{OUT}/crosscheck.json"
STUDY.render_after = [CROSSCHECK]  # the grid renders only after the references are checked
PY = K["PYTHON"]
POV = ["env", f"PM={STUDY.pm}", "bash", "experiments/evaluate-pov.sh", POV_SCENE, W, H, K["EVAL_CACHE"]]
THICK = "$(" + shell_words([PY, "-c", 'import json, sys; print(json.load(open(sys.argv[1]))["rect_thickness"])',
                            OUT + "/pov/thickness.json"]) + ")"
REF_BUILD = [PY, "-m", "experiments.analysis.reference", "build", "--pm", STUDY.pm, "--scene", SCENE, "--width", W,
             "--height", H, "--subpixels", 2, "--photons", REF_P, "--nn", K["CONV_REF_NN"], "--direct",
             K["CONV_REF_DIRECT"], "--seeds", K["CONV_REF_SEEDS"], "--grid-seeds", " ".join(map(str, G.seeds))]
NO_SEED_LINES = "grep -v '^reference: .* seed '"
VARIANTS = [g for name, _, grids in STUDY.blocks if name == "variant" for g in grids]
GATHERS = [g for name, _, grids in STUDY.blocks if name == "gather" for g in grids]
NRENDERS = len(STUDY.run_files)

include: "grid.smk"

localrules: evaluate, evaluate_references, eval_report, eval_crosscheck, eval_thickness, eval_gather

wildcard_constraints:
    preset="reference|fast",


rule eval_pilot:
    input:
        SCENE,
    output:
        f"{OUT}/pilot/pilot.json",
    params:
        msg=f"evaluate: [1/5] pilot: {SCENE} at {SIZE}, P_e={P_MID} n={N_MID}",
        cmd=shell_words([PY, "-m", "experiments.analysis.evaluate", "pilot", "--pm", STUDY.pm, "--scene", SCENE,
                         "--size", SIZE, "--photons", P_MID, "--nn", N_MID, "--out", f"{OUT}/pilot/"]),
    shell:
        "echo {params.msg:q} && {params.cmd}"


rule eval_thickness:
    input:
        POV_SCENE,
        f"{OUT}/pilot/pilot.json",
    output:
        f"{OUT}/pov/thickness.json",
    params:
        msg=f"evaluate: [2/5] POV-Ray references of {POV_SCENE} at {SIZE} (fast and reference presets)",
        cmd=shell_words([PY, "-m", "experiments.analysis.evaluate", "thickness", "--pm", STUDY.pm, "--scene",
                         POV_SCENE, "--out", f"{OUT}/pov/thickness.json"]),
    shell:
        "echo {params.msg:q} && {params.cmd} > /dev/null"


rule eval_pov:
    input:
        f"{OUT}/pov/thickness.json",
    output:
        f"{OUT}/pov/{{preset}}.exr",
    params:
        cmd=lambda wc, output: shell_words(POV + [output[0], "--quality", wc.preset, "--rect-thickness"]) + " " + THICK,
    shell:
        "{params.cmd}"


rule eval_reference:
    input:
        SCENE,
        f"{OUT}/pilot/pilot.json",
        f"{OUT}/pov/reference.exr",
        f"{OUT}/pov/fast.exr",
    output:
        EREF,
    resources:
        timed=STUDY.timed,  # all cores: never beside a timed render
    params:
        msg=(f"evaluate: [3/5] converged reference: corrected, --direct {K['CONV_REF_DIRECT']}, P_e={REF_P} "
             f"n={K['CONV_REF_NN']}, seeds {K['CONV_REF_SEEDS']}, and each at P_e/2"),
        cmd=shell_words(REF_BUILD + ["--dir", f"{REF_DIR}/{SIZE}", "--out", EREF]),
    shell:
        "echo {params.msg:q} && {params.cmd} | " + NO_SEED_LINES


def crosscheck_cmd():
    cc = [PY, "-m", "experiments.analysis.evaluate", "crosscheck", "--ref", EREF, "--pov-ref",
          f"{OUT}/pov/reference.exr", "--pov-fast", f"{OUT}/pov/fast.exr"]
    full = CROSSCHECK + ".full"
    agree = shell_words([PY, "-c", 'import json, sys; sys.exit(json.load(open(sys.argv[1]))["agree"] != "full")', full])
    b2 = " && ".join([
        "echo " + shell_words(["evaluate: [3/5] full bounces disagree: the bounce-limited comparison (export-pov "
                               "--bounces 2 against --photon-depth 3)"]),
        shell_words(POV + [f"{OUT}/pov/b2-reference.exr", "--quality", "reference", "--bounces", "2",
                           "--rect-thickness"]) + " " + THICK,
        shell_words(REF_BUILD + ["--pm-args", "--photon-depth 3", "--dir", f"{REF_DIR}/b2-{SIZE}", "--out", EREF_B2])
        + " | " + NO_SEED_LINES,
        "rm -f " + shell_words([full]),
        shell_words(cc + ["--b2-ours", EREF_B2, "--b2-pov", f"{OUT}/pov/b2-reference.exr", "--out", CROSSCHECK])
        + " > /dev/null"])
    said = shell_words([PY, "-c", 'import json, sys; d = json.load(open(sys.argv[1])); '
                        'print("evaluate: [3/5] references:", d["sentence"])', CROSSCHECK])
    grid = (f"evaluate: [4/5] grid: {NRENDERS} renders (P_e {{{K['PHOTONS']}}} x n {{{K['NNS']}}} x both methods x "
            f"{{{K['ESTIMATES']}}} x seeds 1..{K['SEEDS']}, variants {{{K['EVAL_VARIANTS']}}}"
            + (f"; final gathering N {{{K['EVAL_GATHERS']}}} x P_e {{{' '.join(GATHERS[0].photons)}}} x n "
               f"{{{' '.join(GATHERS[0].nns)}}} x both methods" if GATHERS else "") + "), paired")
    return (shell_words(cc + ["--out", full]) + " > /dev/null && "
            f"if {agree}; then mv {shell_words([full, CROSSCHECK])}; else {b2}; fi && {said} && echo {shell_words([grid])}")


rule eval_crosscheck:
    input:
        EREF,
        f"{OUT}/pov/reference.exr",
        f"{OUT}/pov/fast.exr",
    output:
        CROSSCHECK,
    params:
        cmd=lambda wc: crosscheck_cmd(),
    shell:
        "{params.cmd}"


def report_cmd():
    settings = (f"Scene `{SCENE}` (content hash {KEY}) at {SIZE}, 2x2 subpixels, threads: {K['THREADS'] or 'all'}; "
                f"grid P_e in {{{K['PHOTONS']}}} x n in {{{K['NNS']}}} x both methods x estimates {{{K['ESTIMATES']}}} "
                f"x seeds 1..{K['SEEDS']}, variants {{{K['EVAL_VARIANTS']}}}"
                + (f"; final gathering (--gather N --direct shadow-rays) N in {{{K['EVAL_GATHERS']}}} x P_e in "
                   f"{{{' '.join(GATHERS[0].photons)}}} x n in {{{' '.join(GATHERS[0].nns)}}} x both methods x "
                   f"estimates {{{' '.join(GATHERS[0].estimates)}}}" if GATHERS else "")
                + f"; time {K['TIME']}; POV-Ray scene "
                f"`{POV_SCENE}`; command: make evaluate SCENE={SCENE} SIZE={SIZE} SEEDS={K['SEEDS']} OUT={OUT}")
    words = [PY, "-m", "experiments.analysis.evaluate", "report", "--scene", SCENE, "--pilot",
             f"{OUT}/pilot/pilot.json", "--thickness", f"{OUT}/pov/thickness.json", "--crosscheck", CROSSCHECK,
             "--ref", EREF, "--runs-csv", G.files["runs_csv"], "--table-csv", G.files["table"] + ".csv",
             "--equal-error-csv", G.files["equal_error"] + ".csv", "--equal-error-png", G.files["equal_error"] + ".png",
             "--runroot", G.root, "--out", OUT, "--estimates", K["ESTIMATES"], "--time", K["TIME"]]
    for v in VARIANTS:
        words += ["--variant", f"{v.name}={v.files['table']}.csv,{v.files['runs_csv']}"]
    if GATHERS:
        words += ["--gather-csv", STUDY.files["gather"] + ".csv"]
    return shell_words(words + ["--settings", settings])


def gather_cmd():
    """analysis/gather.py over the gather grids, with the main grid as the
    map seen directly (the same scene and size)."""
    words = [PY, "-m", "experiments.analysis.gather"]
    for g in GATHERS:
        words += ["--grid", g.scene, g.size, g.knobs["GATHER"], g.files["runs_csv"]]
    for scene, size, ref in dict.fromkeys((g.scene, g.size, g.ref) for g in GATHERS):
        words += ["--ref", scene, size, ref]
    return shell_words(words + ["--direct", G.scene, G.size, G.files["runs_csv"], "--time", K["TIME"], "--out",
                                STUDY.files["gather"], "--figure", STUDY.files["gather_figure"], "--bootstrap",
                                K["BOOTSTRAP"], "--bootstrap-seed", K["BOOTSTRAP_SEED"], "--pm", STUDY.pm])


rule eval_gather:
    input:
        [g.files["runs_csv"] for g in GATHERS],
        G.files["runs_csv"],
    output:
        STUDY.files["gather"] + ".md",
        STUDY.files["gather"] + ".csv",
        STUDY.files["gather_figure"],
    params:
        cmd=lambda wc: gather_cmd(),
    shell:
        "{params.cmd}"


rule eval_report:
    input:
        CROSSCHECK,
        [g.files[f] for g in STUDY.grids for f in ("runs_csv",)],
        [g.files["table"] + ".csv" for g in STUDY.grids],
        G.files["equal_error"] + ".csv",
        [STUDY.files["gather"] + ".csv"] if GATHERS else [],
    output:
        STUDY.files["report"],
    params:
        cmd=lambda wc: report_cmd(),
    shell:
        "{params.cmd}"


rule evaluate:
    input:
        STUDY.files["report"],
    params:
        msg=f"evaluate: done: {STUDY.files['report']}",
    shell:
        "echo {params.msg:q}"


rule evaluate_references:
    input:
        CROSSCHECK,
