# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The parts of `colcon test --wasm` that a build would hide a mistake in.

The recipe's `tests` key, the test settings and the CMake arguments they
give, the result files for what `colcon test-result` would not see (read
back by colcon-test-result's own parser, from a real CTest run), the test
executables' `#!` line, and `colcon test-result --wasm`. The whole chain
(Emscripten, gtest, Node.js) runs in tests/test_colcon_test.py.
"""

import argparse
import os
from pathlib import Path
import shutil
import subprocess
import sys
import textwrap
import time

from colcon_test_result.test_result.xunit import parse_xunit_xml
from colcon_wasm import resources
from colcon_wasm.link import test_link
from colcon_wasm.recipe import load_recipe
from colcon_wasm.recipe import load_recipe_file
from colcon_wasm.recipe import RecipeError
from colcon_wasm.recipe.spec import PackageRule
from colcon_wasm.testing import results
from colcon_wasm.testing.options import cmake_arguments_for_tests
from colcon_wasm.testing.options import recipe_overlays_for_tests
from colcon_wasm.testing.options import TestSettings
import pytest

COLCON = Path(sys.executable).parent / 'colcon'


def _args(**kwargs):
    return argparse.Namespace(**kwargs)


def test_tests_key_of_a_package_rule(tmp_path):
    path = tmp_path / 'r.yaml'
    path.write_text(textwrap.dedent("""\
        packages:
          foo:
            tests:
              not-built: needs mimick
              not-applicable:
                test_fork: needs fork()
                test_signal_*: installs signal handlers
        """))
    rule = load_recipe([path]).rule('foo')
    assert rule.tests.not_built == 'needs mimick'
    assert rule.tests.not_applicable_reason('test_fork') == 'needs fork()'
    assert rule.tests.not_applicable_reason('test_signal_int') == 'installs signal handlers'
    assert rule.tests.not_applicable_reason('test_other') is None
    # exact names can be reported when the build left the test out; globs cannot
    assert rule.tests.unlisted_not_applicable({'test_other'}) == {'test_fork': 'needs fork()'}
    assert rule.tests.unlisted_not_applicable({'test_fork'}) == {}


@pytest.mark.parametrize('text, message', [
    ('packages:\n  foo:\n    tests: 3\n',
     ":3: 'packages.foo.tests': expected a mapping, got int 3"),
    ('packages:\n  foo:\n    tests:\n      skip: x\n',
     ":4: 'packages.foo.tests.skip': unknown key, expected one of: not-built, not-applicable"),
    ('packages:\n  foo:\n    tests:\n      not-applicable:\n        test_a: ""\n',
     ":5: 'packages.foo.tests.not-applicable.test_a': expected a non-empty string"),
    ('packages:\n  foo:\n    tests:\n      not-built: [a]\n',
     ":4: 'packages.foo.tests.not-built': expected a non-empty string, got a list"),
])
def test_tests_key_errors_name_file_line_and_key(tmp_path, text, message):
    path = tmp_path / 'r.yaml'
    path.write_text(text)
    with pytest.raises(RecipeError) as info:
        load_recipe_file(path)
    assert f'{path}{message}' in str(info.value)


def test_overlays_merge_tests_rules(tmp_path):
    first = tmp_path / 'a.yaml'
    first.write_text('packages:\n  foo:\n    tests:\n      not-applicable: {t1: one}\n')
    second = tmp_path / 'b.yaml'
    second.write_text('packages:\n  foo:\n    tests:\n      not-built: later\n'
                      '      not-applicable: {t2: two}\n')
    rule = load_recipe([first, second]).rule('foo')
    assert rule.tests.not_applicable == {'t1': 'one', 't2': 'two'}
    assert rule.tests.not_built == 'later'


def test_tests_overlay_is_applied_for_test_builds_and_colcon_test():
    assert recipe_overlays_for_tests(_args(wasm_tests=None, verb_name='build')) == []
    overlay = resources.file('recipes', 'humble-tests.yaml')
    assert recipe_overlays_for_tests(_args(wasm_tests=[], verb_name='build')) == [overlay]
    assert recipe_overlays_for_tests(_args(wasm_tests=None, verb_name='test')) == [overlay]
    recipe = load_recipe([overlay])
    for name in ('gtest_vendor', 'gmock_vendor', 'osrf_testing_tools_cpp',
                 'test_rmw_implementation', 'rmw_dds_common'):
        assert recipe.skip_reason(name) is None, name
    assert 'machine code' in recipe.skip_reason('mimick_vendor')
    for name in ('osrf_testing_tools_cpp', 'rcl'):
        patches = recipe.rule(name).patches
        assert patches and all(p.file.is_file() for p in patches), name
    assert 'mimick' in recipe.rule('rcl').tests.not_applicable_reason('test_logging')
    assert recipe.rule('rcutils').tests.not_built


def test_tests_of_named_packages_or_all_but_not_built():
    rule = PackageRule('foo')
    assert TestSettings(_args(wasm_tests=None)).tests_of('foo', rule) == (False, None)
    assert TestSettings(_args(wasm_tests=[])).tests_of('foo', rule) == (True, None)
    named = TestSettings(_args(wasm_tests=['bar']))
    assert named.tests_of('foo', rule) == (False, 'not named by --wasm-tests')
    assert named.tests_of('bar', rule) == (True, None)
    rule.tests.not_built = 'needs mimick'
    assert TestSettings(_args(wasm_tests=[])).tests_of('foo', rule) == (False, 'needs mimick')
    # naming a package builds its tests anyway
    assert TestSettings(_args(wasm_tests=['foo'])).tests_of('foo', rule) == (True, None)


def cmake_arguments_for_tests_are_always_given_on_or_off():
    rule = PackageRule('foo')
    off = TestSettings(_args(wasm_tests=None, wasm_fault_injection=False))
    assert cmake_arguments_for_tests(off, 'foo', rule) == [
        '-DCOLCON_WASM_TESTS=OFF', '-DCOLCON_WASM_FAULT_INJECTION=OFF']
    on = TestSettings(_args(wasm_tests=['foo'], wasm_fault_injection=True))
    assert cmake_arguments_for_tests(on, 'foo', rule) == [
        '-DCOLCON_WASM_TESTS=ON', '-DCOLCON_WASM_FAULT_INJECTION=ON']
    assert on.describe() == {'fault_injection': True}
    assert off.describe() == {}


@pytest.fixture(scope='module')
def ctest_run(tmp_path_factory):
    """Run CTest: a passing, a failing and a timed-out test, and one never run."""
    if shutil.which('cmake') is None or shutil.which('ctest') is None:
        pytest.skip('cmake and ctest are needed (apt-get install cmake)')
    root = tmp_path_factory.mktemp('ctest')
    source = root / 'src'
    source.mkdir()
    python = sys.executable
    (source / 'CMakeLists.txt').write_text(textwrap.dedent(f"""\
        cmake_minimum_required(VERSION 3.16)
        project(sample NONE)
        enable_testing()
        add_test(NAME passes COMMAND "{python}" -c "print('fine')")
        add_test(NAME fails COMMAND "{python}" -c "import sys; print('broken'); sys.exit(3)")
        add_test(NAME hangs COMMAND "{python}" -c "import time; print('waiting'); time.sleep(60)")
        set_tests_properties(hangs PROPERTIES TIMEOUT 2)
        add_test(NAME missing COMMAND "{python}" -c "")
        set_tests_properties(missing PROPERTIES REQUIRED_FILES "{root}/not_built.js")
        """))
    build = root / 'build'
    subprocess.run(['cmake', '-S', str(source), '-B', str(build)], check=True,
                   stdout=subprocess.DEVNULL)
    tests = results.list_tests(shutil.which('ctest'), build)
    started = time.time()
    subprocess.run(['ctest', '-D', 'ExperimentalTest', '--no-compress-output'], cwd=build,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    results.read_ctest_record(build, tests)
    return build, tests, started


def test_ctest_record_says_how_each_test_ended(ctest_run):
    _, tests, _ = ctest_run
    by_name = {t.name: t for t in tests}
    assert set(by_name) == {'passes', 'fails', 'hangs', 'missing'}
    assert by_name['passes'].status == 'passed'
    assert by_name['fails'].status == 'failed' and 'broken' in by_name['fails'].output
    assert results.timed_out(by_name['hangs']) and by_name['hangs'].timeout == 2.0
    assert by_name['missing'].status == 'notrun'


def test_results_for_what_test_result_would_not_see(ctest_run, tmp_path):
    _, tests, started = ctest_run
    written = results.write_results(
        package='sample', tests=tests, result_base=tmp_path, default_timeout='300',
        run_started=started, not_applicable={'test_fork': 'needs fork()'},
        linters=['ament_cmake_copyright', 'ament_cmake_xmllint'])
    folder = tmp_path / results.RESULTS_FOLDER
    assert sorted(p.name for p in written) == [
        'fails.xml', 'hangs.xml', 'linters.xml', 'missing.xml', 'passes.xml', 'test_fork.xml']
    # read back by colcon test-result's own parser
    parsed = {p.stem: parse_xunit_xml(str(p), get_testcases=True) for p in written}
    assert (parsed['passes'].test_count, parsed['passes'].failure_count) == (1, 0)
    hangs = '\n'.join(parsed['hangs'].details)
    assert parsed['hangs'].failure_count == 1
    assert 'timed out: CTest stopped it after 2.' in hangs and 'limit is 2.0 s' in hangs
    assert 'waiting' in hangs  # the test's output
    assert 'failed: Failed (3)' in '\n'.join(parsed['fails'].details)
    assert 'not run' in '\n'.join(parsed['missing'].details)
    assert parsed['test_fork'].skipped_count == 1
    assert 'not applicable in WebAssembly: needs fork()' in (folder / 'test_fork.xml').read_text()
    linters = (folder / 'linters.xml').read_text()
    assert parsed['linters'].skipped_count == 2
    assert "'ament_copyright' is a Python linter" in linters
    # a new run starts from scratch
    results.clear_results(tmp_path)
    assert not folder.exists()


def test_ament_result_files_of_this_run_are_kept(tmp_path):
    result = tmp_path / 'test_results' / 'pkg' / 'test_a.gtest.xml'
    test = results.CtestTest('test_a', [
        sys.executable, '-u', '/x/ament_cmake_test/run_test.py', str(result),
        '--package-name', 'pkg', '--command', '/b/test_a.js'])
    test.status = 'failed'
    assert test.ament_result_file == result
    result.parent.mkdir(parents=True)
    result.write_text('<testsuite tests="1" failures="1"/>')
    started = time.time() - 5
    results.write_results(package='pkg', tests=[test], result_base=tmp_path,
                          default_timeout='60', run_started=started,
                          not_applicable={}, linters=[])
    assert not (tmp_path / results.RESULTS_FOLDER).exists()  # gtest's own file says it all
    # a timed-out test: run_test.py's "did not generate a result file" is replaced
    test.completion = 'Timeout'
    test.seconds = 60.1
    results.write_results(package='pkg', tests=[test], result_base=tmp_path,
                          default_timeout='60', run_started=started,
                          not_applicable={}, linters=[])
    assert 'timed out: CTest stopped it after 60.1 s' in result.read_text()


def test_linters_of_a_package():
    class Descriptor:
        dependencies = {'test': {'ament_lint_auto', 'ament_lint_common', 'ament_cmake_gtest'}}
    assert results.package_linters(Descriptor()) == sorted(results.AMENT_LINT_COMMON)
    Descriptor.dependencies = {'test': {'ament_cmake_copyright', 'ament_cmake_gtest'}}
    assert results.package_linters(Descriptor()) == []  # without ament_lint_auto


def test_test_executables_run_by_themselves(tmp_path):
    script = tmp_path / 'test_x.js'
    script.write_text('console.log("ran with " + process.argv.slice(2).join(" "));\n')
    test_link.make_runnable(str(script))
    test_link.make_runnable(str(script))  # once only
    text = script.read_text()
    assert text.startswith('#!/usr/bin/env node\n') and text.count('#!') == 1
    assert os.access(script, os.X_OK)
    if shutil.which('node'):
        done = subprocess.run([str(script), '--gtest_output=xml:r.xml'], capture_output=True,
                              text=True, timeout=60)
        assert done.stdout == 'ran with --gtest_output=xml:r.xml\n'


def test_test_links_are_gtest_gmock_or_noderawfs():
    class Link:
        def __init__(self, arguments, archives):
            self.arguments = arguments
            self.archives = archives
    assert test_link.is_test_link(Link([], ['gtest/libgtest_main.a', 'libfoo.a']))
    assert test_link.is_test_link(Link([], ['/b/gmock/libgmock.a']))
    assert test_link.is_test_link(Link(['-sNODERAWFS=1'], []))
    assert not test_link.is_test_link(Link([], ['libfoo.a', 'libgtest_helpers.a']))
    flags = test_link.test_link_flags(Link([], []), '/t/pre.js')
    assert flags == ['-sNODERAWFS=1', '--pre-js', '/t/pre.js']
    assert test_link.test_link_flags(Link(['-sNODERAWFS=1'], []), 'p') == ['--pre-js', 'p']


def test_test_result_wasm_reads_build_wasm(tmp_path):
    folder = tmp_path / 'build_wasm' / 'pkg' / 'test_results'
    folder.mkdir(parents=True)
    (folder / 'r.xml').write_text(
        '<testsuite name="pkg.t" tests="1" failures="1"><testcase classname="pkg" name="t">'
        '<failure message="it broke"/></testcase></testsuite>')
    env = dict(os.environ, COLCON_HOME=str(tmp_path / '.colcon'))
    done = subprocess.run([str(COLCON), 'test-result', '--wasm', '--verbose'], cwd=tmp_path,
                          env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode == 1, done.stdout + done.stderr
    assert 'build_wasm/pkg/test_results/r.xml: 1 test, 0 errors, 1 failure' in done.stdout
    assert 'it broke' in done.stdout
    # without --wasm: colcon's default (build/), which is not there
    done = subprocess.run([str(COLCON), 'test-result'], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "Path 'build' does not exist" in done.stderr
    # an explicit base wins over --wasm
    done = subprocess.run([str(COLCON), 'test-result', '--wasm', '--test-result-base',
                           'build_wasm/pkg'], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=120)
    assert 'build_wasm/pkg/test_results/r.xml' in done.stdout, done.stdout + done.stderr
    shutil.rmtree(tmp_path / 'build_wasm')
    done = subprocess.run([str(COLCON), 'test-result', '--wasm'], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "Path 'build_wasm' does not exist" in done.stderr
