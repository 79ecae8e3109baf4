# scenes.settings.sh: the render settings, block sizes and negative controls
# of tests/scenes.test.sh, shared with reference/measure-scenes.sh, which
# measures the numbers that set the thresholds (reference/README.md, "More
# scenes"). Sourced, not run.

# direct light only, per pixel, as for cornell (tests/povray.test.sh)
DIRECT=(--direct shadow-rays --photons 0 --width 129 --height 96 --subpixels 3 --quiet)
DIRECT_REL=1e-3      # two half-float rounding steps
DIRECT_MAXBAD=0.002  # share of pixels allowed beyond it (measured at most 0.10%)

# slabs.scene: 2M photons (at 500k the thin-geometry bias of both estimates
# alone reaches p99 0.2-0.28: reference/README.md), 8x8-pixel blocks
SLABS=(--photons 2000000 --nn 100 --width 128 --height 96 --threads 2)
SLABS_BLOCKS=(16 12)
SLABS_GREEN_WALL='s/^material red   lambert rho 0.63 0.065 0.05/material red   lambert rho 0.065 0.63 0.05/'
SLABS_NO_BLINDS='^rect corner -\?0\.45 '   # grep -v: the 20 slats' 120 rectangles

# tworooms.scene: 2 bounces (--photon-depth 3) against POV-Ray's 2 bounces;
# 2M photons, 16x16-pixel blocks (the camera room is lit by few photons)
TWOROOMS=(--photons 2000000 --nn 100 --photon-depth 3 --width 128 --height 96 --threads 2)
TWOROOMS_BLOCKS=(8 6)
TWOROOMS_WHITE_WALL='s/material orange  # far wall/material white   # far wall/'

# library.scene: 500k photons, 16x16-pixel blocks
LIBRARY=(--photons 500000 --nn 100 --width 128 --height 96 --threads 2)
LIBRARY_BLOCKS=(8 6)
LIBRARY_GREY_BOOKS='s/^material book\([0-9]\) lambert rho .*/material book\1 lambert rho 0.4 0.4 0.4/'
