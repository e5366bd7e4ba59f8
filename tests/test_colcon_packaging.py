# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""A wheel installed into a fresh venv finds its data and builds."""

from pathlib import Path
import shutil
import subprocess
import sys
import zipfile

from colcon_helpers import copy_fixture
from colcon_helpers import node
from colcon_helpers import REPO
import pytest

DATA_FILES = (
    'colcon_wasm/_data/recipes/humble.yaml',
    'colcon_wasm/_data/recipes/humble.repos',
    'colcon_wasm/_data/recipes/schema.md',
    'colcon_wasm/_data/toolchains/wasm-ros.cmake',
    'colcon_wasm/_data/toolchains/wasm-ros-cache.cmake',
    'colcon_wasm/_data/toolchains/project/libyaml_vendor.cmake',
    'colcon_wasm/_data/patches/rcutils/'
    '0001-strerror_r-xsi-under-emscripten.patch',
    'colcon_wasm/_data/templates/glue/00-node-fetch.j2',
    'colcon_wasm/_data/packages/README.md',
    'colcon_wasm/_data/packages/wasm_js/src/python/rclpy/__init__.py',
)


@pytest.fixture(scope='module')
def wheel_venv(tmp_path_factory):
    """Build a wheel from a clean copy and install it into a fresh venv."""
    root = tmp_path_factory.mktemp('wheel')
    source = root / 'source'
    shutil.copytree(REPO, source, ignore=shutil.ignore_patterns(
        '.git', '.venv', 'build', 'install', 'log', 'build_wasm',
        'install_wasm', '*.egg-info', '__pycache__', 'node_modules',
        'artifacts', '.pytest_cache'))
    subprocess.run(
        [sys.executable, '-m', 'pip', 'wheel', '--no-deps',
         '--no-build-isolation', '-w', str(root / 'dist'), str(source)],
        check=True, capture_output=True, text=True)
    wheel = next((root / 'dist').glob('colcon_wasm-*.whl'))
    venv = root / 'venv'
    # the fresh venv takes colcon & co. from the interpreter running the
    # tests: only colcon-wasm itself comes from the wheel
    subprocess.run([sys.executable, '-m', 'venv', '--system-site-packages',
                    str(venv)], check=True)
    for path in Path(sys.prefix).glob('lib/python3*/site-packages'):
        (venv / 'lib' / path.parent.name / 'site-packages' /
         'parent.pth').write_text(str(path) + '\n')
    subprocess.run([str(venv / 'bin' / 'pip'), 'install', '--no-deps',
                    '--no-index', str(wheel)], check=True,
                   capture_output=True, text=True)
    return {'wheel': wheel, 'venv': venv}


def test_wheel_holds_the_data(wheel_venv):
    names = set(zipfile.ZipFile(wheel_venv['wheel']).namelist())
    for name in DATA_FILES:
        assert name in names, name
    entry_points = zipfile.ZipFile(wheel_venv['wheel']).read(
        next(n for n in names if n.endswith('entry_points.txt'))).decode()
    for group in ('colcon_core.argument_parser', 'colcon_core.task.build',
                  'colcon_core.package_selection',
                  'colcon_core.package_discovery', 'colcon_wasm.cli'):
        assert f'[{group}]' in entry_points, group


def test_installed_package_finds_its_data(wheel_venv):
    venv = wheel_venv['venv']
    result = subprocess.run(
        [str(venv / 'bin' / 'python'), '-c',
         'import colcon_wasm, colcon_wasm.resources as r\n'
         'print(colcon_wasm.__file__)\n'
         'for n in r.DATA_NAMES: print(r.path(n))'],
        capture_output=True, text=True, check=True, cwd='/')
    lines = result.stdout.splitlines()
    assert lines[0].startswith(str(venv)), lines
    for line in lines[1:]:
        assert line.startswith(str(venv)) and '_data' in line, line
        assert Path(line).is_dir(), line


def test_installed_colcon_builds(wheel_venv, tmp_path):
    venv = wheel_venv['venv']
    ws = copy_fixture('ws_basic', tmp_path)
    completed = subprocess.run(
        [str(venv / 'bin' / 'python'), '-c',
         'import sys; from colcon_core.command import main; '
         'sys.exit(main())', '--log-base', 'log', 'build', '--wasm',
         '--packages-up-to', 'calc_app'], cwd=ws, capture_output=True,
        text=True, env={'PATH': '/usr/bin:/bin', 'HOME': str(tmp_path),
                        'COLCON_HOME': str(tmp_path / '.colcon')})
    assert completed.returncode == 0, completed.stdout[-4000:]
    cache = (ws / 'build_wasm' / 'calc_app' / 'CMakeCache.txt').read_text()
    assert f'CMAKE_TOOLCHAIN_FILE:FILEPATH={venv}' in cache or \
        f'CMAKE_TOOLCHAIN_FILE:UNINITIALIZED={venv}' in cache
    result = node(ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.js', 6, 3)
    assert result.stdout.strip() == 'result 2'
