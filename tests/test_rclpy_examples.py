# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rclpy packages of ros2/examples, unmodified, with their rclcpp counterparts.

The Humble snapshot's examples_rclpy_minimal_publisher, _subscriber,
_service, _client, _action_server, _action_client, examples_rclpy_executors
and _guard_conditions are built by ``colcon build --wasm`` (packed for
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
import sys

from humble_build import humble_build
from humble_build import unpacked_source
from launch_until import finished
from launch_until import run_until
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
    'examples_rclpy_minimal_action_server': 'actions/minimal_action_server',
    'examples_rclpy_minimal_action_client': 'actions/minimal_action_client',
    'examples_rclpy_executors': 'executors',
    'examples_rclpy_guard_conditions': 'guard_conditions',
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


def launch(build, *items, duration=40, until=None):
    """
    Run ``colcon-wasm launch`` in the overlay; (status, stdout and stderr).

    :param duration: its ``--duration``: the launch stops then at the latest
    :param until: ``until(output so far)`` true ends it sooner (tests/launch_until.py)
    """
    env = dict(os.environ, COLCON_WASM_PYODIDE=str(PYODIDE))
    return run_until([Path(sys.executable).parent / 'colcon-wasm', 'launch', '--install-base',
                      build.install, '--duration', duration, *items],
                     until=until, timeout=duration + 120, env=env)


def test_python_and_cpp_minimal_publishers_and_subscribers_hear_each_other(overlay):
    # Python -> C++, on 'topic' (std_msgs/msg/String)
    def cpp_heard(out):
        return re.findall(r'\[subscriber_member_function-2\] \[INFO\] \[[\d.]+\] '
                          r"\[minimal_subscriber\]: I heard: 'Hello World: (\d+)'", out)

    # C++ -> Python
    def py_heard(out):
        return re.findall(r'\[subscriber_member_function-4\] \[INFO\] \[[\d.]+\] '
                          r'\[minimal_subscriber\]: I heard: "Hello, world! (\d+)"', out)

    code, out = launch(
        overlay,
        'examples_rclpy_minimal_publisher/publisher_member_function',
        'examples_rclcpp_minimal_subscriber/subscriber_member_function',
        'examples_rclcpp_minimal_publisher/publisher_member_function',
        'examples_rclpy_minimal_subscriber/subscriber_member_function',
        until=lambda out: len(cpp_heard(out)) >= 5 and len(py_heard(out)) >= 5)
    cpp_heard = cpp_heard(out)
    py_heard = py_heard(out)
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
                       'examples_rclcpp_minimal_client/client_main',
                       until=finished('client_main-2'))
    assert re.search(r'\[service-1\] \[INFO\] \[[\d.]+\] \[minimal_service\]: Incoming request',
                     out), out[-6000:]
    assert '[service-1] a: 41 b: 1' in out, out[-6000:]
    assert re.search(r'\[client_main-2\] \[INFO\] \[[\d.]+\] \[minimal_client\]: result of '
                     r'41 \+ 1 = 42', out), out[-6000:]
    assert '[INFO] [client_main-2]: process has finished cleanly' in out
    # rclpy client -> rclcpp service
    code, out = launch(overlay, 'examples_rclcpp_minimal_service/service_main',
                       'examples_rclpy_minimal_client/client_async',
                       until=finished('client_async-2'))
    assert re.search(r'\[service_main-1\] \[INFO\] \[[\d.]+\] \[minimal_service\]: request: '
                     r'41 \+ 1', out), out[-6000:]
    assert re.search(r'\[client_async-2\] \[INFO\] \[[\d.]+\] \[minimal_client_async\]: Result '
                     r'of add_two_ints: for 41 \+ 1 = 42', out), out[-6000:]
    assert '[INFO] [client_async-2]: process has finished cleanly' in out


def log(out, process, node, text):
    """Find what ``process`` (launch's ``name-N``) logged matching ``text`` (a regex)."""
    return re.findall(rf'\[{process}\] \[INFO\] \[[\d.]+\] \[{node}\]: {text}', out)


