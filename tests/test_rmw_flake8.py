# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""Lint the Python code of the rmw_wasm_cpp tests and benchmark as a test."""

import subprocess
import sys

from humble_build import REPO


def test_flake8():
    """Check style, docstrings, import order and quotes (as tests/test_colcon_flake8.py)."""
    paths = sorted(
        str(p.relative_to(REPO)) for p in
        [*REPO.glob('tests/test_rmw_*.py'), *REPO.glob('tests/test_humble_*.py'),
         REPO / 'tests' / 'rclcpp_build.py', *REPO.glob('tests/rmw/**/*.py'),
         REPO / 'bench' / 'rclcpp', REPO / 'tests' / 'rmw_scenario.py',
         REPO / 'scripts' / 'humble_examples_report.py']
        if p.exists())
    completed = subprocess.run(
        [sys.executable, '-m', 'flake8', '--extend-ignore=D100,D103,D104',
         '--per-file-ignores=tests/*:D101,D102,D105,D107'] + paths,
        cwd=REPO, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stdout + completed.stderr
