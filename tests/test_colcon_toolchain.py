# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Finding Emscripten (lookup order, version check, one-line errors); the toolchain files."""

from pathlib import Path
import subprocess

from colcon_wasm import resources
from colcon_wasm import toolchain
from colcon_wasm.error import ColconWasmError
from colcon_wasm.toolchain import find_emscripten
import pytest


def _fake_root(folder, version, *, with_emcc=True):
    """Make a folder shaped like an Emscripten root (its version is read)."""
    folder.mkdir(parents=True)
    (folder / 'emcc.py').write_text('')
    (folder / 'emscripten-version.txt').write_text(f'"{version}"\n')
    if with_emcc:
        (folder / 'emcc').write_text('#!/bin/sh\nexit 1\n')
        (folder / 'emcc').chmod(0o755)
    return folder


@pytest.fixture
def no_debian(monkeypatch, tmp_path):
    """Pretend Debian's Emscripten is not installed."""
    monkeypatch.setattr(toolchain, 'DEBIAN_ROOT', tmp_path / 'no-debian')


def test_option_comes_first(tmp_path):
    root = _fake_root(tmp_path / 'emsdk' / 'upstream' / 'emscripten', '3.1.40')
    other = _fake_root(tmp_path / 'other', '3.1.30')
    found = find_emscripten(str(tmp_path / 'emsdk'),
                            env={'EMSDK': str(other), 'PATH': ''})
    assert found.root == root and found.source == '--wasm-emscripten'
    assert found.version == (3, 1, 40)
    # an emcc executable works too
    found = find_emscripten(str(root / 'emcc'), env={'PATH': ''})
    assert found.root == root and found.bin_dir == root


def test_emsdk_before_path(tmp_path):
    emsdk = tmp_path / 'emsdk'
    root = _fake_root(emsdk / 'upstream' / 'emscripten', '3.1.50')
    found = find_emscripten(env={'EMSDK': str(emsdk), 'PATH': '/usr/bin'})
    assert found.root == root and found.source == 'EMSDK'


def test_path_then_debian():
    if not Path('/usr/bin/emcc').exists():
        pytest.skip("Debian's emscripten is not installed")
    found = find_emscripten(env={'PATH': '/usr/bin'})
    assert found.source == 'emcc on PATH'
    assert found.root == Path('/usr/share/emscripten')
    assert found.bin_dir == Path('/usr/bin')
    found = find_emscripten(env={'PATH': ''})
    assert found.source == 'Debian'
    assert found.version >= toolchain.MINIMUM_VERSION


def test_nothing_found_is_one_line(no_debian):
    with pytest.raises(ColconWasmError) as info:
        find_emscripten(env={'PATH': ''})
    message = str(info.value)
    assert '\n' not in message
    assert message.startswith('no Emscripten found (looked for: EMSDK (not '
                              'set); emcc on PATH (not found); Debian')
    assert 'apt-get install emscripten' in message and 'emsdk' in message


def test_too_old(tmp_path, no_debian):
    _fake_root(tmp_path / 'old', '2.0.34')
    with pytest.raises(ColconWasmError, match=r'2\.0\.34 .* too old, need '
                       r'3\.1\.6 or newer'):
        find_emscripten(env={'EMSDK': str(tmp_path / 'old'), 'PATH': ''})


def test_bad_option_is_not_replaced(tmp_path):
    with pytest.raises(ColconWasmError, match='--wasm-emscripten'):
        find_emscripten(str(tmp_path / 'missing'), env={'PATH': '/usr/bin'})


def test_environment_for_debian():
    emscripten = toolchain.Emscripten(
        root=toolchain.DEBIAN_ROOT, bin_dir=Path('/usr/bin'),
        version=(3, 1, 6), source='Debian')
    changes = emscripten.environment({'PATH': '/bin'})
    assert changes['PATH'].split(':')[:2] == ['/usr/bin', '/bin']
    if toolchain.DEBIAN_NODE_PATH.is_dir():
        assert changes['NODE_PATH'] == str(toolchain.DEBIAN_NODE_PATH)
    assert emscripten.environment(
        {'PATH': '/usr/bin:/bin', 'NODE_PATH': '/usr/share/nodejs'}) == {}


def test_version_parsing():
    assert toolchain.parse_version('emcc (Emscripten) 3.1.6 ()') == (3, 1, 6)
    assert toolchain.parse_version('"3.1.45"') == (3, 1, 45)
    assert toolchain.parse_version('nothing') is None


def _configure(tmp_path, **variables):
    """Configure an empty C project with colcon-wasm's toolchain files, as CMake would."""
    source = tmp_path / 'src'
    source.mkdir(exist_ok=True)
    (source / 'CMakeLists.txt').write_text('cmake_minimum_required(VERSION 3.16)\nproject(p C)\n')
    emscripten = find_emscripten(None)
    defaults = {
        'COLCON_WASM_EMSCRIPTEN_ROOT': str(emscripten.root),
        'COLCON_WASM_EMSCRIPTEN_BIN': str(emscripten.bin_dir),
        'COLCON_WASM_PTHREAD': 'ON', 'COLCON_WASM_PTHREAD_POOL_SIZE': '4',
        'COLCON_WASM_DEBUG': 'OFF', 'COLCON_WASM_OPT_LEVEL': '2',
        'COLCON_WASM_LINK_OPT_LEVEL': '2'}
    defaults.update(variables)
    return subprocess.run(
        ['cmake', '-S', str(source), '-B', str(tmp_path / 'build')]
        + [f'-D{k}={v}' for k, v in defaults.items() if v is not None]
        + ['-C', str(resources.file('toolchains', 'wasm-ros-cache.cmake')),
           '-DCMAKE_TOOLCHAIN_FILE=' + str(resources.file('toolchains', 'wasm-ros.cmake'))],
        capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize('variable', [
    'COLCON_WASM_OPT_LEVEL', 'COLCON_WASM_LINK_OPT_LEVEL', 'COLCON_WASM_DEBUG',
    'COLCON_WASM_PTHREAD', 'COLCON_WASM_PTHREAD_POOL_SIZE'])
def test_toolchain_files_stop_when_a_setting_is_unset(tmp_path, variable):
    # no defaults in CMake: colcon_wasm/options.py holds them, and says so
    completed = _configure(tmp_path, **{variable: None})
    assert completed.returncode != 0
    message = ' '.join((completed.stdout + completed.stderr).split())
    assert f'colcon-wasm: {variable} is not set; colcon-wasm sets it' in message, message
    assert 'colcon_wasm/options.py' in message


def test_toolchain_files_take_the_settings_given(tmp_path):
    completed = _configure(tmp_path, COLCON_WASM_OPT_LEVEL='s', COLCON_WASM_LINK_OPT_LEVEL='1')
    assert completed.returncode == 0, completed.stdout + completed.stderr
    cache = (tmp_path / 'build' / 'CMakeCache.txt').read_text()
    assert 'CMAKE_C_FLAGS_RELEASE:STRING=-Os -DNDEBUG' in cache
    assert 'CMAKE_EXE_LINKER_FLAGS_RELEASE:STRING=-O1' in cache
    assert 'CMAKE_EXE_LINKER_FLAGS_DEBUG:STRING=-g -O0 -sASSERTIONS=2' in cache
