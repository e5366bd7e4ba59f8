# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`blasm` keeps the thesis' options on top of `colcon build --wasm`."""

import json
import os
from pathlib import Path
import subprocess

from colcon_helpers import copy_fixture
from colcon_helpers import node
from colcon_helpers import tool
from colcon_wasm.blasm import colcon_arguments
from colcon_wasm.blasm import create_parser
from colcon_wasm.blasm import install_base

REPO = Path(__file__).resolve().parents[1]


def blasm(workspace, *args, env=None):
    """Run the installed blasm console script."""
    env = dict(os.environ, COLCON_HOME=str(workspace / '.colcon_home'), **(env or {}))
    env.pop('COLCON_DEFAULTS_FILE', None)
    return subprocess.run(
        [tool('blasm')] + list(args), cwd=workspace, env=env,
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        timeout=900)


def test_help_lists_the_thesis_options(tmp_path):
    result = blasm(tmp_path, '-h')
    assert result.returncode == 0
    for option in ('-h', '-c', '-d', '-u PKG', '-s PKG', '-i', '-p', '-v'):
        assert option in result.stdout, option


def test_option_translation():
    options, extra = create_parser().parse_known_args(
        ['-u', 'calc_app', '-i', 'a b', '-v', '-d', '--', '--merge-install'])
    assert colcon_arguments(options, extra) == [
        'build', '--wasm', '--packages-up-to', 'calc_app',
        '--packages-ignore', 'a', 'b', '--event-handlers', 'console_direct+',
        '--wasm-debug', '--merge-install', '--cmake-args',
        '-DCMAKE_VERBOSE_MAKEFILE=ON']


def test_export_reads_the_install_base_colcon_gets():
    assert install_base(['--merge-install']) == 'install_wasm'
    assert install_base(['--install-base', 'elsewhere', '--merge-install']) == 'elsewhere'
    assert install_base(['--install-base=elsewhere']) == 'elsewhere'


def test_python_checks_for_pyodide(tmp_path):
    pyodide = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'
    missing = tmp_path / 'no-pyodide'
    result = blasm(tmp_path, '-p', env={'COLCON_WASM_PYODIDE': str(missing)})
    assert result.returncode == 2
    assert f"[BLASM]: -p: Python nodes need Pyodide 314.0.8, and '{missing}' " \
        '($COLCON_WASM_PYODIDE) lacks pyodide.mjs' in result.stdout
    assert 'npm install --prefix' in result.stdout
    if not (pyodide / 'pyodide.asm.wasm').is_file():
        # the rest needs tests/js's npm ci, which .ci/run does
        assert not os.environ.get('CI'), f'the npm package pyodide is missing in {pyodide}'
        return
    result = blasm(tmp_path, '-p', '-u', 'x', env={'COLCON_WASM_PYODIDE': str(pyodide)})
    assert f'[BLASM]: Python nodes run with Pyodide 314.0.8 from {pyodide}; colcon build ' \
        '--wasm packs the ament_python packages for it' in result.stdout
    assert 'is not a workspace directory' in result.stdout  # then it builds as without -p
    assert result.returncode == 1


def test_not_a_workspace(tmp_path):
    result = blasm(tmp_path, '-u', 'x')
    assert result.returncode == 1
    assert 'is not a workspace directory' in result.stdout


def test_debug_build_select_and_clean(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    result = blasm(ws, '-d', '-u', 'calc_app', '--parallel-workers', '1')
    assert result.returncode == 0, result.stdout[-3000:]
    assert '[BLASM]: colcon build --wasm --packages-up-to calc_app' in \
        result.stdout
    cache = (ws / 'build_wasm' / 'calc_app' / 'CMakeCache.txt').read_text()
    assert 'CMAKE_BUILD_TYPE:STRING=Debug' in cache
    assert 'CMAKE_VERBOSE_MAKEFILE:BOOL=ON' in cache
    calc = ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.js'
    assert 'caught DivisionByZero' in node(calc, 1, 0).stdout
    result = blasm(ws, '-s', 'calc_lib', '-v')
    assert result.returncode == 0, result.stdout[-3000:]
    assert 'Building CXX object' in result.stdout  # -s rebuilt from clean
    result = blasm(ws, '-c')
    assert result.returncode == 0
    for name in ('build_wasm', 'install_wasm', 'log'):
        assert not (ws / name).exists(), name
    assert (ws / 'src').is_dir()


def test_export_after_the_build(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    result = blasm(ws, '-h')
    assert '-e DIR' in result.stdout and "-r 'PKG/EXE [ARGS]'" in result.stdout
    result = blasm(ws, '-r', 'calc_app/calc')
    assert result.returncode == 2
    assert '[BLASM]: -r needs -e DIR' in result.stdout
    assert not (ws / 'install_wasm').exists()  # refused before building
    result = blasm(ws, '-u', 'calc_app', '-e', 'site', '-r', 'calc_app/calc 6 3',
                   '--parallel-workers', '1')
    assert result.returncode == 0, result.stdout[-3000:]
    assert '[BLASM]: colcon-wasm export site --install-base install_wasm ' \
        "'--run=calc_app/calc 6 3'" in result.stdout
    assert 'Exported 2 executable(s) of ' in result.stdout  # colcon-wasm export's own line
    site = ws / 'site'
    assert '<html' in (site / 'index.html').read_text()
    workspace = json.loads((site / 'workspace.json').read_text())
    assert workspace['static'] is True
    assert workspace['autorun'] == ['calc_app/calc 6 3']
    for name in ('calc.wasm', 'calc.js', 'calc.worker.js'):
        assert (site / 'ws' / 'calc_app' / 'bin' / name).read_bytes() == \
            (ws / 'install_wasm' / 'calc_app' / 'bin' / name).read_bytes(), name
    assert (site / 'coi_sw.js').is_file()
    # a failed export: its reason, blasm's line, nonzero, nothing written
    result = blasm(ws, '-u', 'calc_app', '-e', 'other', '-r', 'calc_app/nope')
    assert result.returncode == 1, result.stdout[-3000:]
    assert 'colcon-wasm export: --run calc_app/nope: there is no executable ' \
        "'calc_app/nope' in the install space" in result.stdout
    assert "[BLASM]: -e: exporting 'install_wasm' into 'other' failed (exit code 1" \
        in result.stdout
    assert not (ws / 'other').exists()
    # a failed build: no export
    result = blasm(ws, '-u', 'no_such_package', '-e', 'third')
    assert result.returncode == 1
    assert 'colcon-wasm export' not in result.stdout
    assert not (ws / 'third').exists()
