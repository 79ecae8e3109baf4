#!/usr/bin/env bash
# calibrate.test.sh: the cost model of experiments/calibrate.py on synthetic
# renders (tests/test_calibrate.py): a fit validates on renders it did not
# see, and one fitted on shuffled times does not (the negative control).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
PY=${PYTHON:-/usr/bin/python3}
if "$PY" -c 'import pytest, numpy, scipy' 2>/dev/null; then
  check "pytest tests/test_calibrate.py" "$PY" -m pytest -q -p no:cacheprovider tests/test_calibrate.py
else
  echo "skipped: needs python3-pytest, numpy and scipy"; echo "$PASS passed, $FAIL failed, 1 skipped"; [ "$FAIL" -eq 0 ]; exit
fi
finish
