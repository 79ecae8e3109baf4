#!/usr/bin/env bash
# Installs the Debian 12 packages photonmap needs, only those missing.
# Idempotent; `make` runs it once (stamp: build/.deps-stamp).
set -euo pipefail

PACKAGES=(
  build-essential clang pkg-config
  libopenexr-dev libpng-dev         # EXR via OpenEXR's C API, PNG previews
  openimageio-tools                 # idiff, oiiotool: image diffs and composites
  povray                            # POV-Ray 3.7: the independent reference
  gnuplot-nox                       # plots
  libnanoflann-dev                  # benchmark comparison (C++ header-only)
  libclang-rt-14-dev                # sanitizer and libFuzzer runtimes for clang
  time                              # /usr/bin/time: CPU seconds of every table cell
  valgrind linux-perf python3       # make bench: instruction counts, profile, JSON
  python3-numpy python3-scipy       # statistics of the experiments (CIs, bootstrap, fits)
  python3-pandas python3-matplotlib # tables and figures
  python3-openimageio               # EXR pixels in the analysis (OpenImageIO's Python binding)
  python3-pytest                    # make test: the analysis package's unit tests (tests/test_analysis.py)
  slurmctld slurmd slurm-client munge  # tests/slurm.test.sh: a private single-node Slurm for make sweep-slurm
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "install-deps: need root to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
