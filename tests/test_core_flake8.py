# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Lint the middleware-core tests and bench (same rules as the colcon code)."""

import subprocess
import sys

from core import harness


def test_flake8_core():
    """Check style, docstrings, import order and quotes."""
    paths = ['tests/core/harness.py', 'bench/transport'] + sorted(
        str(p.relative_to(harness.REPO))
        for p in harness.REPO.glob('tests/test_core_*.py'))
    completed = subprocess.run(
        [sys.executable, '-m', 'flake8', '--extend-ignore=D100,D103,D104',
         '--per-file-ignores=tests/*:D101,D102,D105,D107'] + paths,
        cwd=harness.REPO, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stdout + completed.stderr
