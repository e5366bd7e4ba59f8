#!/usr/bin/env python3
# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Write the table of rcl's own tests in docs/testing.md from a real run.

    python scripts/testing_report.py                 # the cached test build of the tests
    python scripts/testing_report.py --workspace WS  # a workspace built like it
    python scripts/testing_report.py --no-run        # read the last results only

It runs `colcon test --wasm --packages-select rcl` in the test build of
tests/wasm_test_build.py (building it when it is not cached), reads what
`colcon test --wasm` left (gtest result files, and colcon-wasm's own for
not-applicable tests) and replaces the table between the markers of
docs/testing.md. tests/test_testing_doc.py checks the table against a run.

Each failing case needs a reason in KNOWN_FAILURES; a failure without one is
printed and written as "unexplained".
"""

import argparse
from pathlib import Path
import re
import sys
import xml.etree.ElementTree as ElementTree

REPO = Path(__file__).resolve().parents[1]
DOC = REPO / 'docs' / 'testing.md'
BEGIN = '<!-- rcl-table:begin (scripts/testing_report.py) -->'
END = '<!-- rcl-table:end -->'

"""Why a case of rcl's tests fails in WebAssembly ('Suite.case': reason)."""
CLOCK = (
    "Emscripten 3.1.6's CLOCK_REALTIME is Date.now(), whole milliseconds: "
    'two readings in one millisecond are equal, and the test expects the '
    'system clock to advance between them (RCL_SYSTEM_TIME; steady time has '
    'microseconds). In a run where the millisecond changes between the two '
    'readings, it passes')
KNOWN_FAILURES = {
    'TestTimerFixture.test_system_time_to_ros_time': CLOCK,
    'TestPreInitTimer.test_timer_call': CLOCK,
}


"""Known failures that pass in some runs (they depend on timing)."""
MAY_PASS = {case for case, reason in KNOWN_FAILURES.items() if reason is CLOCK}


class Row:
    """One test of the table: a CTest test, run or not applicable."""

    def __init__(self, name, result, cases=0, passed=0, failed=(), note=''):
        """Describe a row."""
        self.name = name
        self.result = result      # 'passed', 'failed' or 'not applicable'
        self.cases = cases
        self.passed = passed
        self.failed = list(failed)
        self.note = note

    def key(self):
        """Get what a run must reproduce (the note is prose)."""
        return (self.name, self.result, self.cases, self.passed, tuple(sorted(self.failed)))

    def markdown(self):
        """Format the row."""
        if self.result == 'not applicable':
            return f'| `{self.name}` | not applicable | | | {self.note} |'
        note = self.note
        if self.failed:
            note = '; '.join(
                f'`{case}` failed: {KNOWN_FAILURES.get(case, "unexplained")}'
                for case in self.failed)
            # one reason for several cases: say it once
            reasons = {KNOWN_FAILURES.get(c, 'unexplained') for c in self.failed}
            if len(reasons) == 1:
                note = ', '.join(f'`{c}`' for c in self.failed) + ' failed: ' + reasons.pop()
        return (f'| `{self.name}` | {self.result} | {self.cases} | {self.passed} | '
                f'{note} |')


def read_rows(build_base):
    """
    Read the rows from the result files of `colcon test --wasm` in rcl's build folder.

    :param build_base: the package's build folder (`build_wasm/rcl`)
    """
    build_base = Path(build_base)
    rows = {}
    for path in sorted((build_base / 'test_results' / 'rcl').glob('*.gtest.xml')):
        name = path.name[:-len('.gtest.xml')]
        root = ElementTree.parse(str(path)).getroot()
        cases = 0
        failed = []
        for case in root.iter('testcase'):
            cases += 1
            if case.find('failure') is not None or case.find('error') is not None:
                suite = case.get('classname', '').split('.', 1)[-1]
                failed.append(f"{suite}.{case.get('name')}")
        rows[name] = Row(name, 'failed' if failed else 'passed', cases,
                         cases - len(failed), failed)
    for path in sorted((build_base / 'colcon_wasm').glob('*.xml')):
        root = ElementTree.parse(str(path)).getroot()
        for case in root.iter('testcase'):
            skipped = case.find('skipped')
            failure = case.find('failure')
            name = case.get('name')
            if path.stem == 'linters':
                continue
            if skipped is not None:
                reason = skipped.get('message', '')
                reason = reason.replace('not applicable in WebAssembly: ', '', 1)
                rows[name] = Row(name, 'not applicable', note=reason)
            elif failure is not None and name not in rows:
                rows[name] = Row(name, 'failed', 1, 0, [name],
                                 note=failure.get('message', ''))
    return [rows[name] for name in sorted(rows)]


