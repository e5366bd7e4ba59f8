# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Zenoh gateway (`colcon-wasm launch --zenoh`) against a real Zenoh router.

The router and the Zenoh peers that play rmw_zenoh participants are
eclipse-zenoh's (tests/zenoh_peers.py).

zenoh-pico 1.9.0 comes from the corpus snapshot ($COLCON_WASM_CORPUS,
src/eclipse-zenoh/zenoh-pico), unmodified: `colcon build --wasm` builds it
(with the recipe's patch, on a copy) and the bundled zenoh_wasm_gateway, on
the demo build as an underlay. The router is eclipse-zenoh's, on loopback.
Every launch is bounded by --duration, every wait by a timeout.
"""

import os
from pathlib import Path
import re
import shutil
import struct
import time

from colcon_helpers import colcon
import demo_build
import humble_build
import pytest
from rosbridge_launch import BackgroundLaunch
import zenoh_peers
from zenoh_peers import RmwZenohPeer
from zenoh_peers import ZenohRouter

CHATTER = 'demo_interfaces/msg/Chatter'
ADD_TWO_INTS = 'demo_interfaces/srv/AddTwoInts'
CONNECTED = re.compile(r'connected to the Zenoh router at (\S+) \(session ([0-9a-f]+)\)')


def zenoh_pico_source():
    """Return the corpus' zenoh-pico 1.9.0 (unpacked once), or skip saying what is missing."""
    if not (humble_build.corpus_snapshot() / 'src.tar.xz').is_file():
        pytest.skip(f'corpus snapshot not found at {humble_build.corpus_snapshot()} '
                    '(set COLCON_WASM_CORPUS): it holds zenoh-pico')
    source = humble_build.unpacked_source(humble_build.corpus_snapshot(), 'humble-corpus-src')
    path = source / 'eclipse-zenoh' / 'zenoh-pico'
    assert (path / 'version.txt').read_text().strip() == '1.9.0', path
    return path


_OVERLAY = {}


@pytest.fixture(scope='module')
def install(tmp_path_factory):
    """Build the overlay with zenoh-pico and the gateway on the demo build, once per run."""
    pytest.importorskip('zenoh', reason='eclipse-zenoh is missing: pip install -e .[test]')
    if 'install' in _OVERLAY:
        return _OVERLAY['install']
    source = zenoh_pico_source()
    underlay = demo_build.demo_install()
    workspace = tmp_path_factory.mktemp('zenoh_overlay')
    shutil.copytree(source, workspace / 'src' / 'zenoh-pico')
    # (colcon() checks that src/ is byte-identical after the build)
    colcon(workspace, 'build', '--wasm', '--wasm-underlay', str(underlay))
    # zenoh-pico writes its config.h at configure time: into the patched copy, not src/
    config = Path('include') / 'zenoh-pico' / 'config.h'
    assert (workspace / 'src' / 'zenoh-pico' / config).read_bytes() == \
        (source / config).read_bytes()
    module = workspace / 'install_wasm' / 'zenoh_wasm_gateway' / 'share' / 'zenoh_wasm_gateway'
    assert (module / 'zenoh_session.mjs').is_file() and (module / 'zenoh_session.wasm').is_file()
    _OVERLAY['install'] = workspace / 'install_wasm'
    return _OVERLAY['install']


@pytest.fixture
def router():
    """Run a router with tcp and ws listeners on loopback."""
    with ZenohRouter() as r:
        yield r


def _launch(install, *items, endpoint, duration=60):
    run = BackgroundLaunch(install, *items, '--zenoh', endpoint, duration=duration, wait_url=False)
    match = run.wait_for(CONNECTED, timeout=60)
    return run, match.group(2)


def _wait(predicate, timeout, what):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.2)
    raise AssertionError(f'timed out after {timeout} s waiting for {what}')


def test_a_talker_is_heard_by_a_zenoh_peer_with_rmw_zenoh_keys_attachments_tokens(
        install, router):
    peer = RmwZenohPeer(router.tcp)
    key = zenoh_peers.data_key('/chatter', CHATTER)
    peer.listen(key)
    try:
        run, zid = _launch(install, 'demo_nodes/talker', endpoint=router.tcp)
        with run:
            samples = _wait(lambda: len(peer.samples(key)) >= 3 and peer.samples(key),
                            30, 'three samples of the talker')
            tokens = peer.tokens()
            gateway = [t for t in tokens if f'/{zid}/' in t]
            node, = [t for t in gateway if '/NN/' in t]
            assert re.fullmatch(rf'@ros2_lv/0/{zid}/(\d+)/\1/NN/%/%/talker', node), node
            publisher, = [t for t in gateway if '/MP/' in t]
            assert publisher.endswith('/MP/%/%/talker/%chatter/'
                                      'demo_interfaces::msg::dds_::Chatter_/'
                                      'TypeHashNotSupported/::,10:,:,:,,'), publisher
            # the gateway's own node is not announced
            assert not any('zenoh_gateway' in t for t in tokens)
        for sample_key, payload, attachment in samples:
            assert sample_key == key
            text, count = zenoh_peers.parse_chatter(payload)
            assert text == f'Hello World: {count}'
        sequences = [zenoh_peers.parse_attachment(a)[0] for _, _, a in samples]
        assert sequences == list(range(sequences[0], sequences[0] + len(sequences)))
        gids = {zenoh_peers.parse_attachment(a)[2] for _, _, a in samples}
        assert len(gids) == 1 and len(next(iter(gids))) == 16
        stamp = zenoh_peers.parse_attachment(samples[-1][2])[1]
        assert abs(stamp - time.time_ns()) < 120e9
        # the launch is over: its tokens went with the session
        _wait(lambda: not [t for t in peer.tokens() if f'/{zid}/' in t], 20,
              'the tokens to be withdrawn')
    finally:
        peer.close()


