# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Recipe patches are applied to a copy of the source, all or nothing."""

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import is_elf
from colcon_helpers import node
from colcon_helpers import tree_digest


def test_patch_applies_to_a_copy(tmp_path):
    ws = copy_fixture('ws_patch', tmp_path)
    before = tree_digest(ws / 'src')
    args = ['build', '--wasm', '--wasm-recipe', 'recipe.yaml',
            '--packages-select', 'patched_hello']
    colcon(ws, *args)
    hello = ws / 'install_wasm' / 'patched_hello' / 'bin' / 'hello.js'
    result = node(hello)
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip() == 'hello from the patched copy'
    assert tree_digest(ws / 'src') == before
    copy = ws / 'build_wasm' / '.colcon_wasm' / 'source' / 'patched_hello'
    assert 'patched copy' in (copy / 'hello.cpp').read_text()
    # a second build keeps the copy (no re-copy, no re-link)
    wasm = hello.with_suffix('.wasm')
    mtime = (copy / 'hello.cpp').stat().st_mtime_ns, wasm.stat().st_mtime_ns
    colcon(ws, *args)
    assert ((copy / 'hello.cpp').stat().st_mtime_ns,
            wasm.stat().st_mtime_ns) == mtime
    # the native build uses the original source
    colcon(ws, 'build', '--packages-select', 'patched_hello')
    native = ws / 'install' / 'patched_hello' / 'bin' / 'hello'
    assert is_elf(native)
    assert tree_digest(ws / 'src') == before


def test_failing_patch_is_a_clear_error(tmp_path):
    ws = copy_fixture('ws_patch', tmp_path)
    before = tree_digest(ws / 'src')
    result = colcon(ws, 'build', '--wasm', '--wasm-recipe', 'recipe.yaml',
                    '--packages-select', 'bad_patch_pkg', check=False)
    assert result.returncode != 0
    assert ("package 'bad_patch_pkg': patch '0001-does-not-match.patch' "
            'hunk #1') in result.stdout
    assert 'main.cpp near line 1) does not apply' in result.stdout
    assert "the source has no line '  return 1;'" in result.stdout
    assert tree_digest(ws / 'src') == before
    source_copies = ws / 'build_wasm' / '.colcon_wasm' / 'source'
    assert not (source_copies / 'bad_patch_pkg').exists()
    assert not (source_copies / 'bad_patch_pkg.tmp').exists()
    assert not (ws / 'install_wasm' / 'bad_patch_pkg').exists()


def test_patch_added_later_rebuilds_from_the_copy(tmp_path):
    # a package first configured from src/ must switch to the patched copy
    # when a recipe later adds a patch (and back when it is removed)
    ws = copy_fixture('ws_patch', tmp_path)
    hello = ws / 'install_wasm' / 'patched_hello' / 'bin' / 'hello.js'
    colcon(ws, 'build', '--wasm', '--packages-select', 'patched_hello')
    assert node(hello).stdout.strip() == 'hello from the original source'
    colcon(ws, 'build', '--wasm', '--wasm-recipe', 'recipe.yaml',
           '--packages-select', 'patched_hello')
    assert node(hello).stdout.strip() == 'hello from the patched copy'
    colcon(ws, 'build', '--wasm', '--packages-select', 'patched_hello')
    assert node(hello).stdout.strip() == 'hello from the original source'
