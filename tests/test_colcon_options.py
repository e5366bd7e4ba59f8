# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Every colcon option keeps working with `--wasm`."""

import json

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import node


def _cache_value(build_dir, name):
    for line in (build_dir / 'CMakeCache.txt').read_text().splitlines():
        if line.startswith(name + ':'):
            return line.split('=', 1)[1]
    return None


def _built(ws, base='build_wasm'):
    folder = ws / base
    return sorted(p.name for p in folder.iterdir()
                  if p.is_dir() and not p.name.startswith('.'))


def test_explicit_bases_win(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--build-base', 'wb', '--install-base',
           'wi', '--packages-select', 'calc_lib')
    assert (ws / 'wi' / 'calc_lib' / 'lib' / 'libcalc.a').is_file()
    assert (ws / 'wb' / 'calc_lib' / 'CMakeCache.txt').is_file()
    assert not (ws / 'build_wasm').exists()
    assert not (ws / 'install_wasm').exists()


def test_packages_up_to_and_select(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--packages-select', 'calc_lib')
    assert _built(ws) == ['calc_lib']
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app')
    assert _built(ws) == ['calc_app', 'calc_lib']


def test_merge_install(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--merge-install')
    prefix = ws / 'install_wasm'
    result = node(prefix / 'bin' / 'calc.js', 9, 3)
    assert result.stdout.strip() == 'result 3', result.stderr[-2000:]
    manifest = json.loads(
        (prefix / 'share' / 'calc_app' / 'colcon_wasm' /
         'manifest.json').read_text())
    assert [e['js'] for e in manifest['executables']] == [
        'bin/args_env.js', 'bin/calc.js']


def test_user_cmake_args_come_last(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--packages-select', 'calc_lib',
           '--cmake-args', '-DCMAKE_BUILD_TYPE=Debug', '-DBUILD_TESTING=ON')
    build = ws / 'build_wasm' / 'calc_lib'
    # colcon-wasm's defaults are Release and BUILD_TESTING=OFF
    assert _cache_value(build, 'CMAKE_BUILD_TYPE') == 'Debug'
    assert _cache_value(build, 'BUILD_TESTING') == 'ON'
    assert _cache_value(build, 'COLCON_WASM_PTHREAD') == 'ON'


def test_event_handlers_and_parallel_workers(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    output = colcon(ws, 'build', '--wasm', '--parallel-workers', '1',
                    '--event-handlers', 'console_direct+',
                    '--packages-up-to', 'calc_app').stdout
    assert 'Linking CXX executable calc.js' in output
    assert 'loading initial cache file' in output


def test_mixin(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    mixin = tmp_path / 'wasm.mixin'
    mixin.write_text(json.dumps({'build': {'lib-only': {
        'packages-select': ['calc_lib'],
        'cmake-args': ['-DCALC_FROM_MIXIN=yes']}}}))
    colcon(ws, 'build', '--wasm', '--mixin-files', str(mixin),
           '--mixin', 'lib-only')
    assert _built(ws) == ['calc_lib']
    assert _cache_value(ws / 'build_wasm' / 'calc_lib',
                        'CALC_FROM_MIXIN') == 'yes'


def test_defaults_file(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    defaults = tmp_path / 'defaults.yaml'
    defaults.write_text(
        'build:\n  wasm: true\n  packages-select: [calc_lib]\n')
    colcon(ws, 'build', env={'COLCON_DEFAULTS_FILE': str(defaults)})
    assert _built(ws) == ['calc_lib']
    assert not (ws / 'build').exists()
    # a build base from the defaults file is the user's choice: it is kept
    defaults.write_text(
        'build:\n  wasm: true\n  build-base: my_build\n'
        '  packages-select: [calc_lib]\n')
    colcon(ws, 'build', env={'COLCON_DEFAULTS_FILE': str(defaults)})
    assert (ws / 'my_build' / 'calc_lib' / 'CMakeCache.txt').is_file()


def test_debug_and_no_pthread_reconfigure(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app')
    bin_dir = ws / 'install_wasm' / 'calc_app' / 'bin'
    assert (bin_dir / 'calc.worker.js').is_file()
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app',
           '--wasm-no-pthread', '--wasm-debug')
    assert not (bin_dir / 'calc.worker.js').exists()
    manifest = json.loads(
        (ws / 'install_wasm' / 'calc_app' / 'share' / 'calc_app' /
         'colcon_wasm' / 'manifest.json').read_text())
    assert manifest['flags']['pthread'] is False
    assert manifest['flags']['debug'] is True
    assert all(not e['pthread'] for e in manifest['executables'])
    build = ws / 'build_wasm' / 'calc_app'
    assert _cache_value(build, 'CMAKE_BUILD_TYPE') == 'Debug'
    assert '-pthread' not in _cache_value(build, 'CMAKE_CXX_FLAGS')
    result = node(bin_dir / 'calc.js', 8, 0)
    assert result.returncode == 3, result.stderr[-2000:]
    assert 'caught DivisionByZero' in result.stdout


def test_pthread_pool_size_reconfigures_and_reaches_the_link(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    manifest_path = (ws / 'install_wasm' / 'calc_app' / 'share' /
                     'calc_app' / 'colcon_wasm' / 'manifest.json')
    glue = ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.js'
    build = ws / 'build_wasm' / 'calc_app'
    for size in ('2', '0'):
        colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app',
               '--wasm-pthread-pool-size', size)
        manifest = json.loads(manifest_path.read_text())
        assert manifest['flags']['pthread_pool_size'] == int(size)
        assert _cache_value(build, 'COLCON_WASM_PTHREAD_POOL_SIZE') == size
        link = (build / 'CMakeFiles' / 'calc.dir' / 'link.txt').read_text()
        assert f'-sPTHREAD_POOL_SIZE={size} ' in link
    result = node(glue, 8, 2)
    assert result.returncode == 0, result.stderr[-2000:]
    bad = colcon(ws, 'build', '--wasm', '--wasm-pthread-pool-size', '-1',
                 check=False)
    assert bad.returncode != 0
    assert "'-1' is not a pool size" in bad.stdout


def test_opt_level_reaches_every_compile_and_link(tmp_path):
    # CMake's Clang module appends " -O3" to a toolchain's Release flags:
    # the chosen level must be the only one on compile and link lines
    ws = copy_fixture('ws_basic', tmp_path)
    build = ws / 'build_wasm' / 'calc_app'
    flags = build / 'CMakeFiles' / 'calc.dir' / 'flags.make'
    link = build / 'CMakeFiles' / 'calc.dir' / 'link.txt'
    for level in ('2', 's'):
        colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app',
               '--wasm-opt-level', level)
        assert _cache_value(build, 'CMAKE_CXX_FLAGS_RELEASE') == \
            f'-O{level} -DNDEBUG'
        opts = [w for w in flags.read_text().split() if w.startswith('-O')]
        assert opts and set(opts) == {f'-O{level}'}, opts
        opts = [w for w in link.read_text().split() if w.startswith('-O')]
        assert opts and set(opts) == {f'-O{level}'}, opts


def test_link_opt_level_applies_to_links_only(tmp_path):
    """--wasm-link-opt-level 1 links at -O1 and still compiles at -O2."""
    ws = copy_fixture('ws_basic', tmp_path)
    build = ws / 'build_wasm' / 'calc_app'
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app',
           '--wasm-link-opt-level', '1')
    flags = (build / 'CMakeFiles' / 'calc.dir' / 'flags.make').read_text()
    link = (build / 'CMakeFiles' / 'calc.dir' / 'link.txt').read_text()
    assert {w for w in flags.split() if w.startswith('-O')} == {'-O2'}
    # CMake puts the compile flags on link lines too, the linker flags after
    # them: emcc's last -O decides how the link optimizes
    assert [w for w in link.split() if w.startswith('-O')][-1] == '-O1', link
    bad = colcon(ws, 'build', '--wasm', '--wasm-link-opt-level', '9',
                 check=False)
    assert bad.returncode != 0 and "invalid choice: '9'" in bad.stdout
