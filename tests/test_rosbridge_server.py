# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rosbridge v2 server of `colcon-wasm launch --rosbridge` with real clients.

Third-party clients: roslibjs (npm `roslib`, tests/js/rosbridge_roslib.mjs),
roslibpy (PyPI, tests/rosbridge_roslibpy.py) and raw requests over npm `ws`
(tests/js/rosbridge_raw.mjs), against real C++ nodes of the Humble build
(tests/rclcpp_build.py): rmw_wasm_cpp_node_tests' probe (a 10 Hz talker on
/chatter, a listener, an AddTwoInts server, a client that calls once, an
image echo) and examples_rclcpp_minimal_action_server (Fibonacci). All on
127.0.0.1, every wait bounded.
"""

import json
from pathlib import Path
import re
import socket
import subprocess
import sys
import textwrap

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from rclcpp_build import rclcpp_build  # noqa: E402, I100
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from rosbridge_launch import node_script  # noqa: E402

LAUNCH = """
    launch:
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: param_talker, name: talker}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: listener}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: add_server,
             remap: [{from: hold, to: add}]}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: caller,
             remap: [{from: hold, to: served}]}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: bench_pong_image}
    - node: {pkg: examples_rclcpp_minimal_action_server, exec: action_server_not_composable}
"""

MAX_QUEUED = 1000000
MAX_MESSAGE = 200000
TOKEN = 's3cret-t0ken'


@pytest.fixture(scope='module')
def install():
    """Get the Humble build with the probe and the minimal action server."""
    return rclcpp_build().install


@pytest.fixture(scope='module')
def server(install, tmp_path_factory):
    """One launch of the C++ nodes with a rosbridge server, for the module."""
    path = tmp_path_factory.mktemp('rosbridge') / 'bridge.launch.yaml'
    path.write_text(textwrap.dedent(LAUNCH).lstrip(), encoding='utf-8')
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0', '--rosbridge-max-queued-bytes',
                          MAX_QUEUED, path) as run:
        run.wait_for('NAME /talker TOPIC /chatter', timeout=60)
        run.wait_for('[bench_pong]: READY', timeout=60)
        yield run


def test_roslibjs_graph_fields_publish_and_call(server):
    """Check RosLib getTopics/getNodes/getServices, typed fields, publish into C++, call C++."""
    r = node_script('rosbridge_roslib.mjs', 'basic', server.url)
    topics = dict(zip(r['topics']['topics'], r['topics']['types']))
    assert topics['/chatter'] == 'std_msgs/msg/String'
    assert topics['/bench/pong'] == 'sensor_msgs/msg/Image'
    for node in ('/talker', '/probe_listener', '/add_server', '/minimal_action_server',
                 '/rosbridge_websocket', '/rosapi'):
        assert node in r['nodes'], r['nodes']
    assert '/add' in r['services'] and '/rosapi/topics' in r['services']
    assert r['topicType'] == 'std_msgs/msg/String'
    # rosapi's topics_and_raw_types: each type's complete definition, as rosbag2 writes it
    raw = dict(zip(r['raw']['topics'], r['raw']['typedefs_full_text']))
    assert re.search(r'^string data$', raw['/chatter'], re.M), raw['/chatter']
    assert f"\n{'=' * 80}\nMSG: std_msgs/Header\n" in raw['/bench/pong'], raw['/bench/pong']
    assert r['details'][:2] == ['sensor_msgs/Image', 'std_msgs/Header']
    assert r['decoded']['data'] == ['uint8'] and r['decoded']['header']['frame_id'] == 'string'
    assert all(h.startswith('hello ') for h in r['heard']), r['heard']
    numbers = [int(h.split()[1]) for h in r['heard']]
    assert numbers == list(range(numbers[0], numbers[0] + 3))
    assert r['sum'] == {'sum': 42}
    assert 'does not exist' in r['missingError']
    server.wait_for('HEARD from roslibjs 19', timeout=10)
    assert server.count('HEARD from roslibjs') >= 20


def test_roslibjs_serves_a_service_a_cpp_client_calls(server):
    """advertise_service: the C++ caller's request reaches roslibjs, its answer the caller."""
    r = node_script('rosbridge_roslib.mjs', 'serve', server.url)
    assert r['requests'][0] == {'a': 2, 'b': 3}
    server.wait_for('RESULT 203', timeout=20)


