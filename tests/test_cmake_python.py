# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Python part of a CMake package (ament_cmake_python), run in Pyodide.

tests/ros_fixtures/py_cmake_mixed is an ament_cmake package that installs a
Python module (``ament_python_install_package``) and a Python script
(``install(PROGRAMS scripts/mixed_talker.py DESTINATION lib/...)``) that
imports it. Built by the real colcon with ``--wasm`` as an overlay of the
rclcpp build (tests/rclcpp_build.py), its script is an executable of the
install space, as ``ros2 run py_cmake_mixed mixed_talker.py`` would find
it: it runs in Node.js and on the page, heard by the rclcpp
minimal subscriber.
"""

import json
import os
from pathlib import Path
import re
import shutil
import sys

from humble_build import humble_build
from launch_until import run_until
import pytest
from rclcpp_build import rclcpp_build

REPO = Path(__file__).resolve().parents[1]
PYODIDE = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'
FIXTURE = REPO / 'tests' / 'ros_fixtures' / 'py_cmake_mixed'
SUBSCRIBER = 'examples_rclcpp_minimal_subscriber/subscriber_member_function'
HEARD = r"I heard: 'Hello from an ament_cmake_python package: \d+'"


@pytest.fixture(scope='module')
def overlay():
    """Build the fixture on the rclcpp build (cached, keyed by its inputs)."""
    assert shutil.which('node'), 'Node.js 20 is needed (apt-get install nodejs)'
    if not (PYODIDE / 'pyodide.asm.wasm').is_file():
        pytest.skip('the npm package pyodide is missing: run `npm ci` in tests/js')
    return humble_build(up_to=('py_cmake_mixed',), skip=(),
                        extra={'py_cmake_mixed': FIXTURE},
                        underlay=rclcpp_build(), snapshot=False)


def test_the_manifest_lists_the_script_and_the_module(overlay):
    prefix = overlay.install / 'py_cmake_mixed'
    manifest = json.loads((prefix / 'share' / 'py_cmake_mixed' / 'colcon_wasm'
                           / 'manifest.json').read_text())
    script, = manifest['executables']
    assert script == {'name': 'mixed_talker.py', 'js': 'lib/py_cmake_mixed/mixed_talker.py',
                      'python': {'script': True}, 'uses_bus': True, 'pthread': False}
    folder, = manifest['python']['path']
    assert re.fullmatch(r'lib/python3\.\d+/site-packages', folder), folder
    assert f'{folder}/py_cmake_mixed/__init__.py' in manifest['python']['files']
    for relative in manifest['python']['files']:
        assert (prefix / relative).is_file(), relative


def test_the_script_runs_beside_a_cpp_subscriber(overlay):
    env = dict(os.environ, COLCON_WASM_PYODIDE=str(PYODIDE))
    heard = r'\[subscriber_member_function-2\] .*\[minimal_subscriber\]: ' + HEARD
    code, out = run_until(
        [Path(sys.executable).parent / 'colcon-wasm', 'launch', '--install-base',
         overlay.install, '--duration', '30', 'py_cmake_mixed/mixed_talker.py', SUBSCRIBER],
        until=lambda out: re.search(heard, out), timeout=150, env=env)
    assert re.search(r'\[mixed_talker\.py-1\] \[INFO\] \[[\d.]+\] \[mixed_talker\]: '
                     r'Publishing: "Hello from an ament_cmake_python package: 1"', out), \
        out[-6000:]
    assert re.search(heard, out), out[-6000:]


def test_the_page_runs_the_script_beside_a_cpp_subscriber(overlay):
    from served_page import explain_page
    from served_page import ServedPage
    package, exe = SUBSCRIBER.split('/')
    steps = [
        {'start': 'subscriber', 'pkg': package, 'exe': exe},
        {'start': 'talker', 'pkg': 'py_cmake_mixed', 'exe': 'mixed_talker.py'},
        {'wait': 'subscriber', 'regex': HEARD, 'count': 2, 'timeoutMs': 90000},
    ]
    with ServedPage(overlay.install, args=['--pyodide', PYODIDE]) as page:
        result = page.run(steps, timeout_ms=150000)
    assert result['ok'], explain_page(result)
    assert result['snapshots']['talker'] is True, result['snapshots']


def test_only_python_scripts_become_executables_and_extensions_are_named(tmp_path, caplog):
    # what colcon_wasm/cmake_python.py reads of an install (no build: files as CMake installs)
    from colcon_wasm.cmake_python import python_part
    files = {
        'lib/pkg/run_me': '#!/usr/bin/env python3\nprint(1)\n',
        'lib/pkg/tool.py': 'print(2)\n',
        'lib/pkg/start.sh': '#!/bin/sh\necho 3\n',
        'lib/pkg/node.js': '// an Emscripten executable\n',
        'lib/pkg/sub/deep.py': 'print(4)\n',
        'lib/python3.11/site-packages/pkg/__init__.py': '',
        'lib/python3.11/site-packages/pkg/_fast.cpython-311-x86_64-linux-gnu.so': 'ELF',
        'share/pkg/package.xml': '<package/>',
    }
    for relative, text in files.items():
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / relative).write_text(text)
    python, scripts = python_part(tmp_path, 'pkg', [tmp_path / r for r in files])
    assert [s['name'] for s in scripts] == ['run_me', 'tool.py']
    assert python == {'path': ['lib/python3.11/site-packages'],
                      'files': ['lib/python3.11/site-packages/pkg/__init__.py']}
    assert '_fast.cpython-311-x86_64-linux-gnu.so' in caplog.text
    assert 'Pyodide cannot load them' in caplog.text
    # no module installed: no python entry
    python, scripts = python_part(tmp_path, 'pkg', [tmp_path / 'lib/pkg/tool.py'])
    assert python is None and [s['name'] for s in scripts] == ['tool.py']
