# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon test --wasm` on real packages (issue 15).

The cached test build of tests/wasm_test_build.py (Humble up to
test_rmw_implementation and rcl, with fault injection, plus the fixtures)
is tested here with `colcon test --wasm`, and read back with `colcon
test-result --wasm`, as a user would:

* the fixture package tests/ros_fixtures/wasm_test_cases: gtest and gmock
  tests, one failing on purpose (shown with its message), data files, a test
  that times out (reported as such, without hanging), one that needs fork()
  (failing clearly, or not applicable through a recipe overlay), the memory
  tools, the linters it asks for (skipped with the reason);
* test_rmw_implementation, the rmw conformance suite: all 123 cases pass,
  with fault injection (and rmw_wasm_cpp_fault_tests: no leak, no endpoint
  left on the bus, messages still carried after injected failures);
* rcl's own tests: checked against docs/testing.md (tests/test_testing_doc.py).
"""

import xml.etree.ElementTree as ElementTree

import pytest
from wasm_test_build import colcon_test
from wasm_test_build import wasm_test_build

"""The number of test cases of test_rmw_implementation at Humble (2.8.4)."""
RMW_CONFORMANCE_CASES = 123


@pytest.fixture(scope='module')
def build():
    """Get the cached test build; skips when a snapshot is absent."""
    return wasm_test_build()


def gtest_cases(build, package):
    """
    Read the gtest result files of a package's last `colcon test`.

    :returns: {test executable: {'Suite.case': (outcome, message)}}, outcome
      'passed', 'failed' or 'skipped'
    """
    folder = build.build / package / 'test_results' / package
    found = {}
    for path in sorted(folder.glob('*.gtest.xml')):
        cases = {}
        for case in ElementTree.parse(str(path)).getroot().iter('testcase'):
            suite = case.get('classname', '').split('.', 1)[-1]
            failure = case.find('failure')
            if failure is None:
                failure = case.find('error')
            if failure is not None:
                outcome, message = 'failed', failure.get('message', '')
            elif case.find('skipped') is not None or case.get('status') == 'notrun':
                outcome, message = 'skipped', ''
            else:
                outcome, message = 'passed', ''
            cases[f"{suite}.{case.get('name')}"] = (outcome, message)
        found[path.name[:-len('.gtest.xml')]] = cases
    return found


def failures(cases):
    return {f'{exe}: {name}': message for exe, by_name in cases.items()
            for name, (outcome, message) in by_name.items() if outcome == 'failed'}


@pytest.fixture(scope='module')
def fixture_run(build):
    """Run the fixture package's tests once."""
    return colcon_test(build, 'wasm_test_cases')


def test_failing_test_is_shown_with_its_message(fixture_run):
    tested, shown = fixture_run
    # test failures are not a colcon error: the package finishes "with test failures"
    assert tested.returncode == 0, tested.stdout[-4000:]
    assert 'wasm_test_cases [' in tested.stdout and 'with test failures' in tested.stdout
    assert shown.returncode == 1, shown.stdout[-4000:]
    assert 'test_failing.gtest.xml: 2 tests, 0 errors, 1 failure' in shown.stdout, shown.stdout
    assert 'wasm_test_cases.Failing on_purpose' in shown.stdout
    assert 'this test fails on purpose: 2 + 2 is not 5' in shown.stdout


def test_gtest_and_gmock_tests_pass_in_node(build, fixture_run):
    cases = gtest_cases(build, 'wasm_test_cases')
    assert cases['test_calculator'] == {
        'Calculator.adds': ('passed', ''), 'Calculator.multiplies': ('passed', ''),
        'Calculator.exceptions_and_threads': ('passed', '')}
    assert cases['test_mock'] == {'CalculatorJournal.records_each_operation': ('passed', '')}
    assert cases['test_failing']['Failing.passes_first'] == ('passed', '')
    # the executables are Node.js programs that run by themselves
    exe = build.build / 'wasm_test_cases' / 'test_calculator.js'
    assert exe.read_text().startswith('#!/usr/bin/env node\n')