def test_roslibjs_action_feedback_result_cancel(server):
    """send_action_goal with feedback and result, and cancel_action_goal, on a C++ server."""
    r = node_script('rosbridge_roslib.mjs', 'action', server.url, timeout=120)
    assert r['result'] == {'sequence': [0, 1, 1, 2]}
    assert r['feedback'] == [[0, 1, 1], [0, 1, 1, 2]]
    assert 'canceled' in r['cancelled'].get('error', ''), r['cancelled']
    server.wait_for('Goal Canceled', timeout=10)


def test_roslibjs_serves_an_action_a_cpp_client_uses(install, tmp_path):
    """advertise_action: the C++ minimal action client's goal, feedback and result cross."""
    path = tmp_path / 'client.launch.yaml'
    path.write_text(textwrap.dedent("""
        launch:
        - node: {pkg: examples_rclcpp_minimal_action_client, exec: action_client_not_composable}
    """).lstrip(), encoding='utf-8')
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0', path) as run:
        r = node_script('rosbridge_roslib.mjs', 'serveAction', run.url)
        assert r['goals'] == [{'order': 10}], r
        run.wait_for('result received', timeout=20)
        run.wait_for('process has finished cleanly', timeout=20)
        output = run.output()
    numbers = [int(n) for n in re.findall(r'\[minimal_action_client\]: (\d+)$', output, re.M)]
    assert numbers == [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55], output[-3000:]


def test_roslibjs_throttle_rate_and_queue_length(server):
    """throttle_rate drops within the window; queue_length 1 keeps the newest."""
    r = node_script('rosbridge_roslib.mjs', 'throttle', server.url)
    assert 25 <= r['all'] <= 35, r
    assert 5 <= r['throttled'] <= 7, r
    assert all(g >= 450 for g in r['throttledGaps']), r
    assert 3 <= len(r['queued']) <= 5, r
    assert all(g >= 900 for g in r['queuedGaps']), r
    # one per second, the newest: 10 Hz numbers about 10 apart, never consecutive
    steps = [b - a for a, b in zip(r['queued'], r['queued'][1:])]
    assert all(8 <= s <= 12 for s in steps), r


def test_roslibjs_images_cbor_raw_and_cbor(server):
    """640x480 rgb8 images through a C++ node, received as cbor-raw bytes and cbor."""
    r = node_script('rosbridge_roslib.mjs', 'images', server.url)
    assert r['rawHasTime']
    assert (r['rawHeight'], r['rawWidth']) == (480, 640)
    assert r['rawBytes'] > 640 * 480 * 3
    assert r['rawDataTail'] == r['expectedTail']
    assert r['cborDataIsBytes'] and r['cborDataLength'] == 640 * 480 * 3
    assert (r['cborEncoding'], r['cborFrame']) == ('rgb8', 'camera')


def test_roslibpy(server):
    """roslibpy: subscribe, publish into the C++ listener, call with int64, graph, a parameter."""
    result = subprocess.run(
        [sys.executable, str(Path(__file__).resolve().parent / 'rosbridge_roslibpy.py'),
         str(server.port)], capture_output=True, text=True, timeout=90)
    assert result.returncode == 0, result.stderr[-3000:]
    r = json.loads(result.stdout.strip().splitlines()[-1])
    assert r['connected']
    assert r['sum'] == 2 ** 62 + 7  # int64 exact through JSON
    assert any(h.startswith('hello ') for h in r['heard']), r['heard']
    assert '/chatter' in r['topics'] and '/talker' in r['nodes']
    assert r['type'] == 'std_msgs/msg/String'
    assert '/talker:period_ms' in r['params'], r['params']
    assert isinstance(r['period'], int) and r['period_set'] == 300, r
    server.wait_for('HEARD from roslibpy 9', timeout=10)


def test_bad_input_gets_status_errors_and_the_connection_stays(server):
    """Each bad request: a status error naming the field or type, with its id."""
    r = node_script('rosbridge_raw.mjs', 'bad', server.url)
    by = {o['what']: o for o in r['out']}
    for what, o in by.items():
        assert o['status'].get('op') == 'status', (what, o)
        assert o['status']['level'] == 'error', (what, o)
        if o.get('id') is not None:
            assert o['status'].get('id') == o['id'], (what, o)
    expect = {
        'malformed': 'malformed JSON', 'not an object': 'must be a JSON object',
        'no op': "no 'op' field", 'unknown op': 'unknown operation "fly"',
        'missing topic': "field 'topic' is "
                         'missing', 'topic wrong type': "field 'topic' must be a string",
        'bad throttle': "field 'throttle_rate' must be an integer",
        'bad compression': "field 'compression' must be one of",
        'unknown type': "unknown message type 'no_pkg/msg/Nothing'",
        'bad topic '
        'name': 'not a valid ROS name', 'wrong field type': "field 'data': expected a string",
        'unknown field': "has no field 'text'", 'missing msg': "field 'msg' is missing",
        'wrong args': "field 'a': expected an "
                      'integer', 'missing service': "field 'service' is missing",
        'bad level': "field 'level' must be one of", 'bad fragment': "field 'num'",
        'unknown action type': "unknown action type 'nope/action/Nope'",
        'response without advertise': 'has not been advertised',
    }
    for what, text in expect.items():
        assert text in by[what]['status']['msg'], (what, by[what])
    assert r['after'] and '/talker' in r['nodes'] and r['fragmented']


