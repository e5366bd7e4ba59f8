# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Foxglove WebSocket server of `colcon-wasm launch --foxglove` with real clients.

The client is npm `@foxglove/ws-protocol`'s FoxgloveClient over npm `ws`,
decoding and encoding with `@foxglove/rosmsg` and
`@foxglove/rosmsg2-serialization` from the advertised schemas
(tests/js/foxglove_client.mjs), against the C++ talker, listener and
add_two_ints_server of the demo build (tests/demo_build.py). All on
127.0.0.1, every wait bounded.
"""

from pathlib import Path
import re
import socket
import subprocess
import sys
import textwrap

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from foxglove_assets_case import check_fetch_asset  # noqa: E402
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from rosbridge_launch import node_script  # noqa: E402

URL = re.compile(r'foxglove server listening on (ws://\S+)')

LAUNCH = """
    launch:
    - node: {pkg: demo_nodes, exec: talker, args: "--ros-args -p rate:=10"}
    - node: {pkg: demo_nodes, exec: listener}
    - node: {pkg: demo_nodes, exec: add_two_ints_server}
"""


@pytest.fixture(scope='module')
def install():
    """Build the demo workspace."""
    return demo_build.demo_install()


@pytest.fixture(scope='module')
def server(install, tmp_path_factory):
    """One launch of the demo nodes with a Foxglove server, for the module."""
    path = tmp_path_factory.mktemp('foxglove') / 'foxglove.launch.yaml'
    path.write_text(textwrap.dedent(LAUNCH).lstrip(), encoding='utf-8')
    with BackgroundLaunch(install, '--foxglove', '127.0.0.1:0', path, duration=120,
                          url_pattern=URL) as run:
        run.wait_for("Publishing: 'Hello World: 3'", timeout=60)
        run.wait_for('Ready to add two ints', timeout=60)
        yield run


def test_foxglove_client_decodes_publishes_calls(server):
    """Advertise, subscribe and decode with Foxglove's decoder; publish; call; bad input."""
    r = node_script('foxglove_client.mjs', 'demo', server.url)
    assert r['protocol'] == 'foxglove.websocket.v1'
    assert r['sdkProtocol'] == 'foxglove.sdk.v1'
    info = r['info']
    assert {'clientPublish', 'services', 'connectionGraph'} <= set(info['capabilities'])
    assert info['supportedEncodings'] == ['cdr', 'json']
    channel = r['channel']
    assert channel['encoding'] == 'cdr' and channel['schemaEncoding'] == 'ros2msg'
    assert channel['schemaName'] == 'demo_interfaces/msg/Chatter'
    definition = (Path(demo_build.REPO) / 'demo' / 'src' / 'demo_interfaces' / 'msg' /
                  'Chatter.msg').read_text(encoding='utf-8')
    assert channel['schema'] == definition
    # what the C++ talker published, decoded by @foxglove/rosmsg2-serialization
    talked = [m for m in r['heard'] if m['data'].startswith('Hello World: ')]
    assert len(talked) >= 3
    for m in talked:
        assert m['data'] == f"Hello World: {m['count']}"
        server.wait_for(f"Publishing: '{m['data']}'", timeout=5)
    counts = [m['count'] for m in talked]
    assert counts == list(range(counts[0], counts[0] + len(counts)))
    stamps = r['timestamps']
    assert stamps == sorted(stamps) and stamps[0] > 1.6e18
    # its own messages came back on the channel it subscribed to, in both encodings
    mine = [m for m in r['heard'] if m['data'].startswith('from foxglove')]
    assert {'from foxglove cdr 4', 'from foxglove json 4'} <= {m['data'] for m in mine}
    for i in range(5):
        server.wait_for(f'I heard: [from foxglove cdr {i}]', timeout=10)
        server.wait_for(f'I heard: [from foxglove json {i}]', timeout=10)
    assert r['sumCdr'] == {'sum': 42} and r['sumJson'] == {'sum': 11}
    server.wait_for('Incoming request: a: 40 b: 2', timeout=5)
    assert r['missing']['callId'] == 9 and 'no service 9999' in r['missing']['message']
    assert '/add_two_ints' in r['services']
    graph = r['graph']
    published = {t['name']: t['publisherIds'] for t in graph['publishedTopics']}
    assert '/talker' in published['/chatter']
    provided = {s['name']: s['providerIds'] for s in graph['advertisedServices']}
    assert provided['/add_two_ints'] == ['/add_two_ints_server']
    # bad JSON, an unknown op, an unknown binary opcode: a status each, and the rest went on
    messages = [s['message'] for s in r['status'] if s.get('op') == 'status']
    assert any(m.startswith('malformed JSON') for m in messages), messages
    assert any("unknown op 'noSuchOp'" in m for m in messages), messages
    assert any('unknown binary opcode 0x7f' in m for m in messages), messages
    assert all(s['level'] == 2 for s in r['status'])


def test_foxglove_refuses_a_client_without_its_subprotocol(server):
    """A WebSocket client that offers no Foxglove subprotocol gets HTTP 400 with the reason."""
    r = node_script('foxglove_client.mjs', 'refused', server.url)
    assert r['status'] == 400
    assert 'foxglove.websocket.v1' in r['body']


def test_foxglove_port_in_use_stops_before_the_nodes(install, tmp_path):
    """A taken port is a clear error, and no node starts."""
    taken = socket.socket()
    taken.bind(('127.0.0.1', 0))
    taken.listen(1)
    try:
        port = taken.getsockname()[1]
        result = subprocess.run(
            [str(demo_build.venv_tool('colcon-wasm')), 'run', '--install-base', str(install),
             '--foxglove', f'127.0.0.1:{port}', '--duration', '5', 'demo_nodes',
             'talker'], capture_output=True, text=True, timeout=60)
    finally:
        taken.close()
    assert result.returncode == 1
    assert f'port {port} on 127.0.0.1 is already in use' in result.stderr
    assert '--foxglove HOST:PORT' in result.stderr
    assert 'process started' not in result.stdout


def test_foxglove_bad_address(install):
    """--foxglove with something that is no [HOST:]PORT names the option."""
    result = subprocess.run(
        [str(demo_build.venv_tool('colcon-wasm')), 'run', '--install-base', str(install),
         '--foxglove', 'nowhere', 'demo_nodes', 'talker'],
        capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert "--foxglove 'nowhere' is not [HOST:]PORT" in result.stderr


def test_foxglove_big_topic_drops_and_does_not_starve_a_small_one(server):
    """A client that stops reading: the flooding topic's queue drops (counted), /chatter's not."""
    r = node_script('foxglove_client.mjs', 'slow', server.url)
    assert 0 < r['big'] < r['sent'], r
    chatter = r['chatter']
    assert len(chatter) >= 10, r
    assert chatter == list(range(chatter[0], chatter[0] + len(chatter))), r
    drops = [s for s in r['status'] if s.get('id') == 'dropped:/fox/big']
    assert drops and drops[0]['level'] == 1, r['status']
    assert not [s for s in r['status'] if s.get('id') == 'dropped:/chatter'], r['status']
    match = server.wait_for(re.compile(r'dropped for it: (\d+) of /fox/big'), timeout=10)
    assert 0 < int(match.group(1)) <= r['sent'] - r['big']


def test_foxglove_fetch_asset_serves_package_files_and_refuses_the_rest(
        server, install, tmp_path):
    """fetchAsset: package:// files of the install space; each refusal names why."""
    check_fetch_asset(server.url, install, tmp_path)
