# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Finding Emscripten: lookup order, version check, one-line errors."""

from pathlib import Path

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
