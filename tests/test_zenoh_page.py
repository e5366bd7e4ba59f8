# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The launcher page's Zenoh gateway (`?zenoh=ws/HOST:PORT`) in headless Chromium.

It runs against eclipse-zenoh's router (its WebSocket listener on loopback): a page
and a Zenoh peer playing an rmw_zenoh participant, a page and a Node.js
launch, and two pages, each pair on one graph through the router.
The install is test_zenoh_gateway's (zenoh-pico of the corpus on the demo).
"""

import re
import threading

import pytest
from rosbridge_launch import BackgroundLaunch
from served_page import explain_page
from served_page import ServedPage
from test_zenoh_gateway import CHATTER
from test_zenoh_gateway import CONNECTED
from test_zenoh_gateway import install  # noqa: F401 (the module fixture)
import zenoh_peers
from zenoh_peers import RmwZenohPeer
from zenoh_peers import ZenohRouter

CONNECTED_STEP = {'until': 'colconWasm.session.zenoh && colconWasm.session.zenoh.state === '
                           "'connected'", 'timeoutMs': 60000}


@pytest.fixture
def router():
    """Run a router with tcp and ws listeners on loopback."""
    with ZenohRouter() as r:
        yield r


def test_a_page_joins_a_zenoh_peer_both_ways(install, router):  # noqa: F811
    peer = RmwZenohPeer(router.tcp)
    key = zenoh_peers.data_key('/chatter', CHATTER)
    peer.listen(key)
    node = peer.announce_node('py_talker')
    publish = peer.advertise('py_talker', node, '/news', CHATTER)
    stop = threading.Event()

    def keep_publishing():
        count = 0
        while not stop.wait(0.3):
            count += 1
            publish(zenoh_peers.cdr_chatter(f'from zenoh {count}', count))
    publisher = threading.Thread(target=keep_publishing, daemon=True)
    publisher.start()
    try:
        with ServedPage(install) as page:
            result = page.run([
                {'start': 'talker', 'pkg': 'demo_nodes', 'exe': 'talker', 'args': []},
                {'start': 'listener', 'pkg': 'demo_nodes', 'exe': 'listener',
                 'args': ['--ros-args', '-r', 'chatter:=news']},
                CONNECTED_STEP,
                {'wait': 'listener', 'regex': r'I heard: \[from zenoh \d+\]', 'count': 3},
                {'until': 'colconWasm.session.graph.nodes.filter((n) => n.remote).map((n) => '
                          "n.fqn + ' ' + n.process).join('\\n') || null", 'save': 'remote'},
                {'until': "document.querySelector('#zenoh-state').textContent", 'save': 'chip'},
                {'until': 'colconWasm.session.zenoh.status().zid', 'save': 'zid'},
                {'sleep': 1500},
            ], query=f'?zenoh={router.ws}')
            assert result['ok'], explain_page(result)
        assert f'/py_talker remote zenoh {router.ws}' in result['saved']['remote'], result['saved']
        assert result['saved']['chip'] == 'zenoh: connected', result['saved']
        texts = [zenoh_peers.parse_chatter(p)[0] for _, p, _ in peer.samples(key)]
        assert any(re.fullmatch(r'Hello World: \d+', t) for t in texts), texts
    finally:
        stop.set()
        publisher.join(timeout=5)
        peer.close()


def test_a_page_and_a_node_launch_share_one_graph_through_the_router(install, router):  # noqa: F811,E501
    with BackgroundLaunch(install, 'demo_nodes/listener', '--zenoh', router.tcp, duration=120,
                          wait_url=False) as launch:
        launch.wait_for(CONNECTED, timeout=60)
        with ServedPage(install) as page:
            result = page.run([
                {'start': 'talker', 'pkg': 'demo_nodes', 'exe': 'talker', 'args': []},
                CONNECTED_STEP,
                {'wait': 'talker', 'regex': r'Publishing: .Hello World: 6', 'timeoutMs': 60000},
            ], query=f'?zenoh={router.ws}')
            assert result['ok'], explain_page(result)
        launch.wait_for(re.compile(r'I heard: \[Hello World: \d+\]'), timeout=30)


def test_two_pages_talk_through_the_router(install, router):  # noqa: F811
    results = {}

    def talker_page():
        with ServedPage(install) as page:
            results['talker'] = page.run([
                {'start': 'talker', 'pkg': 'demo_nodes', 'exe': 'talker', 'args': []},
                CONNECTED_STEP,
                {'wait': 'talker', 'regex': r'Publishing: .Hello World: 40', 'timeoutMs': 80000},
            ], query=f'?zenoh={router.ws}', timeout_ms=120000)
    thread = threading.Thread(target=talker_page, daemon=True)
    thread.start()
    try:
        with ServedPage(install) as page:
            listener = page.run([
                {'start': 'listener', 'pkg': 'demo_nodes', 'exe': 'listener', 'args': []},
                CONNECTED_STEP,
                {'wait': 'listener', 'regex': r'I heard: \[Hello World: \d+\]', 'count': 3,
                 'timeoutMs': 60000},
            ], query=f'?zenoh={router.ws}')
    finally:
        thread.join(timeout=180)
    assert listener['ok'], explain_page(listener)
    assert results.get('talker', {}).get('ok'), explain_page(results.get('talker', {}))


def test_the_page_without_the_gateway_says_why(install):  # noqa: F811
    import demo_build
    with ServedPage(demo_build.demo_install()) as page:
        result = page.run([
            {'until': "document.querySelector('#zenoh-error') && "
                      "document.querySelector('#zenoh-error').textContent", 'save': 'error'},
            {'until': "document.querySelector('#zenoh-endpoint').disabled", 'save': 'off'},
        ], query='?zenoh=ws/127.0.0.1:7447')
        assert result['ok'], explain_page(result)
    assert 'the install space has no zenoh_wasm_gateway' in result['saved']['error']


def test_a_pages_services_and_tokens_reach_a_zenoh_peer_both_ways(install, router):  # noqa: F811
    import struct
    peer = RmwZenohPeer(router.tcp)
    calls = []

    def handler(request):
        a, b = struct.unpack_from('<qq', request, 4)
        calls.append((a, b))
        return b'\x00\x01\x00\x00' + struct.pack('<q', a + b)
    node = peer.announce_node('py_adder')
    peer.serve('py_adder', node, '/py_add', 'demo_interfaces/srv/AddTwoInts', handler)
    found = {}

    def call_and_list():
        try:
            found['tokens'] = [t for t in peer.tokens() if '/SS/' in t or '/NN/' in t]
            if any('%add_two_ints' in t for t in found['tokens']):
                found['replies'] = peer.call(
                    '/add_two_ints', 'demo_interfaces/srv/AddTwoInts',
                    b'\x00\x01\x00\x00' + struct.pack('<qq', 20, 22), sequence=3)
        except Exception as e:  # reported by the assertions below
            found['error'] = repr(e)
    try:
        with ServedPage(install) as page:
            lister_stop = threading.Event()

            def poll():
                while not lister_stop.wait(1.0) and not found.get('replies'):
                    call_and_list()
            lister = threading.Thread(target=poll, daemon=True)
            lister.start()
            result = page.run([
                {'start': 'server', 'pkg': 'demo_nodes', 'exe': 'add_two_ints_server', 'args': []},
                {'start': 'client', 'pkg': 'demo_nodes', 'exe': 'add_two_ints_client',
                 'args': ['--ros-args', '-r', 'add_two_ints:=py_add']},
                CONNECTED_STEP,
                {'wait': 'client', 'regex': r'Result of add_two_ints: for -?\d+ \+ -?\d+ = -?\d+',
                 'timeoutMs': 60000},
                {'until': 'colconWasm.session.zenoh.status().zid', 'save': 'zid'},
                {'sleep': 3000},
            ], query=f'?zenoh={router.ws}')
            lister_stop.set()
            lister.join(timeout=20)
            assert result['ok'], explain_page(result)
        zid = result['saved']['zid']
        tokens = [t for t in found.get('tokens', []) if f'/{zid}/' in t]
        assert any(t.endswith('/NN/%/%/add_two_ints_server') for t in tokens), found
        assert any('/SS/%/%/add_two_ints_server/%add_two_ints/' in t for t in tokens), found
        (payload, attachment, gid), = found.get('replies') or [(None, None, None)]
        assert payload == b'\x00\x01\x00\x00' + struct.pack('<q', 42), found
        assert zenoh_peers.parse_attachment(attachment)[0] == 3
        assert calls, 'the page client never called the Zenoh server'
    finally:
        peer.close()
