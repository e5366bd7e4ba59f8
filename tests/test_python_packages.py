# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
``ament_python`` packages packed by ``colcon build --wasm`` and run in Pyodide.

The fixture packages of tests/ros_fixtures (py_words: a library;
py_chatter: a talker, a listener and a crasher as console_scripts, and a
launch file; py_plain: colcon's plain 'python' type, no package.xml;
py_native: a C extension) are built by the real colcon on the
demo build as an underlay (tests/demo_build.py), and run with the npm
package ``pyodide`` of tests/js next to the C++ demo nodes. Every run is
bounded by ``--duration`` and a subprocess timeout.
"""

import json
import os
from pathlib import Path
import re
import shutil

from colcon_helpers import colcon
import demo_build
from launch_until import line_indexes
from launch_until import run_until
from launch_until import went_on_after
import pytest

REPO = Path(__file__).resolve().parents[1]
FIXTURES = REPO / 'tests' / 'ros_fixtures'
PYODIDE = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'


def _workspace(root, names):
    workspace = Path(root)
    for name in names:
        shutil.copytree(FIXTURES / name, workspace / 'src' / name)
    return workspace


@pytest.fixture(scope='module')
def overlay(tmp_path_factory):
    """py_words and py_chatter built with colcon build --wasm on the demo's install space."""
    assert shutil.which('node'), 'Node.js 20 is needed (apt-get install nodejs)'
    if not (PYODIDE / 'pyodide.asm.wasm').is_file():
        pytest.skip('the npm package pyodide is missing: run `npm ci` in tests/js')
    underlay = demo_build.demo_install()
    workspace = _workspace(tmp_path_factory.mktemp('python_overlay'),
                           ('py_words', 'py_chatter', 'py_plain'))
    colcon(workspace, 'build', '--wasm', '--wasm-underlay', str(underlay))
    # colcon's log of every logger (the INFO lines do not reach the console)
    return workspace, (workspace / 'log' / 'latest_build' / 'logger_all.log').read_text()


def colcon_wasm(workspace, *args, timeout=180, until=None):
    """
    Run colcon-wasm in the overlay with Pyodide from tests/js; (status, stdout and stderr).

    :param until: ``until(output so far)`` true stops it (tests/launch_until.py)
    """
    env = dict(os.environ, COLCON_WASM_PYODIDE=str(PYODIDE))
    return run_until([demo_build.venv_tool('colcon-wasm'), *args], until=until,
                     timeout=timeout, env=env, cwd=workspace)


def test_the_build_packs_the_modules_entry_points_and_data_files(overlay):
    workspace, log = overlay
    install = workspace / 'install_wasm'
    assert "Packed Python package 'py_chatter' for Pyodide (crasher, listener, talker)" in log
    assert "Packed Python package 'py_words' for Pyodide (no entry points)" in log
    # py_chatter's exec_depend on rclpy, which the recipe skips
    assert "Python package 'py_chatter' uses colcon-wasm's rclpy for Pyodide in place of " \
        "'rclpy'" in log
    assert "Python package 'py_words' uses" not in log
    manifest = json.loads((install / 'py_chatter' / 'share' / 'py_chatter' / 'colcon_wasm'
                           / 'manifest.json').read_text())
    by_name = {e['name']: e for e in manifest['executables']}
    assert sorted(by_name) == ['crasher', 'listener', 'talker']
    assert by_name['talker']['python'] == {'module': 'py_chatter.talker', 'function': 'main'}
    assert by_name['talker']['js'] == 'lib/py_chatter/talker'
    folder, = manifest['python']['path']
    assert re.fullmatch(r'lib/python3\.\d+/site-packages', folder), folder
    assert f'{folder}/py_chatter/talker.py' in manifest['python']['files']
    for relative in manifest['python']['files']:
        assert (install / 'py_chatter' / relative).is_file(), relative
    # the data files where setup.py's data_files put them
    assert (install / 'py_chatter' / 'share' / 'py_chatter' / 'launch'
            / 'chatter.launch.xml').is_file()
    assert (install / 'py_chatter' / 'share' / 'ament_index' / 'resource_index' / 'packages'
            / 'py_chatter').is_file()
    words = json.loads((install / 'py_words' / 'share' / 'py_words' / 'colcon_wasm'
                        / 'manifest.json').read_text())
    assert words['executables'] == []
    assert f'{folder}/py_words/__init__.py' in words['python']['files']


def test_a_plain_python_package_is_packed_and_its_node_heard(overlay):
    # colcon's 'python' type (setup.cfg, no package.xml): its scripts go to bin/
    workspace, log = overlay
    assert "Packed Python package 'py_plain' for Pyodide (shouter)" in log
    manifest = json.loads((workspace / 'install_wasm' / 'py_plain' / 'share' / 'py_plain'
                           / 'colcon_wasm' / 'manifest.json').read_text())
    shouter, = manifest['executables']
    assert shouter['python'] == {'module': 'py_plain.shouter', 'function': 'main'}
    assert shouter['js'] == 'bin/shouter'
    heard = r'\[listener-2\] .*I heard: \[SHOUTED FROM A PLAIN PACKAGE: \d+\]'
    code, out = colcon_wasm(workspace, 'launch', '--duration', 25, 'py_plain/shouter',
                            'demo_nodes/listener', until=lambda out: re.search(heard, out))
    assert re.search(heard, out), out[-6000:]


# py_words, another package of the install space, gives the text
CPP_HEARD = r'\[listener-2\] .*I heard: \[Hello from a Python package: \d+\]'
PY_HEARD = (r'\[listener-5\] .*\[py_package_listener\]: I heard: \[Hello World: (\d+)\] '
            r'count=\1$')
