# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Lint all of colcon-wasm's Python code as a test (like colcon-core's test_flake8.py)."""

from pathlib import Path
import subprocess
import sys

REPO = Path(__file__).resolve().parents[1]


def python_scripts():
    """List the Python scripts without a `.py` suffix (bench/*, scripts/*)."""
    found = []
    for folder in ('bench', 'scripts', '.ci'):
        for path in sorted((REPO / folder).glob('*')):
            if path.is_file() and not path.suffix:
                with path.open('rb') as f:
                    if b'python' in f.readline():
                        found.append(str(path.relative_to(REPO)))
    return found


def test_flake8():
    """Check style, docstrings, import order, quotes and f-strings of the whole tree."""
    # the rules (99 columns, looser docstrings for tests, what is left out)
    # are setup.cfg's [flake8] section
    completed = subprocess.run(
        [sys.executable, '-m', 'flake8', '.'] + python_scripts(),
        cwd=REPO, capture_output=True, text=True)
    assert completed.returncode == 0, completed.stdout + completed.stderr


def test_flake8_covers_the_bench_scripts():
    """The extensionless bench scripts are linted too."""
    assert 'bench/build' in python_scripts()
