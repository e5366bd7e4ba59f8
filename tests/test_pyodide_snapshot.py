# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes start from a snapshot of a started Pyodide (python/pyodide_snapshot.mjs).

The first Python node of a host has the snapshot made; every node then
starts from it, with its own argv and environment, and in Node.js the
snapshot is kept in COLCON_WASM_CACHE for the next host. A snapshot that
does not load costs a warning and a fresh start; the bad copy is replaced.
Real Pyodide (tests/js), a real Runtime; no build is needed.
"""

import json
import os
from pathlib import Path
import subprocess

import pytest

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / 'packages' / 'wasm_js' / 'src'
PYODIDE = HERE / 'js' / 'node_modules' / 'pyodide'
SCRIPT = HERE / 'data' / 'pyodide' / 'snapshot_node.py'


@pytest.fixture(autouse=True)
def pyodide():
    if not (PYODIDE / 'pyodide.asm.wasm').is_file():
        pytest.skip('the npm package pyodide is missing: run `npm ci` in tests/js')


def run_nodes(cache, count, *option, snapshot_env=None):
    """Run the check script's nodes on one host; return one report per node."""
    env = dict(os.environ, COLCON_WASM_CACHE=str(cache))
    env.pop('COLCON_WASM_PYODIDE_SNAPSHOT', None)
    if snapshot_env is not None:
        env['COLCON_WASM_PYODIDE_SNAPSHOT'] = snapshot_env
    done = subprocess.run(['node', str(HERE / 'js' / 'pyodide_snapshot_check.mjs'), str(SRC),
                           str(PYODIDE), str(SCRIPT), str(count), *option],
                          capture_output=True, text=True, timeout=240, env=env)
    assert done.returncode == 0, done.stdout + done.stderr
    return [json.loads(line) for line in done.stdout.splitlines()]


def kept(cache):
    return sorted((cache / 'pyodide-snapshots').glob('*.snapshot'))


def said(report, i):
    return f"argv ['arg{i}'] index {i} heard ['through the bus']"


def test_nodes_start_from_one_snapshot_with_their_own_arguments(tmp_path):
    reports = run_nodes(tmp_path, 3)
    for i, report in enumerate(reports):
        assert report['code'] == 0 and report['snapshot'], report
        assert said(report, i) in report['lines'], report
    # the first node starts its own worker; each next one takes the warm Python worker that
    # the runtime loaded meanwhile (python_spares.mjs), with its own argv and environment
    assert [r['warm'] for r in reports] == [False, True, True], reports
    files = kept(tmp_path)
    assert len(files) == 1 and files[0].stat().st_size > 1 << 20, files
    # the next host starts from the kept copy: it is not written again
    before = files[0].stat().st_mtime_ns
    report, = run_nodes(tmp_path, 1)
    assert report['snapshot'] and said(report, 0) in report['lines'], report
    assert kept(tmp_path) == files and files[0].stat().st_mtime_ns == before


def test_a_bad_snapshot_costs_a_warning_and_is_replaced(tmp_path):
    run_nodes(tmp_path, 1)
    file, = kept(tmp_path)
    good_size = file.stat().st_size
    file.write_bytes(file.read_bytes()[:1 << 20])  # cut short, as by a full disk
    first, second = run_nodes(tmp_path, 2)
    assert first['code'] == 0 and not first['snapshot'], first
    assert said(first, 0) in first['lines'], first
    assert any('the Pyodide snapshot does not load' in t and 'starting Pyodide anew' in t
               for t in first['lines']), first
    # the next node had a new snapshot made, and it is kept whole
    assert second['code'] == 0 and second['snapshot'] and said(second, 1) in second['lines']
    assert kept(tmp_path)[0].stat().st_size == good_size


def test_snapshots_can_be_turned_off(tmp_path):
    report, = run_nodes(tmp_path, 1, snapshot_env='0')
    assert report['code'] == 0 and not report['snapshot'] and said(report, 0) in report['lines']
    # without snapshots there is no warm Python worker either: every node starts cold
    reports = run_nodes(tmp_path, 2, 'snapshot=false')
    for i, report in enumerate(reports):
        assert report['code'] == 0 and not report['snapshot'] and not report['warm'], report
        assert said(report, i) in report['lines'], report
    assert not kept(tmp_path)


def test_an_unwritable_cache_costs_a_warning_not_the_node(tmp_path):
    (tmp_path / 'pyodide-snapshots').write_text('a file where the folder would be')
    first, second = run_nodes(tmp_path, 2)
    assert first['snapshot'] and said(first, 0) in first['lines'], first
    assert any('cannot keep the Pyodide snapshot' in t and 'COLCON_WASM_CACHE' in t
               for t in first['lines']), first
    # the host still shares the snapshot it made
    assert second['snapshot'] and said(second, 1) in second['lines'], second
