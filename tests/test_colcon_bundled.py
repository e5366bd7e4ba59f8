# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Bundled packages (colcon-wasm's `packages/`) join `--wasm` builds.

The real colcon runs in a subprocess whose bundled-package folder is the
fixture `tests/fixtures/bundled` (the shipped `packages/` holds the
middleware, which other tests build).
"""

import os
from pathlib import Path
import subprocess
import sys

from colcon_helpers import copy_fixture
from colcon_helpers import FIXTURES
import pytest

_RUNNER = (
    'import sys\n'
    'from pathlib import Path\n'
    'import colcon_wasm.package_discovery.bundled as bundled\n'
    'bundled.bundled_package_paths = lambda: [Path(sys.argv[1])]\n'
    'from colcon_core.command import main\n'
    'sys.exit(main(argv=sys.argv[2:]))\n')


def colcon_with_bundled(workspace, *args):
    """Run colcon with tests/fixtures/bundled/fake_bus as bundled package."""
    env = dict(os.environ, COLCON_HOME=str(Path(workspace) / '.colcon_home'))
    env.pop('COLCON_DEFAULTS_FILE', None)
    completed = subprocess.run(
        [sys.executable, '-c', _RUNNER, str(FIXTURES / 'bundled' / 'fake_bus'),
         '--log-base', 'log'] + list(args),
        cwd=workspace, env=env, stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT, text=True, timeout=600)
    assert completed.returncode == 0, completed.stdout[-4000:]
    return completed.stdout


def _names(output):
    return sorted(line.split()[0] for line in output.splitlines() if line)


@pytest.mark.parametrize('where', [[], ['--base-paths', 'src'],
                                   ['--paths', 'src/*']])
def test_bundled_package_joins_when_needed(tmp_path, where):
    ws = copy_fixture('ws_bundled', tmp_path)
    assert _names(colcon_with_bundled(ws, 'list', '--wasm', *where)) == [
        'bus_user', 'fake_bus', 'plain_tool']
    # without --wasm the bundled package is not part of the workspace
    assert _names(colcon_with_bundled(ws, 'list', *where)) == [
        'bus_user', 'plain_tool']


def test_bundled_package_left_out_when_unused(tmp_path):
    ws = copy_fixture('ws_bundled', tmp_path)
    output = colcon_with_bundled(
        ws, 'list', '--wasm', '--packages-select', 'plain_tool')
    assert _names(output) == ['plain_tool']
    # selecting only bundled packages builds them
    output = colcon_with_bundled(
        ws, 'list', '--wasm', '--packages-select', 'fake_bus')
    assert _names(output) == ['fake_bus']


def test_workspace_copy_wins(tmp_path):
    ws = copy_fixture('ws_bundled_copy', tmp_path)
    listed = colcon_with_bundled(ws, 'list', '--wasm', '--paths', 'src/*')
    assert 'src/fake_bus' in listed
    assert str(FIXTURES / 'bundled') not in listed
    colcon_with_bundled(ws, 'build', '--wasm', '--packages-up-to', 'bus_user')
    origin = ws / 'install_wasm' / 'fake_bus' / 'share' / 'fake_bus' / \
        'origin.txt'
    assert origin.read_text() == 'workspace copy\n'
    log = (ws / 'log' / 'latest_build' / 'logger_all.log').read_text()
    assert "Using the workspace copy of 'fake_bus'" in log


def test_bundled_package_is_built(tmp_path):
    ws = copy_fixture('ws_bundled', tmp_path)
    colcon_with_bundled(ws, 'build', '--wasm', '--packages-up-to', 'bus_user')
    origin = ws / 'install_wasm' / 'fake_bus' / 'share' / 'fake_bus' / \
        'origin.txt'
    assert origin.read_text() == 'bundled\n'
    assert (ws / 'install_wasm' / 'bus_user').is_dir()


def test_recipe_depends_reaches_packages_up_to(tmp_path):
    ws = copy_fixture('ws_bundled', tmp_path)
    overlay = tmp_path / 'edges.yaml'
    overlay.write_text('packages:\n  plain_tool:\n    depends: [bus_user]\n')
    assert _names(colcon_with_bundled(
        ws, 'list', '--wasm', '--packages-up-to', 'plain_tool')) == [
        'plain_tool']
    output = colcon_with_bundled(
        ws, 'list', '--wasm', '--wasm-recipe', str(overlay),
        '--packages-up-to', 'plain_tool', '--topological-order')
    # the recipe edge pulls bus_user (and the bundled package it needs)
    # in, before plain_tool
    assert [line.split()[0] for line in output.splitlines()] == [
        'fake_bus', 'bus_user', 'plain_tool']
