# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Lint the tests and helpers of serve, launch, typedesc, CDR and the page."""

from pathlib import Path
import subprocess
import sys

REPO = Path(__file__).resolve().parents[1]


def test_flake8_of_the_launcher_tests():
    """Check style, docstrings, import order and quotes of these test files."""
    prefixes = ('test_serve', 'test_launch', 'test_typedesc', 'test_cdr', 'test_page',
                'test_pyodide', 'test_record')
    paths = sorted(str(p.relative_to(REPO)) for p in REPO.glob('tests/test_*.py')
                   if p.name.startswith(prefixes))
    paths += ['tests/cdr_fastcdr.py', 'tests/demo_build.py', 'packages/wasm_js/src/python/rclpy']
    completed = subprocess.run(
        [sys.executable, '-m', 'flake8', '--extend-ignore=D100,D103,D104',
         '--per-file-ignores=tests/*:D101,D102,D105,D107'] + paths,
        cwd=REPO, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stdout + completed.stderr
