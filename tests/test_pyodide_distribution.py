# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes import what Pyodide's distribution ships (python/distribution.mjs).

A package of a Pyodide folder's pyodide-lock.json is loaded from that folder
when its wheel is there; otherwise the import names the package, its wheel
and the folder. The test builds its own wheel, and a Pyodide folder (the
npm package's files, linked, with a lock file that lists the wheel), so
nothing is downloaded.
"""

import hashlib
import json
import os
from pathlib import Path
import sys
import zipfile

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from launch_until import run_until  # noqa: E402

PYODIDE = Path(__file__).resolve().parent / 'js' / 'node_modules' / 'pyodide'
WHEEL = 'wasm_probe_pkg-1.0-py3-none-any.whl'


def _wheel(path):
    """Write a pure-Python wheel of the module ``wasm_probe_pkg``."""
    files = {
        'wasm_probe_pkg/__init__.py': "VALUE = 'from a wheel of the test'\n",
        'wasm_probe_pkg-1.0.dist-info/METADATA':
            'Metadata-Version: 2.1\nName: wasm-probe-pkg\nVersion: 1.0\n',
        'wasm_probe_pkg-1.0.dist-info/WHEEL':
            'Wheel-Version: 1.0\nGenerator: colcon-wasm tests\nRoot-Is-Purelib: true\n'
            'Tag: py3-none-any\n',
    }
    record = ''.join(f'{name},,\n' for name in files) + 'wasm_probe_pkg-1.0.dist-info/RECORD,,\n'
    files['wasm_probe_pkg-1.0.dist-info/RECORD'] = record
    with zipfile.ZipFile(path, 'w') as archive:
        for name, text in files.items():
            archive.writestr(name, text)
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _pyodide_with_the_wheel(folder):
    """Make a Pyodide folder: the npm package's files linked, the wheel and its lock entry."""
    folder.mkdir()
    for entry in PYODIDE.iterdir():
        if entry.name != 'pyodide-lock.json':
            (folder / entry.name).symlink_to(entry)
    lock = json.loads((PYODIDE / 'pyodide-lock.json').read_text())
    lock['packages']['wasm-probe-pkg'] = {
        'depends': [], 'file_name': WHEEL, 'imports': ['wasm_probe_pkg'], 'install_dir': 'site',
        'name': 'wasm-probe-pkg', 'package_type': 'package',
        'sha256': _wheel(folder / WHEEL), 'tool': {}, 'unvendored_tests': False,
        'version': '1.0'}
    (folder / 'pyodide-lock.json').write_text(json.dumps(lock))
    return folder


def _run(install, script, pyodide):
    command = [demo_build.venv_tool('colcon-wasm'), 'run', '--install-base', install,
               '--python', script, '--pyodide', pyodide]
    return run_until(command, timeout=240)


@pytest.fixture(scope='module')
def install():
    if not (PYODIDE / 'pyodide.mjs').is_file():
        pytest.skip(f'Pyodide is not installed in {PYODIDE} (npm ci in tests/js)')
    return demo_build.demo_install()


def test_a_package_of_the_lock_file_is_loaded_from_the_pyodide_folder(install, tmp_path):
    pyodide = _pyodide_with_the_wheel(tmp_path / 'pyodide')
    script = tmp_path / 'uses_wheel.py'
    script.write_text('import wasm_probe_pkg\nprint("value:", wasm_probe_pkg.VALUE)\n')
    code, out = _run(install, script, pyodide)
    assert 'value: from a wheel of the test' in out, out
    assert code == 0, out


def test_a_package_whose_wheel_is_missing_is_named_with_its_wheel(install, tmp_path):
    script = tmp_path / 'uses_numpy.py'
    script.write_text('import numpy\n')
    code, out = _run(install, script, PYODIDE)
    lock = json.loads((PYODIDE / 'pyodide-lock.json').read_text())['packages']['numpy']
    assert "ModuleNotFoundError: No module named 'numpy' in colcon-wasm's Python: it comes " \
        "from the package 'numpy', a package of Pyodide's distribution " \
        f"(numpy {lock['version']} in the pyodide-lock.json of {os.path.realpath(PYODIDE)}" \
        in out.replace(str(PYODIDE), os.path.realpath(PYODIDE)), out
    assert f"whose wheel {lock['file_name']} is not in that folder: give a Pyodide release " \
        'folder that has it with --pyodide DIR' in out, out
    assert code == 1, out
