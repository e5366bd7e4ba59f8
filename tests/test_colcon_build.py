# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon build --wasm` on the fixture workspace, with the real toolchain.

One build of `tests/fixtures/ws_basic` (copied to a temporary folder) is
shared by the tests of this module: a plain CMake library used by an
executable of another package (an exception crosses the boundary), an
executable reading argv and environment, and a DDS vendor stand-in that the
recipe must skip.
"""

import json
from pathlib import Path

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import is_elf
from colcon_helpers import node
from colcon_helpers import tree_digest
import pytest


@pytest.fixture(scope='module')
def basic(tmp_path_factory):
    """Build ws_basic with --wasm, then natively; return the workspace."""
    workspace = copy_fixture('ws_basic', tmp_path_factory.mktemp('basic'))
    before = tree_digest(workspace / 'src')
    wasm = colcon(workspace, 'build', '--wasm')
    native = colcon(workspace, 'build')
    return {
        'ws': workspace, 'src_before': before, 'wasm_output': wasm.stdout,
        'native_output': native.stdout}


def test_exception_crosses_package_boundary(basic):
    calc = basic['ws'] / 'install_wasm' / 'calc_app' / 'bin' / 'calc.js'
    result = node(calc, 7, 0)
    assert result.returncode == 3, result.stderr[-2000:]
    assert 'caught DivisionByZero: division of 7 by zero (dividend 7)' in \
        result.stdout
    result = node(calc, 7, 2)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip() == 'result 3'


def test_argv_and_environment(basic):
    exe = basic['ws'] / 'install_wasm' / 'calc_app' / 'bin' / 'args_env.js'
    result = node(exe, 'one', 'two words', env={'CALC_GREETING': 'hello'})
    assert result.returncode == 2, result.stderr[-2000:]
    assert result.stdout.splitlines() == [
        'arg[1]=one', 'arg[2]=two words', 'CALC_GREETING=hello']


def test_companions_installed_beside_js(basic):
    bin_dir = basic['ws'] / 'install_wasm' / 'calc_app' / 'bin'
    for name in ('calc', 'args_env'):
        assert (bin_dir / f'{name}.js').is_file()
        assert (bin_dir / f'{name}.wasm').read_bytes()[:4] == b'\0asm'
        assert (bin_dir / f'{name}.worker.js').is_file()


def test_dds_vendor_stand_in_is_skipped(basic):
    ws = basic['ws']
    assert not (ws / 'install_wasm' / 'fastcdr').exists()
    assert not (ws / 'build_wasm' / 'fastcdr').exists()
    # the native build still has it
    assert (ws / 'install' / 'fastcdr' / 'share' / 'fastcdr' /
            'fastcdr_native.txt').is_file()
    listed = colcon(ws, 'list', '--wasm').stdout
    assert 'fastcdr' not in listed
    assert 'calc_app' in listed and 'wasm.cmake' in listed


def test_src_is_byte_identical(basic):
    assert tree_digest(basic['ws'] / 'src') == basic['src_before']


def test_native_build_still_native(basic):
    ws = basic['ws']
    assert is_elf(ws / 'install' / 'calc_app' / 'bin' / 'calc')
    assert not list((ws / 'install').rglob('*.wasm'))
    assert not list((ws / 'build').rglob('*.wasm'))
    # and the wasm build did not touch the native bases' contents
    assert (ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.wasm').is_file()


def test_manifest(basic):
    prefix = basic['ws'] / 'install_wasm' / 'calc_app'
    manifest = json.loads(
        (prefix / 'share' / 'calc_app' / 'colcon_wasm' /
         'manifest.json').read_text())
    assert manifest['schema'] == 1
    assert manifest['package'] == 'calc_app'
    assert manifest['recipe']['name'] == 'humble'
    assert manifest['emscripten']['version']
    assert manifest['flags']['pthread'] is True
    assert manifest['flags']['debug'] is False
    assert manifest['flags']['opt'] == '2'
    assert any(a.startswith('-DCMAKE_TOOLCHAIN_FILE=')
               for a in manifest['flags']['cmake_args'])
    names = [e['name'] for e in manifest['executables']]
    assert names == ['args_env', 'calc']
    import gzip
    import hashlib
    for entry in manifest['executables']:
        assert entry['js'] == f'bin/{entry["name"]}.js'
        assert entry['pthread'] is True
        assert entry['uses_bus'] is False
        roles = {f['role'] for f in entry['files']}
        assert roles == {'js', 'wasm', 'worker'}
        for file_entry in entry['files']:
            data = (prefix / file_entry['path']).read_bytes()
            assert file_entry['size'] == len(data)
            assert file_entry['sha256'] == hashlib.sha256(data).hexdigest()
            assert 0 < file_entry['gzip_size'] == len(
                gzip.compress(data, compresslevel=9, mtime=0))
    # a library package has a manifest without executables
    lib_manifest = json.loads(
        (basic['ws'] / 'install_wasm' / 'calc_lib' / 'share' / 'calc_lib' /
         'colcon_wasm' / 'manifest.json').read_text())
    assert lib_manifest['executables'] == []


def test_rebuild_injects_once(basic):
    ws = basic['ws']
    glue = ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.js'
    wasm = ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.wasm'
    wasm_mtime = wasm.stat().st_mtime_ns
    colcon(ws, 'build', '--wasm', '--packages-select', 'calc_app')
    text = glue.read_text()
    for fragment in ('00-node-fetch', '10-startup', '20-log-exit'):
        assert text.count(f'/*colcon-wasm:begin {fragment}*/') == 1
    assert wasm.stat().st_mtime_ns == wasm_mtime
    assert node(glue, 1, 1).stdout.strip() == 'result 1'


def test_packages_skip_is_logged_in_colcon_log(basic):
    log = (basic['ws'] / 'log' / 'latest_build' /
           'logger_all.log')
    text = log.read_text()
    # the latest build is the native one; find the wasm build's log instead
    logs = sorted((basic['ws'] / 'log').glob('build_*/logger_all.log'))
    wasm_logs = [p.read_text() for p in logs if '--wasm' in p.read_text()]
    assert wasm_logs, text[:200]
    assert "Skipping 'fastcdr' for --wasm: Fast DDS serialization library" \
        in wasm_logs[0]


def test_wasm_bases_are_separate(basic):
    ws = basic['ws']
    for base in ('build_wasm', 'install_wasm', 'build', 'install'):
        assert (ws / base / 'COLCON_IGNORE').is_file(), base
    assert not (Path(ws) / 'build' / 'calc_app' / 'calc.wasm').exists()