CRASHED = re.escape('[ERROR] [crasher-3]: process has died [exit code 1, Python exception: '
                    'RuntimeError: the packaged crasher gives up')


def test_a_packaged_talker_is_heard_by_the_cpp_listener_and_a_crash_is_contained(overlay):
    workspace, _ = overlay
    code, out = colcon_wasm(workspace, 'launch', '--duration', 40, 'py_chatter/talker',
                            'demo_nodes/listener', 'py_chatter/crasher', 'demo_nodes/talker',
                            'py_chatter/listener',
                            until=went_on_after(CRASHED, CPP_HEARD, PY_HEARD))
    cpp_heard = line_indexes(out, CPP_HEARD)
    py_heard = line_indexes(out, PY_HEARD)
    died = line_indexes(out, CRASHED)
    assert cpp_heard, out[-6000:]
    assert py_heard, out[-6000:]
    tb = out.index('[crasher-3] Traceback (most recent call last):')
    crasher = workspace / 'install_wasm' / 'py_chatter'
    assert re.search(r'\[crasher-3\]   File "' + re.escape(str(crasher)) + r'/lib/python3\.\d+/'
                     r'site-packages/py_chatter/crasher\.py", line 8, in explode', out[tb:]), \
        out[tb:tb + 3000]
    assert '[crasher-3] RuntimeError: the packaged crasher gives up' in out[tb:]
    assert died, out[-6000:]
    assert max(cpp_heard) > died[0] and max(py_heard) > died[0], out[-6000:]
    assert code == 1, out[-3000:]


def test_run_passes_ros_arguments_and_a_launch_file_of_the_package_runs_its_nodes(overlay):
    workspace, _ = overlay
    published = r'\[renamed_talker\]: Publishing: "Hello from a Python package: 1"'
    code, out = colcon_wasm(workspace, 'run', '--duration', 25, 'py_chatter', 'talker',
                            '--ros-args', '-r', '__node:=renamed_talker', '-r', 'chatter:=news',
                            until=lambda out: re.search(published, out))
    assert re.search(published, out), out[-4000:]
    assert code == 0, out[-3000:]
    heard = (r'\[listener-2\] .*\[py_package_listener\]: I heard: \[Hello from a '
             r'Python package: \d+\]')
    code, out = colcon_wasm(workspace, 'launch', '--duration', 40, 'py_chatter',
                            'chatter.launch.xml', until=lambda out: re.search(heard, out))
    assert re.search(r'\[talker-1\] .*\[launched_talker\]: Publishing', out), out[-4000:]
    assert re.search(heard, out), out[-4000:]
    assert code == 0, out[-3000:]


def test_print_plan_names_the_installed_script(overlay):
    workspace, _ = overlay
    code, out = colcon_wasm(workspace, 'launch', '--print-plan', 'py_chatter/listener')
    script = workspace / 'install_wasm' / 'py_chatter' / 'lib' / 'py_chatter' / 'listener'
    assert out.strip() == f'[listener-1] {script}', out
    assert code == 0


def test_a_package_with_a_c_extension_is_refused_with_its_module_named(tmp_path):
    if shutil.which('emcc') is None and not os.environ.get('EMSDK'):
        pytest.skip('Emscripten is not installed (apt-get install emscripten)')
    workspace = _workspace(tmp_path, ('py_native',))
    result = colcon(workspace, 'build', '--wasm', check=False)
    assert result.returncode != 0
    assert re.search(r"'py_native' installs compiled extension modules \(lib/python3\.\d+/"
                     r'site-packages/py_native/_speedups\.[^)]*\.so\): they are built for the '
                     r"host's CPython, and Pyodide cannot load them; skip the package for --wasm "
                     r'\(--packages-skip py_native', result.stdout), result.stdout[-4000:]
    assert not (workspace / 'install_wasm' / 'py_native' / 'share' / 'py_native' / 'colcon_wasm'
                / 'manifest.json').exists()


def test_the_page_lists_a_packaged_entry_point_and_runs_it_beside_a_cpp_listener(overlay):
    """The served page lists the entry points, serves the modules, and Run starts one."""
    from served_page import explain_page
    from served_page import ServedPage
    import urllib.parse
    import urllib.request
    workspace, _ = overlay
    steps = [
        {'start': 'listener', 'pkg': 'demo_nodes', 'exe': 'listener'},
        {'start': 'py_talker', 'pkg': 'py_chatter', 'exe': 'talker'},
        {'wait': 'listener', 'text': 'I heard: [Hello from a Python package: 3]',
         'timeoutMs': 90000},
        {'stop': 'py_talker'},
    ]
    with ServedPage(workspace / 'install_wasm', args=['--pyodide', PYODIDE]) as page:
        listing_url = urllib.parse.urljoin(page.url, '/workspace.json')
        with urllib.request.urlopen(listing_url, timeout=30) as response:
            listing = json.load(response)
        result = page.run(steps, timeout_ms=180000)
    chatter, = [p for p in listing['packages'] if p['name'] == 'py_chatter']
    talker, = [e for e in chatter['executables'] if e['name'] == 'talker']
    assert talker['python'] == {'module': 'py_chatter.talker', 'function': 'main'}
    assert talker['file'] == str(workspace / 'install_wasm' / 'py_chatter' / 'lib' /
                                 'py_chatter' / 'talker')
    served = {f['path'] for f in listing['python']['files']}
    assert any(p.endswith('/site-packages/py_words/__init__.py') for p in served), served
    assert 'demo_nodes' in {p['name'] for p in listing['packages']}  # the underlay's
    assert result['ok'], explain_page(result)
    talked = [line for line in result['logs']['py_talker']
              if '[py_package_talker]: Publishing: "Hello from a Python package' in line]
    assert talked, result['logs']['py_talker']
    assert result['states']['py_talker'] == 'stopped', result['states']
