#!/usr/bin/env bash
# Installs the Debian 12 packages photonmap needs, by tier, only those
# missing; idempotent. The Makefile runs each tier once, when a target
# needs it, and stamps it (build/.deps-TIER):
#   build    the compiler, OpenEXR and libpng: a plain `make`
#   test     what `make test`, the experiments and `make bench` add: clang and
#            its sanitizer/libFuzzer runtimes, POV-Ray, OpenImageIO, Python
#            with numpy/scipy/pandas/matplotlib/OIIO/pytest, valgrind, perf,
#            /usr/bin/time, nanoflann and FLANN (make bench), Snakemake
#   cluster  a private single-node Slurm (tests/slurm.test.sh)
#
#   bash scripts/install-deps.sh [build] [test] [cluster]    (no argument: all three)
# Exit status: 0, 1 when packages are missing and cannot be installed (not
# root, no sudo), 2 on an unknown tier.
set -euo pipefail

tier_packages() { # TIER: its packages, one word each
  case $1 in
    build) echo build-essential pkg-config \
                libopenexr-dev libpng-dev ;;       # EXR via OpenEXR's C API, PNG previews
    test) echo clang libclang-rt-14-dev \
               openimageio-tools \
               povray \
               time \
               valgrind linux-perf libnanoflann-dev libflann-dev \
               python3 python3-numpy python3-scipy python3-pandas python3-matplotlib \
               python3-openimageio python3-pytest \
               snakemake ;;
    # clang + runtimes: the CI's second compiler, the sanitizer build, libFuzzer;
    # oiiotool/idiff: image diffs; POV-Ray 3.7: the independent reference;
    # /usr/bin/time: CPU seconds of every render; valgrind, perf, nanoflann:
    # make bench; Python: the analysis package and its pytest tests;
    # Snakemake: the workflow engine of the studies (experiments/Snakefile)
    cluster) echo slurmctld slurmd slurm-client munge ;;
    *) echo "install-deps: unknown tier '$1' (build, test or cluster)" >&2; return 2 ;;
  esac
}

tiers=("$@")
[ ${#tiers[@]} -gt 0 ] || tiers=(build test cluster)
packages=()
for t in "${tiers[@]}"; do
  words=$(tier_packages "$t") || exit 2
  read -r -a w <<< "$words"
  packages+=("${w[@]}")
done

# One run at a time: `make -j` starts the tiers together, and two apt-gets
# at once fail on apt's lock. The second run waits here, then installs only
# what the first left missing.
exec 9>"${TMPDIR:-/tmp}/photonmap-install-deps.lock"
flock 9

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: ${tiers[*]}: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: ${tiers[*]}: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "install-deps: need root to install: ${missing[*]}" >&2; exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
# and wait (up to 10 minutes) for any other apt or dpkg run to finish
APT_WAIT=(-o DPkg::Lock::Timeout=600)
$SUDO apt-get "${APT_WAIT[@]}" update -qq
$SUDO apt-get "${APT_WAIT[@]}" install -y -qq --no-install-recommends "${missing[@]}"
