#!/usr/bin/env bash
# measure-pbrt.sh: re-runs every pbrt measurement quoted in reference/README.md
# ("A third reference: pbrt-v3") from the committed pbrt EXRs:
#  1. the export checked by direct light alone (needs pbrt: PBRT=/path/to/pbrt,
#     else skipped and said so): pbrt `directlighting` at the renderer's fixed
#     2x2 subpixel points against `render --direct shadow-rays --photons 0`,
#     the per-pixel ratio's median and spread;
#  2. the converged photonmap renders (PM_PHOTONS photons, n = PM_NN,
#     --bias-correction, --direct shadow-rays, seeds 1..PM_SEEDS; and the same
#     at half the photons, for the kernel bias) in
#     build/reference/pbrt-measure/, then reference/pbrt/agreement.py's
#     region table, written to reference/pbrt/agreement.md and spliced into
#     reference/README.md between its two agreement markers, and its rows
#     as numbers to reference/pbrt/agreement.csv (a first comment line gives
#     the converged renders' settings), which `make findings` reads.
# Heavy: nice'd, one render at a time. Exit 1 when a step fails.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-/usr/bin/python3}
PM_PHOTONS=${PM_PHOTONS:-2000000} PM_NN=${PM_NN:-200} PM_SEEDS=${PM_SEEDS:-4}
out=build/reference/pbrt-measure; mkdir -p "$out"
make -s build/photonmap
pbrt=${PBRT:-$(command -v pbrt || true)}
if [ -n "$pbrt" ] && [ -x "$pbrt" ]; then
  build/photonmap export-pbrt scenes/cornell.scene --width 256 --height 192 --integrator directlighting \
    --bounces 31 --spp 4 --fixed-subpixels -o "$out/cornell-direct.pbrt"
  nice -n 5 "$pbrt" --nthreads 2 --quiet --outfile "$out/cornell-direct-pbrt.exr" "$out/cornell-direct.pbrt"
  nice -n 5 build/photonmap render scenes/cornell.scene --direct shadow-rays --photons 0 --width 256 --height 192 \
    --quiet -o "$out/cornell-direct-pm.exr"
  "$PY" - "$out/cornell-direct-pbrt.exr" "$out/cornell-direct-pm.exr" > "$out/direct.txt" <<'PYEOF'
import sys
import numpy as np
sys.path.insert(0, "reference/pbrt")
from agreement import read_exr
a, b = read_exr(sys.argv[1]), read_exr(sys.argv[2])
m = (a > 1e-3) & (b > 1e-3)
r = a[m] / b[m]
q = np.percentile(r, [1, 99])
print(f"direct light, cornell 256x192, 2x2 fixed points: pbrt / photonmap per pixel and channel over "
      f"{m.sum()} lit values: median {np.median(r):.6f}, 1st-99th percentile [{q[0]:.5f}, {q[1]:.5f}], "
      f"{(np.abs(r - 1) < 1e-3).mean() * 100:.2f}% within 1e-3 (half-float rounding); image-mean ratio "
      f"{a.mean() / b.mean():.6f}")
PYEOF
else
  # without pbrt the last measured line stands, said to be carried over
  last=$(grep -m1 '^direct light, ' reference/pbrt/agreement.md 2> /dev/null | sed 's/\.$//; s/ (carried over.*$//' || true)
  if [ -n "$last" ]; then
    echo "$last (carried over from the last run with pbrt: pbrt not found here, set PBRT=...)" > "$out/direct.txt"
  else
    echo "direct-light check skipped: pbrt not found (set PBRT=...)" > "$out/direct.txt"
  fi
fi
specs=()
for s in cornell:256:192:reference/cornell/cornell-reference-256x192.exr \
         tworooms:128:96:reference/tworooms/tworooms-reference-128x96.exr \
         caustic:128:96:reference/caustic/caustic-reference-128x96.exr \
         slabs:128:96:reference/slabs/slabs-reference-128x96.exr \
         library:128:96:reference/library/library-reference-128x96.exr; do
  IFS=: read -r scene w h pov <<< "$s"
  ls reference/$scene/$scene-pbrt-bdpt-256x192-seed*.exr > /dev/null 2>&1 || continue
  # the converged renders, and the same at half the photons (kernel bias)
  for p in $PM_PHOTONS $((PM_PHOTONS / 2)); do
    d=$out/$scene-pm$p-nn$PM_NN-${w}x${h}; mkdir -p "$d"
    for seed in $(seq 1 "$PM_SEEDS"); do
      f=$d/seed$seed.exr
      [ -f "$f" ] && continue
      nice -n 5 build/photonmap render scenes/$scene.scene --photons "$p" --nn "$PM_NN" --bias-correction \
        --direct shadow-rays --width "$w" --height "$h" --seed "$seed" --quiet -o "$d/tmp.exr"
      mv "$d/tmp.exr" "$f"
    done
  done
  specs+=("$scene:$w:$h:$pov:$out/$scene-pm$PM_PHOTONS-nn$PM_NN-${w}x${h}:$out/$scene-pm$((PM_PHOTONS / 2))-nn$PM_NN-${w}x${h}")
done
"$PY" reference/pbrt/agreement.py "$out/agreement.md" "${specs[@]}"
{ echo "<!-- pbrt-agreement begin: written by reference/measure-pbrt.sh -->"
  echo
  echo "$(cat "$out/direct.txt")."
  echo
  echo "Converged photonmap: $PM_PHOTONS photons, n = $PM_NN, \`--bias-correction\`, \`--direct shadow-rays\`, seeds 1-$PM_SEEDS."
  cat "$out/agreement.md"
  echo
  echo "<!-- pbrt-agreement end -->"; } > "$out/section.md"
cp "$out/section.md" reference/pbrt/agreement.md.tmp && mv reference/pbrt/agreement.md.tmp reference/pbrt/agreement.md
{ echo "# converged photonmap: $PM_PHOTONS photons (kernel bias from $((PM_PHOTONS / 2))), n = $PM_NN, --bias-correction, --direct shadow-rays, seeds 1-$PM_SEEDS; pbrt-v3: reference/SCENE/SCENE-pbrt-bdpt-256x192-seed*.exr; ratios to pbrt's mean, intervals 95% (reference/pbrt/agreement.py)"
  cat "$out/agreement.csv"; } > reference/pbrt/agreement.csv.tmp
mv reference/pbrt/agreement.csv.tmp reference/pbrt/agreement.csv
"$PY" - reference/README.md "$out/section.md" <<'PYEOF'
import os, re, sys
readme, section = sys.argv[1], open(sys.argv[2]).read().rstrip("\n")
text = open(readme).read()
pat = re.compile(r"<!-- pbrt-agreement begin.*?<!-- pbrt-agreement end -->", re.S)
if not pat.search(text):
    raise SystemExit("measure-pbrt.sh: reference/README.md has no pbrt-agreement markers")
text = pat.sub(lambda _: section, text)
open(readme + ".tmp", "w").write(text)
os.replace(readme + ".tmp", readme)
PYEOF
echo "wrote reference/pbrt/agreement.md, agreement.csv and the section of reference/README.md"
