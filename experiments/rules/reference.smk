# Our converged reference of a scene at a size (studies.yaml: reference:
# converged, or pov_or_converged where reference/ has no POV-Ray render):
# method-neutral, its own error measured (experiments/analysis/reference.py):
# the corrected estimate with direct light by CONV_REF_DIRECT at
# CONV_REF_PHOTONS photons (empty: CONV_REF_FACTOR x the study's largest
# P_e), n = CONV_REF_NN, the mean of the seeds CONV_REF_SEEDS (none a seed of
# a grid it judges: studies.py refuses it before any render), each rendered
# again at half the photons (its kernel bias); WxH.json beside WxH.exr holds
# noise, bias and the settings. Its path is layout.converged_ref
# (analysis/runs.py); a study asks for one with STUDY.converged_ref(scene, size).
from experiments.analysis import runs as layout
from experiments.studies import shell_words

# the path of layout.converged_ref with each setting a wildcard
CONVREF = layout.converged_ref(STUDY.results, "{name}", "{width}x{height}", "{photons}", "{nn}", "{direct}",
                               "{subpixels}", "{seeds}")


def convref_cmd(wc, output):
    words = [STUDY.python, "-m", "experiments.analysis.reference", "build", "--pm", STUDY.pm,
        "--scene", STUDY.ref_scenes[wc.name], "--width", wc.width, "--height", wc.height,
        "--subpixels", wc.subpixels, "--photons", wc.photons, "--nn", wc.nn, "--direct", wc.direct,
        "--seeds", wc.seeds.replace("_", " "), "--grid-seeds", " ".join(map(str, sorted(STUDY.ref_seeds))),
        "--dir", os.path.join(os.path.dirname(output[0]), f"{wc.width}x{wc.height}"), "--out", output[0]]
    return shell_words(words)


rule converged_reference:
    input:
        lambda wc: STUDY.ref_scenes[wc.name],
    output:
        CONVREF,
    wildcard_constraints:
        name="|".join(re.escape(n) for n in STUDY.ref_scenes) or NONE,
        width="[0-9]+",
        height="[0-9]+",
        photons="[0-9.e+]+",
        nn="[0-9]+",
        direct="shadow-rays|photons",
        subpixels="[0-9]+",
        seeds="[0-9_]+",
    resources:
        timed=STUDY.timed,  # all cores: never beside a timed render
    params:
        cmd=convref_cmd,
        msg=lambda wc: (f"reference: {STUDY.ref_scenes[wc.name]} at {wc.width}x{wc.height}, conventional, corrected, "
                        f"--direct {wc.direct}, P_e={wc.photons} n={wc.nn}, seeds {wc.seeds.replace('_', ' ')}, all cores"),
    shell:
        "echo {params.msg:q} && {params.cmd}"
