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
        # the relay asks for the CDR form only: the other tab subscribes with cbor-raw
        {'until': "(colconWasm.session.bridge.forms.get('/chatter') || {}).cdr "
                  "&& JSON.stringify(colconWasm.session.bridge.forms.get('/chatter'))",
         'save': 'forms', 'timeoutMs': 30000},
        {'sleep': 8000},
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
    assert json.loads(first['saved']['forms']) == {'json': False, 'cdr': True}, first['saved']


def _with_page(served, tab, topic, scenario, timeout_ms=60000):
    """Run a tab; once the relay lists ``topic``, run a roslibjs scenario against the relay."""
    from served_page import explain_page
    with ThreadPoolExecutor(1) as pool:
        page = pool.submit(served.run, tab, timeout_ms)
        node_script('rosbridge_roslib.mjs', 'ready', served.rosbridge_url, topic, timeout=90)
        r = node_script('rosbridge_roslib.mjs', scenario, served.rosbridge_url)
        result = page.result(timeout=200)
    assert result['ok'], explain_page(result)
    return r


def test_roslibjs_throttle_rate_and_queue_length_through_the_relay(served):
    """As against the Node.js server: throttle_rate drops, queue_length 1 keeps the newest."""
    tab = [
        dict(PROBE, start='talker', args=['param_talker', '--ros-args', '-r', '__node:=talker']),
        {'until': CONNECTED},
        {'wait': 'talker', 'text': 'NAME /talker TOPIC /chatter'},
        {'sleep': 16000},
    ]
    r = _with_page(served, tab, '/chatter', 'throttle')
    assert 25 <= r['all'] <= 35, r
    assert 5 <= r['throttled'] <= 7, r
    assert all(g >= 450 for g in r['throttledGaps']), r
    assert 3 <= len(r['queued']) <= 5, r
    assert all(g >= 900 for g in r['queuedGaps']), r
    steps = [b - a for a, b in zip(r['queued'], r['queued'][1:])]
    assert all(8 <= s <= 12 for s in steps), r


def test_roslibjs_images_cbor_raw_and_cbor_through_the_relay(served):
    """640x480 rgb8 images through a C++ node of a tab: cbor-raw (the page's CDR) and cbor."""
    tab = [
        dict(PROBE, start='pong', args=['bench_pong_image']),
        {'until': CONNECTED},
        {'wait': 'pong', 'text': '[bench_pong]: READY'},
        {'sleep': 25000},
    ]
    r = _with_page(served, tab, '/bench/ping', 'images')
    assert r['rawHasTime']
    assert (r['rawHeight'], r['rawWidth']) == (480, 640)
    assert r['rawBytes'] > 640 * 480 * 3
    assert r['rawDataTail'] == r['expectedTail']
    assert r['cborDataIsBytes'] and r['cborDataLength'] == 640 * 480 * 3
    assert (r['cborEncoding'], r['cborFrame']) == ('rgb8', 'camera')


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
        node_script('rosbridge_roslib.mjs', 'ready', served.rosbridge_url, '/chatter',
                    '/add_server', '/add', timeout=90)
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


def test_json_publisher_to_cbor_raw_and_bad_binary_on_the_relay_port(served):
    """On serve's port: JSON from a JSON-only publisher reaches cbor-raw, with one warning."""
    from test_relay_units import Client
    pub, sub = Client.connect(served.rosbridge_url), Client.connect(served.rosbridge_url)
    for c in (pub, sub):
        assert c.receive()['op'] == 'colcon_wasm_relay'
        c.send({'op': 'set_level', 'level': 'warning'})
    pub.send({'op': 'advertise', 'topic': '/plain', 'type': 'std_msgs/msg/String'})
    sub.send({'op': 'subscribe', 'id': 'p1', 'topic': '/plain', 'type': 'std_msgs/msg/String',
              'compression': 'cbor-raw'})
    time.sleep(0.3)
    for i in range(3):
        pub.send({'op': 'publish', 'topic': '/plain', 'msg': {'data': f'json {i}'}})
    seen = [sub.receive() for _ in range(4)]
    assert [m['op'] for m in seen].count('status') == 1, seen
    assert [m['msg']['data'] for m in seen if m['op'] == 'publish'] == [
        'json 0', 'json 1', 'json 2'], seen
    sub.send(b'\xff\x00', binary=True)
    error = sub.until(lambda m: m.get('op') == 'status')
    assert error['level'] == 'error' and 'not CBOR' in error['msg'], error
    pub.send({'op': 'publish', 'topic': '/plain', 'msg': {'data': 'after'}})
    assert sub.until(lambda m: m.get('op') == 'publish')['msg'] == {'data': 'after'}