def test_a_zenoh_publisher_is_heard_by_a_listener_and_samples_without_attachment_dropped(
        install, router):
    peer = RmwZenohPeer(router.tcp)
    try:
        node = peer.announce_node('py_talker')
        publish = peer.advertise('py_talker', node, '/chatter', CHATTER)
        run, _ = _launch(install, 'demo_nodes/listener', endpoint=router.tcp)
        with run:
            count = 0

            def heard():
                nonlocal count
                count += 1
                publish(zenoh_peers.cdr_chatter(f'from zenoh {count}', count))
                return run.count('I heard: [from zenoh') >= 3
            _wait(heard, 30, 'the listener to hear the peer')
            publish(zenoh_peers.cdr_chatter('no attachment', 999), with_attachment=False)
            run.wait_for('dropping a sample on /chatter from Zenoh', timeout=20)
            assert run.count('I heard: [no attachment]') == 0
            # the remote node is in the local graph: the gateway bridged /chatter in
            assert run.process.poll() is None
    finally:
        peer.close()


def _add_two_ints_request(a, b):
    return b'\x00\x01\x00\x00' + struct.pack('<qq', a, b)


def test_a_local_server_answers_a_zenoh_client(install, router):
    peer = RmwZenohPeer(router.tcp)
    try:
        run, zid = _launch(install, 'demo_nodes/add_two_ints_server', endpoint=router.tcp)
        with run:
            _wait(lambda: any('/SS/' in t and '%add_two_ints' in t for t in peer.tokens()),
                  30, "the server's SS token")
            replies = _wait(lambda: peer.call('/add_two_ints', ADD_TWO_INTS,
                                              _add_two_ints_request(2, 40), sequence=7),
                            30, 'a reply from the server')
        (payload, attachment, gid), = replies
        assert payload == b'\x00\x01\x00\x00' + struct.pack('<q', 42)
        seq, _, reply_gid = zenoh_peers.parse_attachment(attachment)
        assert (seq, reply_gid) == (7, gid)  # the client's sequence number and gid, echoed
    finally:
        peer.close()


def test_a_zenoh_server_answers_a_local_client(install, router):
    peer = RmwZenohPeer(router.tcp)
    calls = []

    def handler(request):
        a, b = struct.unpack_from('<qq', request, 4)
        calls.append((a, b))
        return b'\x00\x01\x00\x00' + struct.pack('<q', a + b)
    try:
        node = peer.announce_node('py_adder')
        peer.serve('py_adder', node, '/add_two_ints', ADD_TWO_INTS, handler)
        run, _ = _launch(install, 'demo_nodes/add_two_ints_client', endpoint=router.tcp)
        with run:
            match = run.wait_for(re.compile(r'Result of add_two_ints: for (-?\d+) \+ (-?\d+) = '
                                            r'(-?\d+)'), timeout=40)
        a, b, total = map(int, match.groups())
        assert (a, b) in calls, f'the Zenoh server was not called with {a}, {b}: {calls}'
        assert total == a + b
    finally:
        peer.close()


def test_the_websocket_endpoint_carries_the_same_traffic(install, router):
    peer = RmwZenohPeer(router.tcp)
    key = zenoh_peers.data_key('/chatter', CHATTER)
    peer.listen(key)
    try:
        run, _ = _launch(install, 'demo_nodes/talker', endpoint=router.ws)
        with run:
            _wait(lambda: len(peer.samples(key)) >= 2, 30, 'samples over the ws/ link')
    finally:
        peer.close()


def test_no_router_is_a_clear_error_retried_while_local_nodes_run(install):
    port = zenoh_peers.free_port()
    with BackgroundLaunch(install, 'demo_nodes/talker', 'demo_nodes/listener', '--zenoh',
                          f'tcp/127.0.0.1:{port}', duration=60, wait_url=False) as run:
        run.wait_for(re.compile(rf'cannot reach a Zenoh router at tcp/127.0.0.1:{port}: '
                                r'.*retrying in'), timeout=40)
        run.wait_for(re.compile(r'I heard: \[Hello World: 3\]'), timeout=40)
        # a router that comes up later is joined
        with ZenohRouter(tcp_port=port) as router:
            peer = RmwZenohPeer(router.tcp)
            try:
                run.wait_for(CONNECTED, timeout=40)
                _wait(lambda: any('/NN/%/%/talker' in t for t in peer.tokens()), 20,
                      "the talker's token once connected")
            finally:
                peer.close()