def table(rows):
    """Format the table, with a summary line."""
    ran = [r for r in rows if r.result != 'not applicable']
    cases = sum(r.cases for r in ran)
    passed = sum(r.passed for r in ran)
    lines = [
        f'{len(ran)} test executables ran ({cases} cases, {passed} passed, '
        f'{cases - passed} failed); '
        f'{len(rows) - len(ran)} are not applicable.',
        '',
        '| test | result | cases | passed | failed cases, or why not applicable |',
        '|---|---|---|---|---|',
    ] + [r.markdown() for r in rows]
    return '\n'.join(lines) + '\n'


def differences(documented, measured):
    """
    Compare the documented rows with a run's.

    A case of :data:`MAY_PASS` may pass in a run although the table lists it
    as failed (its row then has one more passed case).

    :returns: a list of differences (empty when the run matches the table)
    """
    problems = []
    documented = {r.name: r for r in documented}
    measured = {r.name: r for r in measured}
    for name in sorted(set(documented) ^ set(measured)):
        where = 'the table' if name in documented else 'the run'
        problems.append(f'{name}: only in {where}')
    for name in sorted(set(documented) & set(measured)):
        doc, run = documented[name], measured[name]
        passed_anyway = [c for c in doc.failed if c not in run.failed and c in MAY_PASS]
        expected_failed = sorted(set(doc.failed) - set(passed_anyway))
        expected_result = doc.result
        if doc.result == 'failed' and not expected_failed:
            expected_result = 'passed'
        expected = (name, expected_result, doc.cases, doc.passed + len(passed_anyway),
                    tuple(expected_failed))
        if run.key() != expected:
            problems.append(f'{name}: the table says {doc.key()}, the run gave {run.key()}')
    return problems


def doc_rows(text=None):
    """Read the rows of the table in docs/testing.md."""
    text = DOC.read_text() if text is None else text
    start = text.index(BEGIN)
    end = text.index(END)
    rows = []
    for line in text[start:end].splitlines():
        match = re.match(r'^\| `([^`]+)` \| ([a-z ]+) \|', line)
        if not match:
            continue
        cells = [c.strip() for c in line.strip('|').split('|')]
        name, result = match.group(1), match.group(2).strip()
        if result == 'not applicable':
            rows.append(Row(name, result, note=cells[4]))
            continue
        failed = re.findall(r'`([^`]+)`', cells[4].split(' failed:')[0]) \
            if 'failed:' in cells[4] else []
        rows.append(Row(name, result, int(cells[2]), int(cells[3]), failed, note=cells[4]))
    return rows


def write_doc(rows):
    """Replace the table between the markers of docs/testing.md."""
    text = DOC.read_text()
    start = text.index(BEGIN) + len(BEGIN)
    end = text.index(END)
    DOC.write_text(text[:start] + '\n' + table(rows) + text[end:])


def main(argv=None):
    """Run rcl's tests and write the table."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--workspace', type=Path,
                        help='a workspace built like tests/wasm_test_build.py (default: '
                             'that build, from the cache)')
    parser.add_argument('--no-run', action='store_true',
                        help='read the results of the last colcon test --wasm')
    args = parser.parse_args(argv)
    sys.path.insert(0, str(REPO / 'tests'))
    from rclcpp_build import ExistingBuild
    from wasm_test_build import colcon_test
    from wasm_test_build import wasm_test_build
    build = ExistingBuild(args.workspace) if args.workspace else wasm_test_build()
    if not args.no_run:
        tested, _ = colcon_test(build, 'rcl')
        if tested.returncode != 0:
            sys.stderr.write(tested.stdout[-4000:])
            return 1
    rows = read_rows(build.build / 'rcl')
    for row in rows:
        for case in row.failed:
            if case not in KNOWN_FAILURES:
                print(f'{row.name}: {case} failed, and KNOWN_FAILURES has no reason for it')
    write_doc(rows)
    print(table(rows))
    return 0


if __name__ == '__main__':
    sys.exit(main())