def test_int64_keeps_precision(server):
    """2^53 + 1 + 10 comes back exact in the JSON text."""
    r = node_script('rosbridge_raw.mjs', 'int64', server.url)
    assert '"sum":9007199254741003' in r['text'], r['text']


def test_a_client_that_stops_reading_is_cut_off(server):
    """Past --rosbridge-max-queued-bytes the slow client is cut off; the other gets everything."""
    r = node_script('rosbridge_raw.mjs', 'slow', server.url, timeout=120)
    assert r['closed'] is not None, r
    assert r['received'] == r['sent'], r
    server.wait_for(f'cut off: the client did not read: more than {MAX_QUEUED} bytes',
                    timeout=10)


@pytest.fixture(scope='module')
def guarded(install, tmp_path_factory):
    """Start a server with a token, a capability list and a message size limit."""
    folder = tmp_path_factory.mktemp('guarded')
    launch = folder / 'guarded.launch.yaml'
    launch.write_text(textwrap.dedent("""
        launch:
        - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: param_talker, name: talker}
        - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: add_server,
                 remap: [{from: hold, to: add}]}
    """).lstrip(), encoding='utf-8')
    capabilities = folder / 'capabilities.yaml'
    capabilities.write_text(textwrap.dedent("""
        subscribe: [/chatter]
        publish: [/allowed/*]
        call: [/rosapi/*]
    """).lstrip(), encoding='utf-8')
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0', '--rosbridge-token', TOKEN,
                          '--rosbridge-capabilities', capabilities,
                          '--rosbridge-max-message-bytes', MAX_MESSAGE, launch) as run:
        run.wait_for('NAME /talker TOPIC /chatter', timeout=60)
        yield run


def test_token_is_checked_on_connect(guarded):
    """No token or a wrong one: HTTP 401; the token in the URL or a Bearer header: open."""
    r = node_script('rosbridge_raw.mjs', 'token', guarded.url, TOKEN)
    assert r['none'] == 'HTTP 401' and r['wrong'] == 'HTTP 401', r
    assert r['right'] == 'open' and r['header'] == 'open', r


def test_capability_list_refuses_with_status_errors(guarded):
    """What the list does not grant is refused by name; what it grants works."""
    r = node_script('rosbridge_raw.mjs', 'capabilities', f'{guarded.url}/?token={TOKEN}')
    assert "not allowed to subscribe '/secret'" in r['refused']['subscribe'], r
    assert "not allowed to publish '/chatter'" in r['refused']['publish'], r
    assert "allows 'publish' only for /allowed/*" in r['refused']['publish'], r
    assert "not allowed to call '/add'" in r['refused']['call'], r
    assert "grants no 'advertise'" in r['refused']['advertise'], r
    assert r['heard'].startswith('hello ') and r['rosapi'], r


def test_oversized_message_is_dropped_with_a_status_error(guarded):
    """A message over --rosbridge-max-message-bytes: a status error, the connection stays up."""
    r = node_script('rosbridge_raw.mjs', 'oversize', f'{guarded.url}/?token={TOKEN}',
                    MAX_MESSAGE)
    assert f'larger than the limit of {MAX_MESSAGE} bytes' in r['status']['msg'], r
    assert r['after'], r


def test_port_in_use_is_reported_as_serve_reports_it(install, tmp_path):
    """--rosbridge on a taken port: exit 1 before any node starts, and what to do."""
    taken = socket.socket()
    taken.bind(('127.0.0.1', 0))
    taken.listen(1)
    port = taken.getsockname()[1]
    try:
        result = subprocess.run(
            [str(demo_build.venv_tool('colcon-wasm')), 'launch', '--install-base', str(install),
             '--rosbridge', f'127.0.0.1:{port}', '--duration', '5',
             'rmw_wasm_cpp_node_tests/probe'], capture_output=True, text=True, timeout=60)
    finally:
        taken.close()
    assert result.returncode == 1
    assert f'colcon-wasm launch: port {port} on 127.0.0.1 is already in use' in \
        result.stderr, result.stderr
    assert 'pass --rosbridge HOST:PORT (port 0 picks a free port)' in result.stderr
    assert 'process started' not in result.stdout


