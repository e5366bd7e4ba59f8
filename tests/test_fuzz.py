# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Every wire format and reader, fuzzed for a bounded seeded count (docs/fuzzing.md).

JS targets (tests/fuzz/targets/*.mjs, run by tests/fuzz/run.mjs in Node.js:
a seeded mutation generator, outcome-guided) and Python targets
(tests/fuzz/py_targets.py, run by tests/fuzz/py_fuzz.py under atheris,
coverage-guided). Each gets its seed corpus (tests/fuzz_corpus/TARGET/),
then a count of mutated inputs through the entry point its server or reader
uses per message, with a check every few inputs that a well-formed input
still works on the same instance; then its regression inputs (the crashes
found so far, tests/fuzz_corpus/TARGET/regressions/) are replayed. Any
exception out of a handler, hang, or failed check fails the test. bench/fuzz
runs the same targets for minutes.
"""

import json
from pathlib import Path
import shutil
import subprocess
import sys
import time

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / 'fuzz'))

import fuzz_types  # noqa: E402, I100, I202
import py_targets  # noqa: E402

JS_TARGETS = {'cdr': 20000, 'rosbridge': 4000, 'foxglove': 3000, 'zenoh': 5000, 'page_yaml': 10000}
PY_TARGETS = {'relay': 4000, 'mcap': 1500, 'launch_xml': 3000, 'launch_yaml': 2000, 'params': 3000}
SEED = 1


@pytest.fixture(scope='module')
def types(tmp_path_factory):
    """Write the cdr_test_msgs type descriptions and schema texts for the JS targets."""
    return fuzz_types.write_types(tmp_path_factory.mktemp('fuzz-types'))


def _node():
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    return node


def _js(target, types, tmp_path, *args, timeout=120):
    types_path, schemas_path = types
    completed = subprocess.run(
        [_node(), str(HERE / 'fuzz' / 'run.mjs'), '--target', target, '--types', str(types_path),
         '--schemas', str(schemas_path), '--findings', str(tmp_path / 'findings'), *args],
        capture_output=True, text=True, timeout=timeout)
    lines = completed.stdout.strip().splitlines()
    assert lines, completed.stderr[-3000:]
    return completed.returncode, json.loads(lines[-1]), completed.stderr


def _report(result):
    return '\n\n'.join(f"{f['kind']} ({f.get('count', 1)}x), input {f['file']}:\n{f['message']}"
                       for f in result.get('findings', [])) or json.dumps(result)[:3000]


@pytest.mark.parametrize('target', sorted(JS_TARGETS))
def test_js_target(target, types, tmp_path):
    """A seeded count of inputs, then the regression inputs, with no finding."""
    code, result, stderr = _js(target, types, tmp_path, '--seed', str(SEED),
                               '--count', str(JS_TARGETS[target]))
    assert code == 0 and not result.get('error'), _report(result) + stderr[-2000:]
    seeds = len(py_targets.read_corpus(py_targets.corpus_dir(target)))
    assert result['inputs'] >= JS_TARGETS[target] + seeds, result
    assert result['checks'] >= JS_TARGETS[target] // 50, result
    regressions = py_targets.corpus_dir(target) / 'regressions'
    if regressions.is_dir():
        code, result, stderr = _js(target, types, tmp_path, '--replay', str(regressions))
        assert code == 0 and not result.get('error'), _report(result) + stderr[-2000:]
        assert result['inputs'] == len(list(regressions.iterdir())), result


def test_js_runner_reports_a_planted_crash(types, tmp_path):
    """The runner is no test that cannot fail: a target that throws on some inputs is reported."""
    code, result, _ = _js('planted', types, tmp_path, '--seed', '1', '--count', '3000',
                          '--corpus', str(py_targets.corpus_dir('page_yaml')))
    assert code == 1, result
    kinds = {f['kind'] for f in result['findings']}
    assert {'exception', 'state'} <= kinds, result
    assert all(Path(f['file']).is_file() for f in result['findings'])


def _atheris():
    try:
        import atheris  # noqa: F401
    except ImportError:
        return False
    return True


@pytest.mark.parametrize('target', sorted(PY_TARGETS))
def test_python_target(target, tmp_path):
    """Coverage-guided: a seeded count of atheris inputs with no finding."""
    if not _atheris():
        import os
        assert not os.environ.get('CI'), 'atheris is missing: .ci/run installs the test extras'
        pytest.skip("atheris is not installed: pip install -e '.[test]'")
    completed = subprocess.run(
        [sys.executable, str(HERE / 'fuzz' / 'py_fuzz.py'), target, '--seed', str(SEED),
         '--runs', str(PY_TARGETS[target]), '--findings', str(tmp_path / 'findings')],
        capture_output=True, text=True, timeout=300)
    result = json.loads(completed.stdout.strip().splitlines()[-1])
    assert completed.returncode == 0, _report(result)
    assert result['inputs'] >= PY_TARGETS[target], result
    assert result['coverage'] and result['coverage']['edges'] > 20, result


@pytest.mark.parametrize('target', sorted(PY_TARGETS))
def test_python_regressions(target):
    """Every crash found so far: each input, in order, on one instance, then the check."""
    regressions = py_targets.corpus_dir(target) / 'regressions'
    files = sorted(regressions.iterdir()) if regressions.is_dir() else []
    instance = py_targets.make(target)
    try:
        instance.check()
        for path in files:
            started = time.monotonic()
            instance.one(path.read_bytes())
            assert time.monotonic() - started < 10, f'{path.name} took too long'
            instance.check()
    finally:
        instance.close()


def test_python_check_fails_on_a_broken_instance():
    """The checks can fail: a relay whose observer left does not pass."""
    instance = py_targets.make('relay')
    try:
        instance.relay.receive(instance.observer, json.dumps(
            {'op': 'unsubscribe', 'topic': instance.CHECK_TOPIC}), False)
        with pytest.raises(py_targets.Finding):
            instance.check()
    finally:
        instance.close()


def test_seed_corpora_are_small():
    """Each target's seed corpus: a few KB of the project's own captured traffic."""
    for target in list(JS_TARGETS) + list(PY_TARGETS):
        seeds = py_targets.read_corpus(py_targets.corpus_dir(target))
        assert seeds, f'no seed corpus for {target}: capture it (docs/fuzzing.md)'
        assert sum(len(s) for s in seeds) < 12000, target


def test_native_cdr_reader(tmp_path):
    """rmw_wasm_cpp's CDR reader built natively with ASan and UBSan, a seeded count of inputs."""
    compiler = shutil.which('g++')
    if compiler is None:
        import os
        assert not os.environ.get('CI'), 'g++ is missing: .ci/run installs it'
        pytest.skip('g++ is needed (apt-get install g++)')
    driver = tmp_path / 'cdr_reader_driver'
    built = subprocess.run(
        [compiler, '-std=c++17', '-O1', '-g', '-fsanitize=address,undefined',
         '-fno-sanitize-recover=all',
         f"-I{HERE.parent / 'packages' / 'rmw_wasm_cpp' / 'src' / 'detail'}",
         str(HERE / 'fuzz' / 'cdr_reader_driver.cpp'), '-o', str(driver)],
        capture_output=True, text=True, timeout=300)
    assert built.returncode == 0, built.stderr[-3000:]
    seeds = []
    for i, data in enumerate(py_targets.read_corpus(py_targets.corpus_dir('cdr'))):
        path = tmp_path / f'seed-{i}'
        path.write_bytes(data[1:])  # the target's first byte names the JS type
        seeds.append(str(path))
    completed = subprocess.run([str(driver), str(SEED), '30000', *seeds],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stdout[-3000:] + completed.stderr[-3000:]
    assert completed.stdout.startswith('ok 30000 '), completed.stdout