def test_a_python_action_server_serves_the_cpp_clients_feedback_result_and_cancel(overlay):
    # rclcpp client -> rclpy server (server.py: MultiThreadedExecutor, a reentrant group, an
    # async execute callback that sleeps 1 s between feedbacks), to the end
    code, out = launch(overlay, 'examples_rclpy_minimal_action_server/server',
                       'examples_rclcpp_minimal_action_client/action_client_member_functions',
                       until=finished('action_client_member_functions-2'))
    client = 'action_client_member_functions-2'
    assert log(out, 'server-1', 'minimal_action_server', 'Received goal request'), out[-6000:]
    feedback = log(out, client, 'minimal_action_client',
                   r'Next number in sequence received: (\d+)')
    # (rclcpp drops feedback that comes before the goal response, natively too)
    assert feedback[-3:] == ['21', '34', '55'], out[-6000:]
    assert log(out, client, 'minimal_action_client', 'Result received'), out[-6000:]
    numbers = re.findall(rf'\[{client}\] \[INFO\] \[[\d.]+\] \[minimal_action_client\]: '
                         r'(\d+)\n', out)
    assert numbers == ['0', '1', '1', '2', '3', '5', '8', '13', '21', '34', '55'], out[-6000:]
    assert f'[INFO] [{client}]: process has finished cleanly' in out, out[-6000:]
    # an rclcpp client that cancels after 3 s: the sleeping execute callback hears it
    code, out = launch(overlay, 'examples_rclpy_minimal_action_server/server',
                       'examples_rclcpp_minimal_action_client/'
                       'action_client_not_composable_with_cancel', duration=25,
                       # the server logs "Goal canceled" after the result went out
                       until=lambda out: finished(
                           'action_client_not_composable_with_cancel-2')(out)
                       and 'Goal canceled' in out)
    client = 'action_client_not_composable_with_cancel-2'
    assert log(out, 'server-1', 'minimal_action_server', 'Received cancel request'), out[-6000:]
    assert log(out, 'server-1', 'minimal_action_server', 'Goal canceled'), out[-6000:]
    assert log(out, client, 'minimal_action_client', 'goal is being canceled'), out[-6000:]
    # the result carries CANCELED (the example then exits with 1, natively too)
    assert re.search(rf'\[{client}\] \[ERROR\] \[[\d.]+\] \[minimal_action_client\]: Goal '
                     'was canceled', out), out[-6000:]
    assert 'Returning result' not in out, out[-6000:]


def test_a_python_action_client_drives_the_cpp_server_feedback_result_and_cancel(overlay):
    # rclpy client (client.py: send_goal_async, feedback, get_result_async) -> rclcpp server
    code, out = launch(overlay, 'examples_rclcpp_minimal_action_server/'
                       'action_server_member_functions',
                       'examples_rclpy_minimal_action_client/client', duration=35,
                       until=finished('client-2'))
    feedback = log(out, 'client-2', 'minimal_action_client',
                   r"Received feedback: array\('i', \[([\d, ]+)\]\)")
    assert feedback[0] == '0, 1, 1' and feedback[-1] == '0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55', \
        out[-6000:]
    assert log(out, 'client-2', 'minimal_action_client', 'Goal succeeded! Result: '
               r"array\('i', \[0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55\]\)"), out[-6000:]
    assert '[INFO] [client-2]: process has finished cleanly' in out, out[-6000:]
    # rclpy client_cancel.py cancels after 2 s
    code, out = launch(overlay, 'examples_rclcpp_minimal_action_server/'
                       'action_server_member_functions',
                       'examples_rclpy_minimal_action_client/client_cancel', duration=25,
                       until=lambda out: finished('client_cancel-2')(out)
                       and 'Goal Canceled' in out)
    assert log(out, 'action_server_member_functions-1', 'minimal_action_server',
               'Received request to cancel goal'), out[-6000:]
    assert log(out, 'client_cancel-2', 'minimal_action_client',
               'Goal successfully canceled'), out[-6000:]
    assert log(out, 'action_server_member_functions-1', 'minimal_action_server',
               'Goal Canceled'), out[-6000:]
    assert '[INFO] [client_cancel-2]: process has finished cleanly' in out, out[-6000:]


def test_the_asyncio_action_client_runs_goals_in_parallel_and_in_sequence(overlay):
    # client_asyncio.py: spin_once in an asyncio task, two goals awaited in parallel, then two
    # one after the other, all in loop.run_until_complete (Pyodide's WebLoop cannot block:
    # rclpy/_event_loop.py)
    code, out = launch(overlay, 'examples_rclcpp_minimal_action_server/'
                       'action_server_member_functions',
                       'examples_rclpy_minimal_action_client/client_asyncio', duration=100,
                       until=finished('client_asyncio-2'))
    sequence = r"array\('i', \[0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55\]\)"
    client = 'client_asyncio-2'
    assert len(log(out, client, 'minimal_action_client_asyncio',
                   f'Goal succeeded! Result: {sequence}')) == 4, out[-6000:]
    assert log(out, client, 'minimal_action_client', 'unfinished: 0'), out[-6000:]
    # the results as rosidl_generator_py's __repr__ prints them
    result = rf'example_interfaces\.action\.Fibonacci_Result\(sequence={sequence}\)'
    assert len(log(out, client, 'minimal_action_client',
                   f'result {result} and status flag 4')) == 2, out[-6000:]
    for step in 'AB':
        assert log(out, client, 'minimal_action_client',
                   rf'{step}\) result {result} and status flag 4'), out[-6000:]
    assert f'[INFO] [{client}]: process has finished cleanly' in out, out[-6000:]


def test_python_action_server_and_client_talk_to_each_other(overlay):
    code, out = launch(overlay, 'examples_rclpy_minimal_action_server/server',
                       'examples_rclpy_minimal_action_client/client_cancel', duration=25,
                       until=lambda out: 'Goal successfully canceled' in out
                       and 'Goal canceled' in out)
    assert log(out, 'server-1', 'minimal_action_server', 'Goal canceled'), out[-6000:]
    assert log(out, 'client_cancel-2', 'minimal_action_client',
               'Goal successfully canceled'), out[-6000:]


