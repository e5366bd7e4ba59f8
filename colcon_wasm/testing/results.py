# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
xUnit result files for what `colcon test-result` would not see otherwise.

`colcon test-result` reads xUnit files only. gtest writes one per
executable and ament's `run_test.py` writes one when a test fails without
it, but nothing is written for

* a test CTest stopped at its time limit (it kills `run_test.py` too),
* a test that never ran (its executable was not built, ...),
* a plain CTest test (`add_test()` without ament),
* what `colcon test --wasm` does not run: linters, and the tests the recipe
  says are not applicable in WebAssembly.

After CTest, :func:`write_results` reads CTest's own record
(`Testing/<tag>/Test.xml`) and writes one xUnit file per such test into
`<test result base>/colcon_wasm/`, each test case with its reason.
"""

import json
from pathlib import Path
import re
import shutil
import subprocess
from xml.etree import ElementTree
from xml.sax.saxutils import escape
from xml.sax.saxutils import quoteattr

from colcon_wasm.testing.options import AMENT_LINTERS

"""Folder of the result files written here (inside the package's test result base)."""
RESULTS_FOLDER = 'colcon_wasm'

"""Members of ament_lint_common (Humble), the linters most packages ask for."""
AMENT_LINT_COMMON = (
    'ament_cmake_copyright', 'ament_cmake_cppcheck', 'ament_cmake_cpplint',
    'ament_cmake_flake8', 'ament_cmake_lint_cmake', 'ament_cmake_pep257',
    'ament_cmake_uncrustify', 'ament_cmake_xmllint')

LINTER_REASON = (
    "not run by colcon test --wasm: '{tool}' is a Python linter of the package's "
    'sources, which are the same for every target; run it with a native colcon test')

"""How much of a test's output goes into a result file."""
OUTPUT_TAIL = 4000


class CtestTest:
    """One test CTest knows of, and how its last run ended."""

    __test__ = False  # not a pytest class

    def __init__(self, name, command):
        """Describe a test by its name and command line."""
        self.name = name
        self.command = list(command)
        self.status = None           # passed, failed, notrun (None: not in this run)
        self.completion = ''          # CTest's 'Completion Status' (Completed, Timeout, ...)
        self.exit_code = ''           # CTest's 'Exit Code' (Failed, Timeout, SEGFAULT, ...)
        self.exit_value = ''
        self.seconds = 0.0
        self.output = ''
        self.timeout = None

    @property
    def ament_result_file(self):
        """Get the xUnit file ament's `run_test.py` writes for this test, or None."""
        for index, argument in enumerate(self.command[:-1]):
            if Path(argument).name == 'run_test.py':
                return Path(self.command[index + 1])
        return None


def list_tests(ctest, build_base, env=None):
    """
    List the tests of a build folder with `ctest --show-only=json-v1`.

    :returns: the :class:`CtestTest` list (empty when CTest lists none)
    """
    completed = subprocess.run(
        [ctest, '--show-only=json-v1'], cwd=str(build_base), env=env,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if completed.returncode != 0:
        return []
    return parse_test_list(completed.stdout)


def parse_test_list(output):
    """Read the output of `ctest --show-only=json-v1` (bytes or text)."""
    if isinstance(output, bytes):
        output = output.decode(errors='replace')
    try:
        data = json.loads(output)
    except ValueError:
        return []
    tests = []
    for item in data.get('tests', []):
        test = CtestTest(item.get('name', ''), item.get('command') or [])
        for prop in item.get('properties', []):
            if prop.get('name') == 'TIMEOUT':
                test.timeout = prop.get('value')
        tests.append(test)
    return tests


def exclude_regex(names):
    """Get a CTest `-E` regular expression that matches exactly these test names."""
    return '^(' + '|'.join(re.escape(n) for n in sorted(names)) + ')$'


def read_ctest_record(build_base, tests):
    """
    Read how each test ended from CTest's record of the last run.

    :param tests: the :class:`CtestTest` list, updated in place
    """
    base = Path(build_base) / 'Testing'
    tag = base / 'TAG'
    if not tag.is_file():
        return
    lines = tag.read_text().splitlines()
    if not lines:
        return
    record = base / lines[0] / 'Test.xml'
    if not record.is_file():
        return
    by_name = {t.name: t for t in tests}
    for node in ElementTree.parse(str(record)).getroot().iter('Test'):
        name = node.findtext('Name')
        test = by_name.get(name)
        if test is None or node.get('Status') is None:
            continue
        test.status = node.get('Status')
        for measurement in node.iter('NamedMeasurement'):
            value = measurement.findtext('Value') or ''
            key = measurement.get('name')
            if key == 'Completion Status':
                test.completion = value
            elif key == 'Exit Code':
                test.exit_code = value
            elif key == 'Exit Value':
                test.exit_value = value
            elif key == 'Execution Time':
                try:
                    test.seconds = float(value)
                except ValueError:
                    pass
        test.output = node.findtext('Results/Measurement/Value') or ''


def _testsuite(suite, cases):
    """Format a testsuite of (name, seconds, kind, message, output) cases."""
    failures = sum(1 for c in cases if c[2] == 'failure')
    skipped = sum(1 for c in cases if c[2] == 'skipped')
    total = sum(c[1] for c in cases)
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<testsuite name={quoteattr(suite)} tests="{len(cases)}" '
             f'failures="{failures}" errors="0" skipped="{skipped}" time="{total:.3f}">']
    for name, seconds, kind, message, output in cases:
        classname = suite
        lines.append(f'  <testcase classname={quoteattr(classname)} '
                     f'name={quoteattr(name)} time="{seconds:.3f}">')
        if kind in ('failure', 'skipped'):
            lines.append(f'    <{kind} message={quoteattr(message)}/>')
        if output:
            lines.append(f'    <system-out>{escape(output[-OUTPUT_TAIL:])}</system-out>')
        lines.append('  </testcase>')
    lines.append('</testsuite>')
    return '\n'.join(lines) + '\n'


def timed_out(test):
    """Check if CTest stopped a test at its time limit."""
    return test.completion == 'Timeout' or test.exit_code == 'Timeout'


def describe_outcome(test, default_timeout):
    """
    Say how a test that wrote no result ended, or None when it passed.

    :returns: (kind, message): kind is 'failure' or None (passed)
    """
    if test.status == 'passed':
        return None, ''
    if timed_out(test):
        limit = test.timeout if test.timeout is not None else default_timeout
        return 'failure', (
            f'timed out: CTest stopped it after {test.seconds:.1f} s (its time limit is '
            f'{limit} s: the TIMEOUT of the test, or --wasm-test-timeout for tests '
            'without one)')
    if test.status == 'notrun':
        return 'failure', (
            f'not run: {test.completion or test.exit_code or "CTest did not start it"} '
            '(is its executable built? a missing REQUIRED_FILES entry, a failed link)')
    what = test.exit_code or test.completion or 'Failed'
    value = f' ({test.exit_value})' if test.exit_value else ''
    return 'failure', f'failed: {what}{value}'


def write_results(*, package, tests, result_base, default_timeout, run_started,
                  not_applicable, linters):
    """
    Write the xUnit files of this run into `<result_base>/colcon_wasm/`.

    :param str package: the package name (suite names are `<package>.<test>`)
    :param tests: the :class:`CtestTest` list, with :func:`read_ctest_record` applied
    :param run_started: the time (`time.time()`) CTest started: an ament
      result file older than that is from an earlier run
    :param not_applicable: {test name: reason} of the tests not run
    :param linters: the linter packages the package asks for (skipped)
    :returns: the files written
    """
    folder = Path(result_base) / RESULTS_FOLDER
    clear_results(result_base)
    written = []

    def write(name, cases):
        folder.mkdir(parents=True, exist_ok=True)
        path = folder / f'{_file_name(name)}.xml'
        path.write_text(_testsuite(f'{package}.{name}', cases))
        written.append(path)

    for test in tests:
        if test.name in not_applicable or test.status is None:
            continue
        kind, message = describe_outcome(test, default_timeout)
        output = test.output if kind else ''
        case = [(test.name, test.seconds, kind, message, output)]
        result_file = test.ament_result_file
        if result_file is not None and timed_out(test):
            # run_test.py, stopped with the test, wrote "The test did not
            # generate a result file": say what happened instead
            result_file.parent.mkdir(parents=True, exist_ok=True)
            result_file.write_text(_testsuite(f'{package}.{test.name}', case))
            written.append(result_file)
            continue
        if result_file is not None and result_file.is_file() and \
                result_file.stat().st_mtime >= run_started - 1:
            continue  # gtest or run_test.py wrote it in this run
        write(test.name, case)
    for name, reason in sorted(not_applicable.items()):
        write(name, [(name, 0.0, 'skipped', f'not applicable in WebAssembly: {reason}', '')])
    if linters:
        write('linters', [
            (tool[len('ament_cmake_'):] if tool.startswith('ament_cmake_') else tool, 0.0,
             'skipped', LINTER_REASON.format(tool=tool.replace('ament_cmake_', 'ament_')), '')
            for tool in linters])
    return written


def clear_results(result_base):
    """Remove the result files of an earlier `colcon test --wasm`."""
    shutil.rmtree(Path(result_base) / RESULTS_FOLDER, ignore_errors=True)


def _file_name(name):
    return re.sub(r'[^A-Za-z0-9_.-]', '_', name)


def package_linters(descriptor):
    """
    Get the linters a package asks ament_lint_auto for.

    :returns: the linter package names, sorted (empty without ament_lint_auto)
    """
    test_depends = {str(d) for d in descriptor.dependencies.get('test', ())}
    if 'ament_lint_auto' not in test_depends:
        return []
    linters = {d for d in test_depends if d in AMENT_LINTERS}
    if 'ament_lint_common' in test_depends:
        linters |= set(AMENT_LINT_COMMON)
    return sorted(linters)
