# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Lint colcon-wasm's Python code as a test (like colcon-core)."""

import subprocess
import sys

from colcon_helpers import REPO


def test_flake8():
    """Check style, docstrings, import order and quotes."""
    paths = [
        'colcon_wasm', 'tests/colcon_helpers.py', 'tests/humble_build.py',
        'bench/build', 'scripts/humble_report.py', 'scripts/testing_report.py',
        'tests/conftest.py', 'tests/wasm_test_build.py',
    ] + sorted(str(p.relative_to(REPO)) for p in REPO.glob('tests/test_*.py')
               if p.name.startswith(('test_colcon', 'test_recipe',
                                     'test_patch', 'test_glue', 'test_blasm',
                                     'test_humble', 'test_ci', 'test_conftest',
                                     'test_testing')))
    paths = [p for p in paths if (REPO / p).exists()]
    completed = subprocess.run(
        [sys.executable, '-m', 'flake8', '--extend-ignore=D100,D103,D104',
         '--per-file-ignores=tests/*:D101,D102,D105,D107'] + paths,
        cwd=REPO, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stdout + completed.stderr
