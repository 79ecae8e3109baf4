#!/usr/bin/env bash
# stability.sh: the name the stability sweeps had first; the sweeps live in
# scripts/stability.py (scale, translation, far object, degenerate settings,
# each with its expected value and verdict). Same options, same output:
#   scripts/stability.sh [--pm build/photonmap] [--quick] [--controls]
# (`make stability` writes its full report to results/stability-extremes.md.)
set -euo pipefail
exec "${PYTHON:-/usr/bin/python3}" "$(dirname "$0")/stability.py" "$@"
