# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes (rclpy in Pyodide) next to the C++ demo nodes, in Node.js.

The demo workspace (tests/demo_build.py, no Humble) and the npm package
``pyodide`` of tests/js (``npm ci`` there). Every run is bounded by
``--duration`` and a subprocess timeout.
"""

import os
from pathlib import Path
import re
import shutil

import demo_build
from launch_until import finished
from launch_until import line_indexes
from launch_until import run_until
from launch_until import went_on_after
import pytest

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / 'tests' / 'data' / 'pyodide'
PYODIDE = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'


@pytest.fixture(scope='module')
def install():
    """Build the demo workspace (once per test run) and check for Pyodide."""
    assert shutil.which('node'), 'Node.js 20 is needed (apt-get install nodejs)'
    if not (PYODIDE / 'pyodide.asm.wasm').is_file():
        pytest.skip('the npm package pyodide is missing: run `npm ci` in tests/js')
    return demo_build.demo_install()


def colcon_wasm(*args, timeout=180, until=None):
    """
    Run colcon-wasm with Pyodide from tests/js; returns (status, output: stdout and stderr).

    :param until: ``until(output so far)`` true stops it (tests/launch_until.py)
    """
    env = dict(os.environ, COLCON_WASM_PYODIDE=str(PYODIDE))
    return run_until([demo_build.venv_tool('colcon-wasm'), *args], until=until,
                     timeout=timeout, env=env)


# Python talker -> C++ listener, C++ talker -> Python listener (byte-exact CDR both ways)
CPP_HEARD = r'\[listener-2\] .*I heard: \[Hello from Python: \d+\]'
PY_HEARD = r'\[listener-4\] .*\[py_listener\]: I heard: \[Hello World: (\d+)\] count=\1$'
CRASHED = re.escape('[ERROR] [crasher-5]: process has died [exit code 1, Python exception: '
                    'ValueError: the Python crasher gives up')


def test_python_and_cpp_nodes_hear_each_other_and_a_python_crash_is_contained(install):
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 45,
        '--python', DATA / 'talker.py', '--python', DATA / 'listener.py',
        '--python', DATA / 'crasher.py', 'demo_nodes/talker', 'demo_nodes/listener',
        until=went_on_after(CRASHED, CPP_HEARD, PY_HEARD))
    lines = out.splitlines()
    cpp_heard = line_indexes(out, CPP_HEARD)
    py_heard = line_indexes(out, PY_HEARD)
    died = line_indexes(out, CRASHED)
    assert cpp_heard, out[-6000:]
    assert py_heard, out[-6000:]
    assert any(re.match(r'\[talker-3\] \[INFO\] \[[\d.]+\] \[py_talker\]: Publishing', line)
               for line in lines), out[-6000:]
    # the crasher: its traceback with file and line, reported as a crash
    tb = out.index('[crasher-5] Traceback (most recent call last):')
    assert f"[crasher-5]   File \"{DATA / 'crasher.py'}\", line 8, in explode" in out[tb:]
    assert '[crasher-5] ValueError: the Python crasher gives up' in out[tb:]
    assert died, out[-6000:]
    # ... and the others go on
    assert max(cpp_heard) > died[0] and max(py_heard) > died[0], out[-6000:]
    assert code == 1, out[-3000:]  # a process crashed


def test_python_services_and_clients_talk_to_cpp_ones(install):
    code, out = colcon_wasm(
        'launch', '--install-base', install, '--duration', 40,
        '--python', DATA / 'add_server.py', '--python', DATA / 'add_client.py',
        DATA / 'services.launch.xml',
        # both clients: the Python one can end before Pyodide's server is up
        until=lambda out: finished('add_client-4')(out) and
        finished('add_two_ints_client-2')(out))
    # C++ client -> Python server on /add_two_ints
    assert re.search(r'\[add_server-3\] .*\[py_server\]: Incoming request: a: (\d+) '
                     r'b: \d+', out), out[-6000:]
    assert re.search(r'\[add_two_ints_client-2\] .*Result of add_two_ints: for (\d+) \+ \d+ = '
                     r'\d+', out), out[-6000:]
    # Python client -> C++ server on /cpp_add_two_ints, int64 beyond 2**32 included
    for a in (1, 20, 2 ** 40):
        assert (f'[py_client]: Result of add_two_ints: for {a} + {2 * a} = '
                f'{3 * a}') in out, out[-6000:]
    assert '[py_client]: Synchronous call: 7 + 5 = 12' in out, out[-6000:]
    took = re.search(r'\[py_client\]: Rate: 5 periods of 50 ms took ([\d.]+) s', out)
    assert took and float(took.group(1)) >= 0.2, out[-6000:]
    assert '[INFO] [add_client-4]: process has finished cleanly' in out
    assert code == 0, out[-3000:]


def test_message_classes_parameters_and_cdr_round_trip(install):
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', DATA / 'messages.py')
    assert code == 0, out[-4000:]
    assert '[checks.py_messages]: message classes behave' in out
    assert '[INFO] [messages-1]: process has finished cleanly' in out


def test_print_plan_lists_python_nodes(install):
    code, out = colcon_wasm('launch', '--install-base', install, '--print-plan',
                            '--python', DATA / 'talker.py', 'demo_nodes/listener')
    assert code == 0, out
    assert f"[talker-2] {DATA / 'talker.py'}" in out.splitlines()


def test_missing_script_and_missing_pyodide_are_clear(install, tmp_path):
    code, out = colcon_wasm('run', '--install-base', install, '--python', tmp_path / 'nope.py')
    assert code == 1
    assert f"Python node '{tmp_path / 'nope.py'}' does not exist" in out
    (tmp_path / 'script.py').write_text('print(1)\n')
    code, out = colcon_wasm('run', '--install-base', install, '--pyodide', tmp_path,
                            '--python', tmp_path / 'script.py')
    assert code == 1
    assert (f"Python nodes need Pyodide 314.0.8, and '{tmp_path}' (--pyodide) lacks "
            'pyodide.mjs') in out
    assert 'npm install --prefix' in out and 'pyodide@314.0.8' in out
    code, out = colcon_wasm('run', '--install-base', install)
    assert code == 1 and 'name PKG EXE (or a Python node with --python FILE' in out


def test_pyodide_version_is_pinned_once():
    """The Python side, the JS side and tests/js pin the same Pyodide release."""
    from colcon_wasm.launch.python_nodes import PYODIDE_VERSION
    spawn = (REPO / 'packages' / 'wasm_js' / 'src' / 'python' / 'spawn.mjs').read_text()
    assert f"PYODIDE_VERSION = '{PYODIDE_VERSION}'" in spawn
    package = (REPO / 'tests' / 'js' / 'package.json').read_text()
    assert f'"pyodide": "{PYODIDE_VERSION}"' in package


def test_time_duration_and_graph_queries(install):
    """rclpy.time / duration as rclpy's, and graph queries that see the C++ nodes."""
    code, out = colcon_wasm('launch', '--install-base', install, '--duration', 60,
                            '--python', DATA / 'time_graph.py', 'demo_nodes/talker',
                            'demo_nodes/listener', 'demo_nodes/add_two_ints_server',
                            until=lambda out: re.search(r'\[time_graph-\d\]: process has', out))
    assert '[py_graph]: time, duration and graph queries behave' in out, out[-6000:]
    assert re.search(r'\[INFO\] \[time_graph-\d\]: process has finished cleanly', out), \
        out[-3000:]


