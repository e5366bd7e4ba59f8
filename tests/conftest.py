# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
No silent skips on CI.

A test skips when a tool it needs is missing (Chromium, the Humble
snapshot, Fast CDR, ...), and says which. Locally that stays a skip, listed
in the summary (`-rs`). When the environment variable `CI` is set (GitHub
Actions and `.ci/run` set it), a skip fails the test instead, with the
skip's reason: CI installs every tool (`.ci/run`), so a skip there means a
test that did not run and nobody would notice.
"""

import os

import pytest

"""The environment variable that marks a CI run."""
CI_VARIABLE = 'CI'


def on_ci():
    """Check if this is a CI run (`CI` set to anything but empty, 0 or false)."""
    value = os.environ.get(CI_VARIABLE, '')
    return value.strip().lower() not in ('', '0', 'false', 'no')


def skip_reason(report):
    """Get the reason of a skipped test's report."""
    longrepr = report.longrepr
    if isinstance(longrepr, tuple) and len(longrepr) == 3:
        return str(longrepr[2]).replace('Skipped: ', '', 1)
    return str(longrepr)


def ci_failure_text(reason):
    """Say why a skip fails the run on CI, naming what was missing."""
    return (f'skipped on CI ({CI_VARIABLE}={os.environ.get(CI_VARIABLE)}): {reason}\n'
            'On CI every test must run: install what it needs in .ci/run (or unset '
            f'{CI_VARIABLE} to let it skip locally).')


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Turn a skip into a failure when `CI` is set (xfail stays xfail)."""
    outcome = yield
    report = outcome.get_result()
    if not report.skipped or hasattr(report, 'wasxfail') or not on_ci():
        return
    report.outcome = 'failed'
    report.longrepr = ci_failure_text(skip_reason(report))


def pytest_configure(config):
    """List skips in the summary of a local run (as `-rs` does)."""
    reportchars = config.option.reportchars or ''
    if 's' not in reportchars and 'a' not in reportchars.lower():
        config.option.reportchars = reportchars + 's'
