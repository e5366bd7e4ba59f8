# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rclpy packages of ros2/examples, unmodified, with their rclcpp counterparts.

The Humble snapshot's examples_rclpy_minimal_publisher, _subscriber,
_service and _client are built by ``colcon build --wasm`` (packed for
Pyodide) as an overlay of the rclcpp build (tests/rclcpp_build.py, which
has std_msgs, example_interfaces, the rclcpp examples and the runtime,
wasm_js). They run in Node.js with
the npm package ``pyodide`` of tests/js: each Python example talks to its
rclcpp counterpart in both directions.
"""

import os
from pathlib import Path
import re
import shutil
import subprocess
import sys

from humble_build import humble_build
from humble_build import unpacked_source
import pytest
from rclcpp_build import rclcpp_build

REPO = Path(__file__).resolve().parents[1]
PYODIDE = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'

"""The examples built, by their folder in ros2/examples/rclpy."""
EXAMPLES = {
    'examples_rclpy_minimal_publisher': 'topics/minimal_publisher',
    'examples_rclpy_minimal_subscriber': 'topics/minimal_subscriber',
    'examples_rclpy_minimal_service': 'services/minimal_service',
    'examples_rclpy_minimal_client': 'services/minimal_client',
}


@pytest.fixture(scope='module')
def overlay():
    """Pack the rclpy examples on the rclcpp build (cached, keyed by its inputs)."""
    assert shutil.which('node'), 'Node.js 20 is needed (apt-get install nodejs)'
    if not (PYODIDE / 'pyodide.asm.wasm').is_file():
        pytest.skip('the npm package pyodide is missing: run `npm ci` in tests/js')
    underlay = rclcpp_build()
    examples = unpacked_source() / 'ros2' / 'examples' / 'rclpy'
    return humble_build(up_to=tuple(EXAMPLES), skip=(),
                        extra={name: examples / folder for name, folder in EXAMPLES.items()},
                        underlay=underlay, snapshot=False)


def launch(build, *items, duration=40):
    """Run ``colcon-wasm launch`` in the overlay; (status, stdout and stderr)."""
    env = dict(os.environ, COLCON_WASM_PYODIDE=str(PYODIDE))
    result = subprocess.run(
        [str(Path(sys.executable).parent / 'colcon-wasm'), 'launch', '--install-base',
         str(build.install), '--duration', str(duration), *items],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
        timeout=duration + 120)
    return result.returncode, result.stdout


def test_python_and_cpp_minimal_publishers_and_subscribers_hear_each_other(overlay):
    code, out = launch(
        overlay,
        'examples_rclpy_minimal_publisher/publisher_member_function',
        'examples_rclcpp_minimal_subscriber/subscriber_member_function',
        'examples_rclcpp_minimal_publisher/publisher_member_function',
        'examples_rclpy_minimal_subscriber/subscriber_member_function')
    # Python -> C++, on 'topic' (std_msgs/msg/String)
    cpp_heard = re.findall(r'\[subscriber_member_function-2\] \[INFO\] \[[\d.]+\] '
                           r"\[minimal_subscriber\]: I heard: 'Hello World: (\d+)'", out)
    # C++ -> Python
    py_heard = re.findall(r'\[subscriber_member_function-4\] \[INFO\] \[[\d.]+\] '
                          r'\[minimal_subscriber\]: I heard: "Hello, world! (\d+)"', out)
    published = re.findall(r'\[publisher_member_function-1\] \[INFO\] \[[\d.]+\] '
                           r'\[minimal_publisher\]: Publishing: "Hello World: (\d+)"', out)
    assert len(cpp_heard) >= 5 and len(py_heard) >= 5, out[-6000:]
    # what the C++ subscriber heard is what the Python publisher sent, in order
    assert [int(n) for n in cpp_heard] == sorted(int(n) for n in cpp_heard)
    assert set(cpp_heard) <= set(published), out[-6000:]
    assert code == 0, out[-3000:]


def test_python_and_cpp_minimal_services_and_clients_call_each_other(overlay):
    # rclcpp client -> rclpy service
    code, out = launch(overlay, 'examples_rclpy_minimal_service/service',
                       'examples_rclcpp_minimal_client/client_main')
    assert re.search(r'\[service-1\] \[INFO\] \[[\d.]+\] \[minimal_service\]: Incoming request',
                     out), out[-6000:]
    assert '[service-1] a: 41 b: 1' in out, out[-6000:]
    assert re.search(r'\[client_main-2\] \[INFO\] \[[\d.]+\] \[minimal_client\]: result of '
                     r'41 \+ 1 = 42', out), out[-6000:]
    assert '[INFO] [client_main-2]: process has finished cleanly' in out
    # rclpy client -> rclcpp service
    code, out = launch(overlay, 'examples_rclcpp_minimal_service/service_main',
                       'examples_rclpy_minimal_client/client_async')
    assert re.search(r'\[service_main-1\] \[INFO\] \[[\d.]+\] \[minimal_service\]: request: '
                     r'41 \+ 1', out), out[-6000:]
    assert re.search(r'\[client_async-2\] \[INFO\] \[[\d.]+\] \[minimal_client_async\]: Result '
                     r'of add_two_ints: for 41 \+ 1 = 42', out), out[-6000:]
    assert '[INFO] [client_async-2]: process has finished cleanly' in out
