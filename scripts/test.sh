#!/usr/bin/env bash
# Run colcon-wasm's test suite (the README's test command).
#   scripts/test.sh                 # everything
#   scripts/test.sh -k humble       # pytest arguments are passed on
# Uses .venv/ when it exists (see README), else the python3 on PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
python=python3
if [ -x .venv/bin/python ]; then
  python=.venv/bin/python
fi
# -rfEs: why each test failed, errored or skipped; --durations: where time goes
exec "$python" -m pytest -q -rfEs --durations=25 tests "$@"