def test_guard_condition_and_executor_examples(overlay):
    code, out = launch(overlay, 'examples_rclpy_guard_conditions/trigger_guard_condition',
                       duration=30, until=finished('trigger_guard_condition-1'))
    process = 'trigger_guard_condition-1'
    assert log(out, process, 'demo_guard_condition',
               'timer callback triggered guard condition'), out[-6000:]
    assert log(out, process, 'demo_guard_condition', 'guard callback called shutdown'), \
        out[-6000:]
    assert f'[INFO] [{process}]: process has finished cleanly' in out, out[-6000:]
    # composed (SingleThreadedExecutor: talker and listener) and callback_group
    # (MultiThreadedExecutor: two timers in one mutually exclusive group, and a listener)

    def published(out):
        return log(out, 'callback_group-2', 'double_talker', r'Publishing: "Hello World: (\d+)"')

    def heard(out, process, n):
        return log(out, process, 'listener', f'I heard: "Hello World: {n}"')

    def composed_heard_the_other_talker(out):
        """Tell whether the composed listener heard a number before its talker published it."""
        for match in re.finditer(r'\[composed-1\] \[INFO\] \[[\d.]+\] \[listener\]: '
                                 r'I heard: "Hello World: (\d+)"', out):
            own = re.search(r'\[composed-1\] \[INFO\] \[[\d.]+\] \[talker\]: '
                            rf'Publishing: "Hello World: {match.group(1)}"', out)
            if not own or own.start() > match.start():
                return True
        return False

    code, out = launch(overlay, 'examples_rclpy_executors/composed',
                       'examples_rclpy_executors/callback_group', duration=25,
                       until=lambda out: len(published(out)) >= 8
                       and heard(out, 'callback_group-2', 2)
                       and composed_heard_the_other_talker(out))
    assert heard(out, 'composed-1', 2), out[-6000:]
    published = published(out)
    # the two timers (1 s and 0.5 s) share one counter, one callback at a time
    assert len(published) >= 8 and published == [str(i) for i in range(len(published))], \
        out[-6000:]
    # each process' listener hears both talkers (same topic): the double talker counts 3 a
    # second, the composed one 1
    assert composed_heard_the_other_talker(out), out[-6000:]
    assert heard(out, 'callback_group-2', 2), out[-6000:]


"""Three nodes: the custom executor example, the custom callback group one, and a C++
talker on the custom executor's 'estop' topic (its high-priority node)."""
CUSTOM_LAUNCH = """<launch>
  <node pkg="examples_rclpy_executors" exec="custom_executor"/>
  <node pkg="examples_rclpy_executors" exec="custom_callback_group"/>
  <node pkg="examples_rclcpp_minimal_publisher" exec="publisher_member_function">
    <remap from="topic" to="estop"/>
  </node>
</launch>
"""


def test_custom_executor_and_custom_callback_group_examples(overlay, tmp_path):
    # custom_executor: an Executor subclass whose spin_once takes wait_for_ready_callbacks'
    # handlers and submits them to concurrent.futures thread pools (run inline: Pyodide
    # starts no thread); custom_callback_group: a token-bucket CallbackGroup subclass
    path = tmp_path / 'custom.launch.xml'
    path.write_text(CUSTOM_LAUNCH)
    code, out = launch(overlay, str(path), duration=30, until=lambda out: len(log(
        out, 'custom_callback_group-2', 'intermittent_talker', 'Publishing')) >= 20
        and len(log(out, 'custom_executor-1', 'estopper', 'I heard')) >= 3
        and log(out, 'custom_executor-1', 'listener', 'I heard: "Hello World: 3"'))
    # the high-priority node (estopper) hears the C++ talker
    estop = log(out, 'custom_executor-1', 'estopper', r'I heard: "Hello, world! (\d+)"')
    assert len(estop) >= 3, out[-6000:]
    # the low-priority ones: the listener hears the talker of its own process
    assert log(out, 'custom_executor-1', 'listener', 'I heard: "Hello World: 3"'), out[-6000:]
    # the throttled talker's 10 Hz timer runs while its bucket of 10 tokens lasts,
    # then at the 2 Hz of the refill
    stamps = [float(s) for s in re.findall(
        r'\[custom_callback_group-2\] \[INFO\] \[([\d.]+)\] \[intermittent_talker\]: '
        r'Publishing: "Hello World: \d+"', out)]
    published = log(out, 'custom_callback_group-2', 'intermittent_talker',
                    r'Publishing: "Hello World: (\d+)"')
    assert published == [str(i) for i in range(len(published))], out[-6000:]
    assert len(published) >= 14, out[-6000:]
    # no more than the bucket and one token per refill since the first
    for i, stamp in enumerate(stamps):
        assert i + 1 <= 10 + (stamp - stamps[0]) / 0.5 + 1, (i, stamps)
    # the last ones: spaced by the refill, not by the 0.1 s timer
    assert stamps[-1] - stamps[-5] >= 4 * 0.5 * 0.8, stamps