def test_bad_listen_address_and_capability_file(install, tmp_path):
    """A bad [HOST:]PORT or capability list is an error naming it, before anything runs."""
    tool = str(demo_build.venv_tool('colcon-wasm'))
    bad = subprocess.run([tool, 'launch', '--install-base', str(install), '--rosbridge',
                          'nine:ninety', 'rmw_wasm_cpp_node_tests/probe'],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 1 and "'nine:ninety' is not [HOST:]PORT" in bad.stderr
    caps = tmp_path / 'caps.yaml'
    caps.write_text('subscribe: [/a]\nfly: [/b]\n', encoding='utf-8')
    bad = subprocess.run([tool, 'launch', '--install-base', str(install), '--rosbridge', '0',
                          '--rosbridge-capabilities', str(caps), 'rmw_wasm_cpp_node_tests/probe'],
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 1 and "unknown key 'fly'" in bad.stderr, bad.stderr


def _check_params(r, node):
    """Check what the `params` scenario of rosbridge_roslib.mjs saw of ``node`` (param_talker)."""
    assert {f'{node}:greeting', f'{node}:period_ms', f'{node}:use_sim_time'} <= set(r['names'])
    assert r['before'] == {'value': 'hello'}
    assert r['set'] == {'set': True} and r['after'] == {'value': 'hi from roslibjs'}
    assert r['setPeriod'] == {'set': True} and r['period'] == {'value': 250}
    # rclcpp refuses a string for its integer parameter, and roslibjs is told why
    assert r['wrongType']['failed'] == (
        f'setting {node}:period_ms failed: Wrong parameter type, parameter {{period_ms}} is of '
        'type {integer}, setting it to {string} is not allowed.')
    assert r['periodStill'] == {'value': 250}
    assert r['missing'] == {'failed': f"{node} has no parameter 'no_such'"}
    assert r['noNode']['failed'].startswith(
        'no node /nobody with parameter services is on the graph'), r['noNode']
    assert r['malformed']['failed'].startswith("malformed parameter name 'no_colon'"), r
    assert r['defaulted'] == {'value': '7', 'successful': True, 'reason': ''}
    assert r['has'] == {'exists': True} and r['hasNot'] == {'exists': False}
    assert r['notJson']['successful'] is False
    assert r['notJson']['reason'].startswith('the value of set_param must be JSON text'), r
    assert r['deleteMissing'] == {
        'failed': f"cannot delete {node}:no_such: {node} has no parameter 'no_such'"}
    assert r['deleteDeclared'] == {
        'failed': f'deleting {node}:greeting failed: cannot undeclare an statically typed '
                  'parameter'}
    assert r['afterDelete'] == {'value': 'hi from roslibjs'}


def test_roslibjs_params_of_an_rclcpp_node(server):
    """Launch --rosbridge: roslibjs' getParams and Param on /talker's parameters, and failures."""
    _check_params(node_script('rosbridge_roslib.mjs', 'params', server.url, '/talker',
                              timeout=120), '/talker')


def test_roslibjs_params_of_a_page_node_through_the_relay(install):
    """
    Serve --rosbridge: roslibjs' Param on an rclcpp node in a page.

    The relay answers rosapi's parameter services by calling the node's rcl
    parameter services, which the page advertised to it; the answers are
    those of the Node.js server (the test above).
    """
    from concurrent.futures import ThreadPoolExecutor
    from served_page import explain_page
    from served_page import param_talker_tab
    from served_page import ServedPage
    tab = param_talker_tab('roslibjs is done')
    with ServedPage(install, args=['--rosbridge', '127.0.0.1:0']) as served:
        with ThreadPoolExecutor(1) as pool:
            page = pool.submit(served.run, tab, 180000)
            try:
                node_script('rosbridge_roslib.mjs', 'ready', served.rosbridge_url, '/chatter',
                            '/param_talker', '/param_talker/get_parameters', timeout=90)
                r = node_script('rosbridge_roslib.mjs', 'params', served.rosbridge_url,
                                '/param_talker', timeout=120)
            finally:
                node_script('rosbridge_roslib.mjs', 'say', served.rosbridge_url,
                            'roslibjs is done', timeout=30)
            result = page.result(timeout=300)
    assert result['ok'], explain_page(result)
    _check_params(r, '/param_talker')
