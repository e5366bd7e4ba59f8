# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Underlays and overlays of --wasm workspaces, as with /opt/ros/humble.

The demo's interfaces (and the middleware) are built in one workspace, the
demo's nodes in another that stands on it, by sourcing its setup.sh or by
--wasm-underlay. The overlay takes the middleware from the underlay, its
executables run, a native shell is not touched, and bad underlays are
refused with what to do.
"""

import json
import os
import shutil
import subprocess

from colcon_helpers import colcon
from colcon_helpers import REPO
from colcon_helpers import tool
import pytest


def _workspace(root, name, packages):
    ws = root / name
    for package in packages:
        shutil.copytree(REPO / 'demo' / 'src' / package, ws / 'src' / package)
    return ws


def _sourced(setup, command, *, cwd, env=None):
    """Run a command in sh after sourcing a setup.sh."""
    return subprocess.run(
        ['sh', '-c', f'. "{setup}" && {command}'], cwd=str(cwd), capture_output=True,
        text=True, env=dict(os.environ, **(env or {})), timeout=900)


@pytest.fixture(scope='module')
def underlay(tmp_path_factory):
    """Build the demo's interfaces and the middleware in their own workspace."""
    ws = _workspace(tmp_path_factory.mktemp('underlay'), 'core', ['demo_interfaces'])
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'demo_interfaces', 'wasm_cpp')
    return ws / 'install_wasm'


def test_setup_sh_sets_only_the_wasm_prefix_path(underlay, tmp_path):
    completed = _sourced(underlay / 'setup.sh', 'env', cwd=tmp_path, env={
        'CMAKE_PREFIX_PATH': '/opt/native', 'AMENT_PREFIX_PATH': '/opt/native'})
    env = dict(line.split('=', 1) for line in completed.stdout.splitlines() if '=' in line)
    assert env['COLCON_WASM_PREFIX_PATH'] == str(underlay)
    # a native build in the same shell sees nothing of WebAssembly
    assert env['CMAKE_PREFIX_PATH'] == '/opt/native'
    assert env['AMENT_PREFIX_PATH'] == '/opt/native'
    assert 'COLCON_PREFIX_PATH' not in env
    # colcon's own scripts are kept for --wasm overlays
    assert (underlay / '.colcon_wasm' / 'colcon' / 'local_setup.sh').is_file()
    marker = json.loads((underlay / '.colcon_wasm_install.json').read_text())
    assert marker['pthread'] is True and marker['underlays'] == []


@pytest.mark.parametrize('how', ['sourced', 'option'])
def test_overlay_builds_on_the_underlay_and_runs(underlay, tmp_path, how):
    ws = _workspace(tmp_path, 'overlay', ['demo_nodes'])
    command = f'"{tool("colcon")}" --log-base log build --wasm --event-handlers console_direct+'
    if how == 'sourced':
        completed = _sourced(underlay / 'setup.sh', command, cwd=ws,
                             env={'COLCON_HOME': str(ws / '.colcon_home')})
    else:
        completed = subprocess.run(
            ['sh', '-c', f'{command} --wasm-underlay "{underlay}"'], cwd=str(ws),
            capture_output=True, text=True, timeout=900,
            env=dict(os.environ, COLCON_HOME=str(ws / '.colcon_home')))
    output = completed.stdout + completed.stderr
    assert completed.returncode == 0, output[-5000:]
    install = ws / 'install_wasm'
    # the middleware and the interfaces come from the underlay
    built = sorted(p.name for p in install.iterdir() if (p / 'share').is_dir())
    assert built == ['demo_nodes'], built
    cache = (ws / 'build_wasm' / 'demo_nodes' / 'CMakeCache.txt').read_text()
    assert f'wasm_cpp_DIR:PATH={underlay}/wasm_cpp/' in cache
    assert f'wasm_js_DIR:PATH={underlay}/wasm_js/' in cache
    marker = json.loads((install / '.colcon_wasm_install.json').read_text())
    assert marker['underlays'] == [str(underlay)]
    # the overlay's executables run with the underlay's runtime, found
    # through the overlay's install space
    launched = subprocess.run(
        [tool('colcon-wasm'), 'launch', 'demo_nodes/talker', 'demo_nodes/listener',
         '--duration', '4'], cwd=str(ws), capture_output=True, text=True, timeout=120)
    assert 'I heard: [Hello World' in launched.stdout, launched.stdout + launched.stderr
    # sourcing the overlay's setup.sh chains the underlay, overlay first
    chained = _sourced(install / 'setup.sh', 'echo "$COLCON_WASM_PREFIX_PATH"', cwd=ws)
    assert chained.stdout.strip() == f'{install}:{underlay}'


def test_native_install_is_refused_as_an_underlay(tmp_path):
    native = tmp_path / 'native_install'
    (native / 'share' / 'rclcpp').mkdir(parents=True)
    (native / '.colcon_install_layout').write_text('isolated\n')
    ws = _workspace(tmp_path, 'overlay', ['demo_interfaces'])
    completed = colcon(ws, 'build', '--wasm', '--wasm-underlay', str(native), check=False)
    assert completed.returncode != 0
    assert f"the underlay '{native}' (--wasm-underlay) was not built with colcon build " \
        '--wasm' in completed.stdout
    assert 'Build that workspace with `colcon build --wasm`' in completed.stdout
    missing = tmp_path / 'nowhere'
    completed = colcon(ws, 'build', '--wasm', check=False,
                       env={'COLCON_WASM_PREFIX_PATH': str(missing)})
    assert f"the underlay '{missing}' (COLCON_WASM_PREFIX_PATH) does not exist" \
        in completed.stdout


def test_native_prefixes_are_dropped_with_a_warning(underlay, tmp_path):
    native = tmp_path / 'opt_ros'
    (native / 'share').mkdir(parents=True)
    ws = _workspace(tmp_path, 'overlay', ['demo_nodes'])
    completed = colcon(ws, 'build', '--wasm', '--wasm-underlay', str(underlay),
                       env={'AMENT_PREFIX_PATH': str(native),
                            'CMAKE_PREFIX_PATH': str(native)})
    assert 'Ignoring native prefixes for this --wasm build' in completed.stdout
    assert str(native) in completed.stdout


def test_moved_workspace_rebuilds_cleanly(tmp_path):
    ws = _workspace(tmp_path, 'first', ['demo_interfaces', 'demo_nodes'])
    colcon(ws, 'build', '--wasm')
    moved = tmp_path / 'second'
    shutil.move(str(ws), str(moved))
    completed = colcon(moved, 'build', '--wasm')
    assert 'moved from' in completed.stdout or 'Finished' in completed.stdout
    for package in ('wasm_js', 'wasm_cpp', 'demo_interfaces'):
        cache = (moved / 'build_wasm' / package / 'CMakeCache.txt').read_text()
        assert f'CMAKE_CACHEFILE_DIR:INTERNAL={moved}/build_wasm/{package}' in cache, package
    talker = moved / 'install_wasm' / 'demo_nodes' / 'lib' / 'demo_nodes' / 'talker.js'
    assert talker.is_file()
