# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rosbridge relay of `colcon-wasm serve --rosbridge`: tabs share one graph.

Two pages of one serve (headless Chromium, tests/js/page_session.mjs), each
with its own bus, bridged by their rosbridge clients through serve's
/rosbridge: a C++ talker in one, a C++ listener in the other. Then
roslibjs and roslibpy on the relay's port against the C++ nodes of a page.
The probe of rmw_wasm_cpp_node_tests (tests/rclcpp_build.py). All on
127.0.0.1, every wait bounded.
"""

from concurrent.futures import ThreadPoolExecutor
import json
from pathlib import Path
import subprocess
import sys
import time

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rclcpp_build import rclcpp_build  # noqa: E402, I100, I202
from rosbridge_launch import node_script  # noqa: E402

PROBE = {'pkg': 'rmw_wasm_cpp_node_tests', 'exe': 'probe'}
CONNECTED = ("colconWasm.session.bridge && colconWasm.session.bridge.state === 'connected' "
             '&& colconWasm.session.bridge.relay')


@pytest.fixture(scope='module')
def install():
    """Get the Humble build with the probe."""
    return rclcpp_build().install


@pytest.fixture(scope='module')
def served(install):
    """One `colcon-wasm serve --rosbridge 127.0.0.1:0` for the module."""
    from served_page import ServedPage
    with ServedPage(install, args=['--rosbridge', '127.0.0.1:0']) as page:
        assert page.rosbridge_url and page.rosbridge_url.startswith('ws://127.0.0.1:'), \
            page.rosbridge_url
        yield page


def test_two_tabs_share_one_graph(served):
    """A talker in one tab is seen (marked remote) and heard (by a listener) in another."""
    from served_page import explain_page
    talker_tab = [
        dict(PROBE, start='talker', args=['param_talker', '--ros-args', '-p',
                                          'greeting:=from_tab_one']),
        {'until': CONNECTED},
        {'wait': 'talker', 'text': 'NAME /param_talker TOPIC /chatter'},
        {'sleep': 12000},
    ]
    listener_tab = [
        {'sleep': 1500},
        dict(PROBE, start='listener', args=['listener']),
        {'until': CONNECTED},
        {'wait': 'listener', 'regex': r'HEARD from_tab_one \d+', 'count': 5, 'timeoutMs': 30000},
        {'until': 'colconWasm.session.graph.nodes.some((n) => n.remote && n.fqn === '
                  "'/param_talker') "
                  "&& colconWasm.session.graph.nodes.filter((n) => n.remote).map((n) => n.fqn + ' "
                  "' + n.process).join('\\n')",
         'save': 'remote', 'timeoutMs': 10000},
    ]
    with ThreadPoolExecutor(2) as pool:
        one = pool.submit(served.run, talker_tab, 60000)
        two = pool.submit(served.run, listener_tab, 60000)
        first, second = one.result(timeout=200), two.result(timeout=200)
    assert second['ok'], explain_page(second)
    assert first['ok'], explain_page(first)
    heard = [int(line.rsplit(' ', 1)[1]) for line in second['logs']['listener']
             if 'HEARD from_tab_one' in line]
    assert heard == sorted(heard) and len(heard) >= 5, heard
    assert '/param_talker remote ' in second['saved']['remote'], second['saved']


def test_roslibjs_and_roslibpy_through_the_relay(served):
    """Third-party clients on the relay's port: graph, typed fields, publish, call, status."""
    from served_page import explain_page
    tab = [
        dict(PROBE, start='talker', args=['param_talker', '--ros-args', '-r', '__node:=talker']),
        dict(PROBE, start='listener', args=['listener']),
        dict(PROBE, start='add', args=['add_server', '--ros-args', '-r', 'hold:=add']),
        {'until': CONNECTED},
        {'wait': 'listener', 'text': 'HEARD from roslibjs 19', 'timeoutMs': 60000},
        {'wait': 'listener', 'text': 'HEARD from roslibpy 9', 'timeoutMs': 60000},
    ]
    with ThreadPoolExecutor(1) as pool:
        page = pool.submit(served.run, tab, 90000)
        time.sleep(4)
        js = node_script('rosbridge_roslib.mjs', 'basic', served.rosbridge_url)
        py = subprocess.run(
            [sys.executable, str(Path(__file__).resolve().parent / 'rosbridge_roslibpy.py'),
             served.rosbridge_url.rsplit(':', 1)[1]], capture_output=True, text=True, timeout=90)
        bad = node_script('rosbridge_raw.mjs', 'bad', served.rosbridge_url)
        result = page.result(timeout=200)
    assert result['ok'], explain_page(result)
    topics = dict(zip(js['topics']['topics'], js['topics']['types']))
    assert topics['/chatter'] == 'std_msgs/msg/String', topics
    assert '/talker' in js['nodes'] and '/add_server' in js['nodes'], js['nodes']
    assert '/add' in js['services'], js['services']
    assert js['topicType'] == 'std_msgs/msg/String'
    assert js['details'][:2] == ['sensor_msgs/Image', 'std_msgs/Header']
    assert all(h.startswith('hello ') for h in js['heard']), js['heard']
    assert js['sum'] == {'sum': 42}
    assert 'does not exist' in js['missingError']
    assert py.returncode == 0, py.stderr[-3000:]
    r = json.loads(py.stdout.strip().splitlines()[-1])
    assert r['sum'] == 2 ** 62 + 7 and any(h.startswith('hello ') for h in r['heard']), r
    by = {o['what']: o['status'] for o in bad['out']}
    assert 'malformed JSON' in by['malformed']['msg'] and by['malformed']['id'] == 'm1'
    assert 'unknown operation "fly"' in by['unknown op']['msg']
    assert "field 'topic' is missing" in by['missing topic']['msg']
    assert bad['after'] and bad['fragmented']
