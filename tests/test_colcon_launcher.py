# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The compile launcher and the toolchain's build settings, with real emcc.

The launcher (colcon_wasm/compile_launcher.py) runs clang directly for
compile-only steps; these tests compare its object files byte for byte with
emcc's, check which commands it leaves to emcc, and check what the toolchain
puts into a package's CMake cache.
"""

import json
import os
from pathlib import Path
import shutil
import subprocess
import sys

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import FIXTURES
from colcon_wasm import compile_launcher
from colcon_wasm.compile_launcher import split_arguments
from colcon_wasm.compile_launcher import Unsupported
from colcon_wasm.toolchain import find_emscripten
import pytest

LAUNCHER = Path(compile_launcher.__file__).resolve()


@pytest.fixture(scope='module')
def emscripten():
    """Find the Emscripten the build uses, with its environment."""
    found = find_emscripten()
    env = dict(os.environ)
    env.update(found.environment())
    return found, env


def _launch(emscripten, cache, compiler, arguments, cwd, extra_env=None):
    found, env = emscripten
    env = dict(env, **(extra_env or {}))
    return subprocess.run(
        [sys.executable, '-I', '-S', str(LAUNCHER), '--cache', str(cache),
         '--root', str(found.root), '--', str(found.bin_dir / compiler)]
        + arguments, cwd=cwd, env=env, capture_output=True, text=True)


def _emcc(emscripten, compiler, arguments, cwd):
    found, env = emscripten
    return subprocess.run(
        [str(found.bin_dir / compiler)] + arguments, cwd=cwd, env=env,
        capture_output=True, text=True)


def test_arguments_are_split_for_the_probe():
    key, passed, source, output = split_arguments([
        '-DNDEBUG', '-I/a', '-isystem', '/b', '-fexceptions', '-pthread',
        '-O2', '-Wall', '-std=gnu++17', '-MD', '-MT', 'x.o', '-MF', 'x.o.d',
        '-o', 'x.o', '-c', '/src/x.cpp'])
    assert key == ['-fexceptions', '-pthread', '-O2', '-Wall',
                   '-std=gnu++17']
    assert passed == ['-DNDEBUG', '-I/a', '-isystem', '/b', '-MD', '-MT',
                      'x.o', '-MF', 'x.o.d']
    assert (source, output) == ('/src/x.cpp', 'x.o')


@pytest.mark.parametrize('arguments', [
    ['-o', 'x.js', 'x.cpp'],                       # a link
    ['-E', 'x.cpp'],                               # preprocessing only
    ['-c', 'x.S', '-o', 'x.o'],                    # assembly
    ['-c', 'a.cpp', 'b.cpp'],                      # two sources
    ['-c', 'x.cpp', '-o', 'x.o', '--js-library', 'l.js'],  # emcc option
    ['-c', 'x.cpp', '-o', 'x.o', '-flto'],         # bitcode
    ['-x', 'c++', '-c', 'x.h', '-o', 'x.o'],       # explicit language
])
def test_unusual_commands_are_left_to_emcc(arguments):
    with pytest.raises(Unsupported):
        split_arguments(arguments)


def test_response_files_are_read(tmp_path):
    rsp = tmp_path / 'includes.rsp'
    rsp.write_text('-I"/with space" -isystem /sys\n')
    key, passed, _, _ = split_arguments(
        [f'@{rsp}', '-O2', '-c', 'x.c', '-o', 'x.o'])
    assert passed == ['-I/with space', '-isystem', '/sys']
    assert key == ['-O2']


@pytest.mark.parametrize('compiler,source,flags', [
    ('em++', 'calc_lib/src/calc.cpp',
     ['-fexceptions', '-pthread', '-O2', '-std=gnu++14']),
    ('em++', 'calc_app/src/calc.cpp', ['-fexceptions', '-O3', '-g']),
    ('emcc', 'plain.c', ['-pthread', '-Os', '-fvisibility=hidden']),
    ('emcc', 'plain.c', ['-O2', '-sSTRICT']),
])
def test_same_object_as_emcc(emscripten, tmp_path, compiler, source, flags):
    src = tmp_path / 'src'
    shutil.copytree(FIXTURES / 'ws_basic' / 'src', src)
    (src / 'plain.c').write_text(
        '#include <stdio.h>\nint twice(int x) { return 2 * x; }\n'
        'void hello(void) { puts("hello"); }\n')
    common = ['-DNDEBUG', f'-I{src}/calc_lib/include', '-MD', '-MT', 'o',
              '-MF', 'o.d', '-c', str(src / source)]
    fast = _launch(emscripten, tmp_path / 'cache', compiler,
                   flags + common + ['-o', 'fast.o'], tmp_path)
    assert fast.returncode == 0, fast.stderr
    reference = _emcc(emscripten, compiler, flags + common + ['-o', 'emcc.o'],
                      tmp_path)
    assert reference.returncode == 0, reference.stderr
    assert (tmp_path / 'fast.o').read_bytes() == \
        (tmp_path / 'emcc.o').read_bytes()
    entries = [json.loads(p.read_text())
               for p in (tmp_path / 'cache').glob('*.json')]
    assert len(entries) == 1 and entries[0]['arguments'] == flags
    assert entries[0]['command'][0] != str(emscripten[0].bin_dir / compiler)
    # the second compile reuses the probe, and the verify mode agrees
    again = _launch(emscripten, tmp_path / 'cache', compiler,
                    flags + common + ['-o', 'again.o'], tmp_path,
                    {'COLCON_WASM_LAUNCHER_VERIFY': '1'})
    assert again.returncode == 0, again.stderr
    assert len(list((tmp_path / 'cache').glob('*.json'))) == 1


def test_compile_errors_come_from_clang(emscripten, tmp_path):
    (tmp_path / 'bad.cpp').write_text('int f() { return undeclared; }\n')
    result = _launch(emscripten, tmp_path / 'cache', 'em++',
                     ['-O2', '-c', 'bad.cpp', '-o', 'bad.o'], tmp_path)
    assert result.returncode != 0
    assert "bad.cpp:1:18: error: use of undeclared identifier 'undeclared'" \
        in result.stderr
    assert not (tmp_path / 'bad.o').exists()


def test_link_goes_through_emcc(emscripten, tmp_path):
    (tmp_path / 'main.c').write_text(
        '#include <stdio.h>\nint main(void) { puts("linked"); return 0; }\n')
    result = _launch(emscripten, tmp_path / 'cache', 'emcc',
                     ['-O1', 'main.c', '-o', 'main.js'], tmp_path)
    assert result.returncode == 0, result.stderr
    assert not (tmp_path / 'cache').exists()  # no probe for a link
    # plain Emscripten glue under Node 20 needs fetch() off
    run = subprocess.run(['node', '--no-experimental-fetch', 'main.js'],
                         cwd=tmp_path, capture_output=True, text=True)
    assert run.stdout.strip() == 'linked', run.stderr


def test_bad_usage_is_explained():
    result = subprocess.run(
        [sys.executable, str(LAUNCHER), '--bogus', 'x', '--', 'emcc'],
        capture_output=True, text=True)
    assert result.returncode != 0
    assert "unknown argument '--bogus'" in result.stderr
    assert 'usage: compile_launcher.py --cache DIR' in result.stderr


def _cache(build_folder):
    values = {}
    for line in (build_folder / 'CMakeCache.txt').read_text().splitlines():
        if ':' in line and '=' in line and not line.startswith(('//', '#')):
            name, _, value = line.partition('=')
            values[name.split(':')[0]] = value
    return values


@pytest.fixture(scope='module')
def configured(tmp_path_factory):
    """ws_basic built with --wasm-opt-level s and a user launcher for C."""
    workspace = copy_fixture('ws_basic', tmp_path_factory.mktemp('launcher'))
    colcon(workspace, 'build', '--wasm', '--wasm-opt-level', 's',
           '--packages-select', 'calc_lib',
           '--cmake-args', '-DCMAKE_C_COMPILER_LAUNCHER=env')
    return workspace / 'build_wasm' / 'calc_lib'


def test_opt_level_reaches_the_compile_flags(configured):
    cache = _cache(configured)
    # CMake's own "-O3 -DNDEBUG" must not override the chosen level
    assert cache['CMAKE_CXX_FLAGS_RELEASE'] == '-Os -DNDEBUG'
    assert cache['CMAKE_C_FLAGS_RELEASE'] == '-Os -DNDEBUG'
    assert cache['CMAKE_EXE_LINKER_FLAGS_RELEASE'] == '-Os'
    assert cache['CMAKE_CXX_FLAGS'].split().count('-fexceptions') == 1


def test_probes_run_once_per_build_folder(configured):
    cache = _cache(configured)
    assert cache['COLCON_WASM_PROBED_CLANG_VERSION'].count('.') == 2
    assert cache['COLCON_WASM_PROBED_EMSCRIPTEN_VERSION'] == \
        find_emscripten().version_string
    assert Path(cache['COLCON_WASM_PROBED_CACHE'], 'sysroot').is_dir()
    copy = configured / 'CMakeFiles' / 'colcon_wasm' / 'Emscripten.cmake'
    assert '-E echo "' + cache['COLCON_WASM_PROBED_CACHE'] + '"' in \
        copy.read_text()


def test_compile_rules_use_the_launcher(configured):
    rules = (configured / 'CMakeFiles' / 'calc.dir' /
             'build.make').read_text()
    assert f'-I -S {LAUNCHER} --cache' in rules
    assert str(configured.parent / '.colcon_wasm' / 'compile_launcher') in \
        rules
    # a launcher given by the user is kept
    assert _cache(configured)['CMAKE_C_COMPILER_LAUNCHER'] == 'env'