def test_data_files_environment_and_working_directory(build, fixture_run):
    cases = gtest_cases(build, 'wasm_test_cases')
    assert cases['test_data'] == {
        'Data.next_to_the_test': ('passed', ''),
        'Data.named_by_the_environment': ('passed', ''),
        'Data.installed': ('passed', ''),
        'Data.written_by_the_test': ('passed', '')}, cases['test_data']
    # written on the host file system, in the test's working directory
    written = build.build / 'wasm_test_cases' / 'written_by_test_data.txt'
    assert written.read_text() == 'written in WebAssembly\n'


def test_a_test_that_never_ends_is_stopped_and_reported(fixture_run):
    tested, shown = fixture_run
    assert 'wasm_test_cases.test_timeout test_timeout' in shown.stdout, shown.stdout
    assert 'timed out: CTest stopped it after 5.' in shown.stdout
    assert 'its time limit is 5.0 s' in shown.stdout
    assert 'Timeout.waits_forever' in shown.stdout  # its output, up to where it hung


def test_fork_fails_with_a_clear_reason(build, fixture_run):
    cases = gtest_cases(build, 'wasm_test_cases')
    outcome, message = cases['test_fork']['Fork.child_exits']
    assert outcome == 'failed' and 'fork: Function not implemented' in message


def test_not_applicable_tests_are_reported_with_the_reason(build, tmp_path):
    overlay = tmp_path / 'no-fork.yaml'
    overlay.write_text(
        'packages:\n  wasm_test_cases:\n    tests:\n      not-applicable:\n'
        '        test_fork: forks a child process; WebAssembly has no fork()\n')
    tested, shown = colcon_test(
        build, 'wasm_test_cases', extra=('--wasm-recipe', str(overlay),
                                         '--ctest-args', '-R', 'test_(fork|calculator)'))
    assert tested.returncode == 0, tested.stdout[-4000:]
    assert 'colcon_wasm/test_fork.xml: 1 test, 0 errors, 0 failures, 1 skipped' in shown.stdout
    result = (build.build / 'wasm_test_cases' / 'colcon_wasm' / 'test_fork.xml').read_text()
    assert 'not applicable in WebAssembly: forks a child process' in result
    assert 'with test failures' not in tested.stdout, tested.stdout[-4000:]


def test_linters_are_skipped_with_the_reason(build, fixture_run):
    _, shown = fixture_run
    assert 'colcon_wasm/linters.xml: 8 tests, 0 errors, 0 failures, 8 skipped' in shown.stdout
    linters = (build.build / 'wasm_test_cases' / 'colcon_wasm' / 'linters.xml').read_text()
    assert "'ament_uncrustify' is a Python linter of the package's sources" in linters


def test_memory_tools_see_allocations(build, fixture_run):
    cases = gtest_cases(build, 'wasm_test_cases')
    assert cases['test_memory_tools'] == {
        'MemoryTools.see_unexpected_allocations': ('passed', '')}


def test_rmw_conformance_suite_passes_with_fault_injection(build):
    tested, shown = colcon_test(build, 'test_rmw_implementation')
    assert tested.returncode == 0, tested.stdout[-4000:]
    cases = gtest_cases(build, 'test_rmw_implementation')
    total = sum(len(c) for c in cases.values())
    assert total == RMW_CONFORMANCE_CASES, sorted(cases)
    assert not failures(cases), failures(cases)
    assert all(o == 'passed' for c in cases.values() for o, _ in c.values())
    assert 'with test failures' not in tested.stdout
    # the failures were injected: rcutils and rmw were built with fault injection
    output = (build.build / 'test_rmw_implementation' / 'ament_cmake_gtest' /
              'test_create_destroy_node__rmw_wasm_cpp.txt').read_text()
    assert 'Injecting fault and returning' in output


def test_injected_failures_leave_no_leak_and_a_working_bus(build):
    tested, shown = colcon_test(build, 'rmw_wasm_cpp_fault_tests')
    cases = gtest_cases(build, 'rmw_wasm_cpp_fault_tests')
    assert not failures(cases), failures(cases)
    assert set(cases['test_fault_injection']) == {
        'FaultInjection.init_and_shutdown', 'FaultInjection.nodes',
        'FaultInjection.publishers_and_subscriptions', 'FaultInjection.services_and_clients',
        'FaultInjection.wait_sets_and_guard_conditions', 'FaultInjection.graph_queries',
        'FaultInjection.the_bus_still_carries_messages'}
    assert tested.returncode == 0 and 'with test failures' not in tested.stdout, \
        tested.stdout[-4000:]
