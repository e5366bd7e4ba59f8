# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
docs/testing.md says what of rcl's own tests runs in WebAssembly: check it.

rcl's tests run with `colcon test --wasm` in the cached test build
(tests/wasm_test_build.py), and the table of docs/testing.md (written by
scripts/testing_report.py) must match the run: the same tests, each passed,
failed (the same cases) or not applicable, with the same numbers of cases.
"""

from pathlib import Path
import sys

import pytest
from wasm_test_build import colcon_test
from wasm_test_build import wasm_test_build

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / 'scripts'))
import testing_report  # noqa: E402, I100, I202


@pytest.fixture(scope='module')
def rcl_run():
    """Run rcl's tests once in the cached test build."""
    build = wasm_test_build()
    tested, shown = colcon_test(build, 'rcl')
    assert tested.returncode == 0, tested.stdout[-4000:]
    return build, tested, shown


def test_table_matches_a_run(rcl_run):
    build, _, _ = rcl_run
    measured = testing_report.read_rows(build.build / 'rcl')
    documented = testing_report.doc_rows()
    assert documented, 'no table in docs/testing.md'
    problems = testing_report.differences(documented, measured)
    assert not problems, (
        "docs/testing.md does not match this run of rcl's tests (run `python "
        'scripts/testing_report.py` and check the result):\n' + '\n'.join(problems))


def test_every_failure_has_a_reason(rcl_run):
    documented = testing_report.doc_rows()
    for row in documented:
        if row.result == 'not applicable':
            assert row.note, row.name
        for case in row.failed:
            assert case in testing_report.KNOWN_FAILURES, (row.name, case)
            assert testing_report.KNOWN_FAILURES[case] in row.note, (row.name, case)


def test_not_applicable_tests_are_reported_by_colcon_test(rcl_run):
    build, _, shown = rcl_run
    documented = [r for r in testing_report.doc_rows() if r.result == 'not applicable']
    assert len(documented) >= 19
    for row in documented:
        result = build.build / 'rcl' / 'colcon_wasm' / f'{row.name}.xml'
        assert f'colcon_wasm/{row.name}.xml: 1 test, 0 errors, 0 failures, 1 skipped' \
            in shown.stdout, row.name
        assert 'not applicable in WebAssembly: ' in result.read_text()


def test_a_changed_run_is_caught():
    documented = testing_report.doc_rows()
    measured = [testing_report.Row(r.name, r.result, r.cases, r.passed, r.failed, r.note)
                for r in documented]
    assert testing_report.differences(documented, measured) == []
    ran = next(r for r in measured if r.result == 'passed')
    ran.result, ran.passed, ran.failed = 'failed', ran.passed - 1, ['Suite.new_failure']
    before = next(d for d in documented if d.name == ran.name)
    assert testing_report.differences(documented, measured) == [
        f'{ran.name}: the table says {before.key()}, the run gave {ran.key()}']
    # a known timing failure may pass in a run
    timer = next(r for r in measured if r.failed)
    timer.result, timer.passed, timer.failed = 'passed', timer.cases, []
    ran.result, ran.passed, ran.failed = 'passed', ran.cases, []
    assert testing_report.differences(documented, measured) == []
    assert testing_report.differences(documented, measured[1:]) == [
        f'{measured[0].name}: only in the table']