def test_use_sim_time_follows_clock(install):
    """A node with use_sim_time:=true reads /clock's time; false goes back to the system time."""
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', DATA / 'sim_time.py')
    assert '[sim]: sim time follows /clock' in out, out[-6000:]
    assert code == 0, out[-3000:]


def test_clock_sleeps_and_rates_follow_clock(install):
    """Clock.sleep_for and a node's Rate on use_sim_time count /clock from another node."""
    code, out = colcon_wasm('launch', '--install-base', install, '--duration', 60,
                            '--python', DATA / 'clock_publisher.py',
                            '--python', DATA / 'sim_sleep.py', timeout=240,
                            until=lambda out: re.search(r'\[sim_sleep-\d\]: process has', out))
    slept = re.search(r'\[sleeper\]: slept on /clock: (\d+) s', out)
    assert slept and int(slept.group(1)) >= 60, out[-6000:]
    assert re.search(r'\[sim_sleep-\d\]: process has finished cleanly', out), out[-6000:]


def test_an_import_of_a_native_only_module_names_its_package(install, tmp_path):
    script = tmp_path / 'uses_tf2.py'
    script.write_text('import rclpy\nrclpy.init()\nimport numpy  # noqa\n')
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', script)
    assert ("ModuleNotFoundError: No module named 'numpy' in colcon-wasm's Python: it comes "
            "from the package 'numpy', a package of Pyodide's distribution (numpy ") in out, \
        out[-4000:]
    assert f'[{script.stem}-1] Traceback (most recent call last):' in out, out[-4000:]
    assert re.search(r'process has died \[exit code 1, Python exception: ModuleNotFoundError',
                     out), out[-4000:]
    assert code == 1, out[-4000:]


def test_the_native_only_modules_are_those_the_recipe_skips():
    import importlib.util
    from colcon_wasm.recipe import load_recipe
    path = REPO / 'packages' / 'wasm_js' / 'src' / 'python' / 'rclpy' / '_native_only.py'
    spec = importlib.util.spec_from_file_location('_native_only', path)
    table = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(table)
    recipe = load_recipe()
    for module, (package, why) in table.MODULES.items():
        skipped = recipe.skip_reason(package) is not None
        # 'skips the package' only for a package the recipe skips, and the reverse
        assert skipped == ('skips the package' in why), (module, package, why)


def test_qos_events_deadline_liveliness_and_incompatible_qos(install):
    code, out = colcon_wasm('run', '--install-base', install, '--duration', 60,
                            '--python', DATA / 'qos_events.py')
    assert '[py_events]: QoS events heard' in out, out[-4000:]
    # the best-effort publisher gets rclpy's default incompatible-QoS callback: a warning
    assert ('[WARN] [' in out and '[py_events]: New subscription discovered on topic '
            "'/mismatch', requesting incompatible QoS. No messages will be sent to it. Last "
            'incompatible policy: RELIABILITY') in out, out[-4000:]
    assert code == 0, out[-4000:]
