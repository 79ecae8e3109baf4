#!/usr/bin/env bash
# analysis.test.sh: the unit tests of the experiment analysis layer
# (experiments/analysis/*.py), in tests/analysis_test.py, on Debian's python3
# (numpy, scipy, pandas, OpenImageIO). Ends with "N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."
exec "${PYTHON:-/usr/bin/python3}" tests/analysis_test.py