def test_a_router_restart_is_survived_and_what_waited_is_sent(install, monkeypatch):
    monkeypatch.setenv('COLCON_WASM_ZENOH_DEBUG', '1')
    router = ZenohRouter().start()
    key = zenoh_peers.data_key('/chatter', CHATTER)
    try:
        run, _ = _launch(install, 'demo_nodes/talker', endpoint=router.tcp)
        with run:
            peer = RmwZenohPeer(router.tcp)
            peer.listen(key)
            _wait(lambda: peer.samples(key), 30, 'a first sample')
            peer.close()
            router.kill()
            run.wait_for('lost the Zenoh router at', timeout=30)
            time.sleep(2.5)  # the talker publishes on (1 Hz): RELIABLE messages wait
            router.start()
            peer = RmwZenohPeer(router.tcp)
            peer.listen(key)
            try:
                _wait(lambda: run.count('connected to the Zenoh router at') >= 2, 40,
                      'the gateway to reconnect')
                waited = run.wait_for(re.compile(r'/chatter: sending the (\d+) messages that '
                                                 r'waited'), timeout=20)
                assert int(waited.group(1)) >= 2, waited.group(0)
                samples = _wait(lambda: len(peer.samples(key)) >= 2 and peer.samples(key), 30,
                                'samples after the restart')
                assert run.process.poll() is None
                # the sequence of the talker's publisher goes on across sessions
                assert zenoh_peers.parse_attachment(samples[0][2])[0] > 1
            finally:
                peer.close()
    finally:
        router.kill()


def test_a_token_that_does_not_parse_is_named_once_and_ignored(install, router):
    peer = RmwZenohPeer(router.tcp)
    try:
        peer.announce('@ros2_lv/0/abc/1/1/XX/%/%/weird')
        run, _ = _launch(install, 'demo_nodes/talker', endpoint=router.tcp)
        with run:
            run.wait_for("ignoring a liveliness token: '@ros2_lv/0/abc/1/1/XX/%/%/weird' has an "
                         "unknown entity kind 'XX'", timeout=30)
            run.wait_for(re.compile(r'Publishing: .Hello World: 3'), timeout=30)
            assert run.count('ignoring a liveliness token') == 1
    finally:
        peer.close()


def test_zenoh_without_the_gateway_package_names_what_to_build(tmp_path):
    underlay = demo_build.demo_install()
    result = os.popen(f"'{demo_build.venv_tool('colcon-wasm')}' launch --install-base "
                      f"'{underlay}' demo_nodes/talker --zenoh tcp/127.0.0.1:7447 "
                      '--duration 1 2>&1').read()
    assert "--zenoh needs the package 'zenoh_wasm_gateway'" in result
    assert 'git clone -b 1.9.0 https://github.com/eclipse-zenoh/zenoh-pico' in result


def test_a_bad_endpoint_is_refused_before_anything_starts(tmp_path):
    underlay = demo_build.demo_install()
    result = os.popen(f"'{demo_build.venv_tool('colcon-wasm')}' run --install-base "
                      f"'{underlay}' --zenoh 127.0.0.1:7447 demo_nodes talker 2>&1").read()
    assert "--zenoh '127.0.0.1:7447' is not a Zenoh endpoint: expected ws/HOST:PORT or " \
        'tcp/HOST:PORT' in result


def test_a_crashed_nodes_tokens_are_withdrawn_and_the_others_stay(install, router, tmp_path):
    launch_file = tmp_path / 'crash.launch.yaml'
    launch_file.write_text(
        'launch:\n'
        '- node: {pkg: demo_nodes, exec: crasher, args: "--ros-args -p delay:=6.0"}\n'
        '- node: {pkg: demo_nodes, exec: talker}\n')
    peer = RmwZenohPeer(router.tcp)
    try:
        run, zid = _launch(install, launch_file, endpoint=router.tcp)
        with run:
            def mine():
                return [t for t in peer.tokens() if f'/{zid}/' in t]
            _wait(lambda: any(t.endswith('/NN/%/%/crasher') for t in mine()), 30,
                  "the crasher's token")
            assert any('/MP/%/%/crasher/%heartbeat/' in t for t in mine())
            run.wait_for('I will crash in 6.0 s', timeout=10)
            _wait(lambda: not any('/crasher' in t for t in mine()), 40,
                  "the crasher's tokens to go after it crashed")
            assert any(t.endswith('/NN/%/%/talker') for t in mine()), mine()
    finally:
        peer.close()
