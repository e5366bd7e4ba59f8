# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Rebuilds: an unchanged package is skipped, every change rebuilds what needs it.

The fixture workspace ws_basic (calc_lib, then calc_app which links it) plus
a pure Python host tool named by a recipe overlay, built with the real colcon
and Emscripten in one temporary workspace; the tests run in order.
"""

import itertools
import json
import os
from pathlib import Path

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import node
import pytest

HOST_TOOL_SETUP = (
    'from setuptools import setup\n'
    "setup(name='calc_tool', version='0.1.0', py_modules=['calc_tool'])\n")

_RUNS = itertools.count(1)


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """ws_basic plus a host tool, built once with --wasm."""
    workspace = copy_fixture('ws_basic', tmp_path_factory.mktemp('noop'))
    tool = workspace / 'src' / 'calc_tool'
    tool.mkdir()
    (tool / 'setup.py').write_text(HOST_TOOL_SETUP)
    (tool / 'calc_tool.py').write_text('"""A host tool."""\n')
    overlay = workspace / 'overlay.yaml'
    overlay.write_text('host-tools: [calc_tool]\n')
    build(workspace)
    return workspace


def build(workspace, *args, check=True):
    """Build with --wasm; return the packages built and the skipped ones."""
    # a log base of its own: two builds in one second would share colcon's
    # timestamped log folder
    log_base = workspace / 'log' / f'run{next(_RUNS)}'
    completed = colcon(
        workspace, '--log-base', str(log_base), 'build', '--wasm', '--wasm-recipe',
        str(workspace / 'overlay.yaml'), *args, check=check)
    log = (log_base / 'latest_build' / 'logger_all.log').read_text()
    skipped = {name for name in ('calc_lib', 'calc_app', 'calc_tool')
               if f"'{name}' is up to date" in log}
    return completed, skipped


def stamp(workspace, name):
    path = workspace / 'build_wasm' / name / 'colcon_wasm_stamp.json'
    return json.loads(path.read_text()) if path.is_file() else None


def test_first_build_writes_stamps(workspace):
    for name in ('calc_lib', 'calc_app', 'calc_tool'):
        data = stamp(workspace, name)
        assert data and len(data['digest']) == 64, name
    app = stamp(workspace, 'calc_app')
    assert app['inputs']['dependencies'] == {
        'calc_lib': stamp(workspace, 'calc_lib')['digest']}
    assert 'wasm.host.' in colcon(workspace, 'list', '--wasm', '--wasm-recipe',
                                  str(workspace / 'overlay.yaml')).stdout


def test_unchanged_workspace_is_skipped(workspace):
    wasm = workspace / 'install_wasm' / 'calc_app' / 'bin' / 'calc.wasm'
    manifest = workspace / 'install_wasm' / 'calc_app' / 'share' / \
        'calc_app' / 'colcon_wasm' / 'manifest.json'
    before = (wasm.stat().st_mtime_ns, manifest.stat().st_mtime_ns)
    _, skipped = build(workspace)
    assert skipped == {'calc_lib', 'calc_app', 'calc_tool'}
    assert (wasm.stat().st_mtime_ns, manifest.stat().st_mtime_ns) == before
    assert node(wasm.with_suffix('.js'), 6, 3).stdout.strip() == 'result 2'


def test_changed_source_rebuilds_the_dependents(workspace):
    source = workspace / 'src' / 'calc_lib' / 'src' / 'calc.cpp'
    os.utime(source, ns=(source.stat().st_atime_ns,
                         source.stat().st_mtime_ns + 10 ** 9))
    old_lib = stamp(workspace, 'calc_lib')['digest']
    _, skipped = build(workspace)
    assert skipped == {'calc_tool'}
    assert stamp(workspace, 'calc_lib')['digest'] != old_lib
    _, skipped = build(workspace)
    assert skipped == {'calc_lib', 'calc_app', 'calc_tool'}


def test_new_cmake_arguments_rebuild(workspace):
    _, skipped = build(workspace, '--packages-select', 'calc_app',
                       '--cmake-args', '-DCALC_UNUSED=1')
    assert 'calc_app' not in skipped
    _, skipped = build(workspace, '--packages-select', 'calc_app',
                       '--cmake-args', '-DCALC_UNUSED=1')
    assert skipped == {'calc_app'}
    _, skipped = build(workspace, '--packages-select', 'calc_app',
                       '--cmake-force-configure', '--cmake-args',
                       '-DCALC_UNUSED=1')
    assert not skipped


def test_missing_installed_file_is_reinstalled(workspace):
    wasm = workspace / 'install_wasm' / 'calc_app' / 'bin' / 'calc.wasm'
    js = wasm.with_suffix('.js')
    js.unlink()
    _, skipped = build(workspace)
    assert skipped == {'calc_lib', 'calc_tool'}
    assert js.is_file() and wasm.is_file()
    assert node(js, 6, 3).stdout.strip() == 'result 2'


def test_failed_build_leaves_no_stamp(workspace):
    source = workspace / 'src' / 'calc_app' / 'src' / 'calc.cpp'
    good = source.read_text()
    source.write_text(good + '\nint broken( {\n')
    try:
        completed, _ = build(workspace, check=False)
        assert completed.returncode != 0
        assert stamp(workspace, 'calc_app') is None
        assert stamp(workspace, 'calc_lib') is not None
    finally:
        source.write_text(good)
    _, skipped = build(workspace)
    assert skipped == {'calc_lib', 'calc_tool'}
    assert stamp(workspace, 'calc_app') is not None


def test_host_tool_change_rebuilds_it(workspace):
    module = workspace / 'src' / 'calc_tool' / 'calc_tool.py'
    module.write_text('"""A host tool, changed."""\n')
    _, skipped = build(workspace)
    assert skipped == {'calc_lib', 'calc_app'}
    installed = list(Path(workspace / 'install_wasm' / 'calc_tool').rglob(
        'calc_tool.py'))
    assert installed and 'changed' in installed[0].read_text()
