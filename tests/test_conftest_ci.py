# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""tests/conftest.py: a skip fails the run on CI (CI set), and stays a skip locally."""

import os
from pathlib import Path
import shutil
import subprocess
import sys

HERE = Path(__file__).resolve().parent

SAMPLE = """
import pytest

def test_runs():
    assert True

def test_needs_a_tool():
    pytest.skip('frobnicator not found at /opt/frob (apt-get install frobnicator)')

@pytest.mark.xfail(reason='known bug', strict=True)
def test_known_bug():
    assert False
"""


def run_sample(tmp_path, ci):
    """Run pytest on the sample with this repository's conftest.py."""
    shutil.copy(HERE / 'conftest.py', tmp_path / 'conftest.py')
    (tmp_path / 'test_sample.py').write_text(SAMPLE)
    env = {k: v for k, v in os.environ.items() if k != 'CI'}
    if ci is not None:
        env['CI'] = ci
    return subprocess.run(
        [sys.executable, '-m', 'pytest', '-p', 'no:cacheprovider', '-q', 'test_sample.py'],
        cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        text=True, timeout=120)


def test_skip_fails_on_ci_and_names_the_missing_tool(tmp_path):
    done = run_sample(tmp_path, 'true')
    assert done.returncode == 1, done.stdout
    assert '1 failed, 1 passed, 1 xfailed' in done.stdout, done.stdout
    assert 'FAILED test_sample.py::test_needs_a_tool' in done.stdout, done.stdout
    assert 'skipped on CI (CI=true): frobnicator not found at /opt/frob' in done.stdout
    assert 'install what it needs in .ci/run' in done.stdout


def test_skip_stays_a_skip_locally_and_is_listed(tmp_path):
    for ci in (None, '', 'false', '0'):
        done = run_sample(tmp_path, ci)
        assert done.returncode == 0, (ci, done.stdout)
        assert '1 passed, 1 skipped, 1 xfailed' in done.stdout, (ci, done.stdout)
        # listed in the short summary, with its reason
        assert 'SKIPPED [1] test_sample.py:' in done.stdout, (ci, done.stdout)
        assert 'frobnicator not found at /opt/frob' in done.stdout, (ci, done.stdout)
