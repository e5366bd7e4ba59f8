# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Lost remote nodes and a lost gateway turn into liveliness events and graph updates.

On the local side, a subscription behind the gateway (tests/js/zenoh_events.mjs)
has one local publisher per remote rmw_zenoh publisher: a remote node that
goes, or a router that goes, is a LIVELINESS_CHANGED event (alive count
down) and a local graph with one publisher less. On the remote side, a
gateway killed without a goodbye has its tokens withdrawn by the router. The
remote nodes are eclipse-zenoh peers playing rmw_zenoh participants
(tests/zenoh_peers.py); the router is eclipse-zenoh's, on loopback. The
install is test_zenoh_gateway's (zenoh-pico of the corpus on the demo).
"""

import json
from pathlib import Path
import queue
import subprocess
import threading
import time

import demo_build
import pytest
from test_zenoh_gateway import CHATTER
from test_zenoh_gateway import install  # noqa: F401 (the module fixture)
from zenoh_peers import RmwZenohPeer
from zenoh_peers import ZenohRouter

SCRIPT = Path(__file__).resolve().parent / 'js' / 'zenoh_events.mjs'


def _read_lines(stream, put):
    for line in stream:
        put(line)


class EventsListener:
    """tests/js/zenoh_events.mjs: its JSON lines, one per change."""

    def __init__(self, install_base, endpoint):
        """Start the script with the gateway (of `install_base`) to `endpoint`."""
        module = (Path(install_base) / 'zenoh_wasm_gateway' / 'share' / 'zenoh_wasm_gateway'
                  / 'zenoh_session.mjs')
        types = [str(p) for p in
                 demo_build.demo_install().glob('*/share/*/colcon_wasm/types.json')]
        self.process = subprocess.Popen(
            ['node', str(SCRIPT), json.dumps({'endpoint': endpoint, 'module': str(module),
                                              'types': types, 'topic': '/chatter',
                                              'type': CHATTER})],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines = queue.Queue()
        self.seen = []
        self.stderr = []
        threading.Thread(target=_read_lines, args=(self.process.stdout, self.lines.put),
                         daemon=True).start()
        threading.Thread(target=_read_lines, args=(self.process.stderr, self.stderr.append),
                         daemon=True).start()

    def wait_for(self, predicate, what, timeout=30):
        """Return the first status line (from now on) for which predicate is true."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                status = json.loads(self.lines.get(timeout=0.5))
            except queue.Empty:
                continue
            self.seen.append(status)
            if predicate(status):
                return status
        raise AssertionError(f'timed out after {timeout} s waiting for {what}; seen '
                             f'{self.seen[-5:]}; stderr: {"".join(self.stderr)[-2000:]}')

    def kill(self):
        """Kill the script (the gateway's session goes without a goodbye)."""
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait(timeout=10)


@pytest.fixture
def router():
    """Run a router with tcp and ws listeners on loopback."""
    with ZenohRouter() as r:
        yield r


def _remote_talker(endpoint, name):
    peer = RmwZenohPeer(endpoint)
    node = peer.announce_node(name)
    peer.advertise(name, node, '/chatter', CHATTER)
    return peer


def test_a_remote_node_that_goes_is_a_liveliness_change_and_a_graph_update(
        install, router):  # noqa: F811
    first = _remote_talker(router.tcp, 'py_talker_1')
    second = _remote_talker(router.tcp, 'py_talker_2')
    open_peers = [first, second]
    listener = EventsListener(install, router.tcp)
    try:
        listener.wait_for(lambda s: s['alive'] == 2 and s['publishers'] == 2
                          and {'/py_talker_1', '/py_talker_2'} <= set(s['remoteNodes']),
                          'two remote publishers alive for the local subscription')
        open_peers.remove(first)
        first.close()
        gone = listener.wait_for(lambda s: s['alive'] == 1, 'the first remote node to go')
        assert gone['aliveChange'] == -1, gone
        listener.wait_for(lambda s: s['publishers'] == 1 and '/py_talker_1' not in s['remoteNodes']
                          and '/py_talker_2' in s['remoteNodes'],
                          'the local graph without the first remote node')
        open_peers.remove(second)
        second.close()
        gone = listener.wait_for(lambda s: s['alive'] == 0, 'the second remote node to go')
        assert gone['aliveChange'] == -1, gone
        listener.wait_for(lambda s: s['publishers'] == 0 and not s['remoteNodes'],
                          'the local graph without remote nodes')
    finally:
        listener.kill()
        for peer in open_peers:
            peer.close()


def test_a_lost_router_and_a_lost_gateway_are_seen_on_both_sides(install):  # noqa: F811
    router = ZenohRouter().start()
    talker = None
    listener = None
    try:
        talker = _remote_talker(router.tcp, 'py_talker')
        listener = EventsListener(install, router.tcp)
        listener.wait_for(lambda s: s['alive'] == 1 and '/py_talker' in s['remoteNodes'],
                          'the remote publisher alive for the local subscription')
        # the router goes: every remote node goes from the local graph, and its publisher
        router.kill()
        gone = listener.wait_for(lambda s: s['alive'] == 0 and not s['remoteNodes'],
                                 'the remote side to go with the router')
        assert gone['aliveChange'] == -1 and gone['publishers'] == 0, gone
        talker.close()
        router.start()
        talker = _remote_talker(router.tcp, 'py_talker')
        listener.wait_for(lambda s: s['state'] == 'connected' and s['alive'] == 1,
                          'the remote publisher again, once the gateway reconnected', timeout=60)
        # the gateway goes without a goodbye: the router withdraws its tokens
        observer = RmwZenohPeer(router.tcp)
        try:
            deadline = time.monotonic() + 20
            while not any('/NN/%/%/events_listener' in t for t in observer.tokens()):
                assert time.monotonic() < deadline, "the local node's token never came"
                time.sleep(0.2)
            listener.kill()
            deadline = time.monotonic() + 30
            while any('/NN/%/%/events_listener' in t for t in observer.tokens()):
                assert time.monotonic() < deadline, "the killed gateway's tokens stayed"
                time.sleep(0.2)
        finally:
            observer.close()
    finally:
        if listener:
            listener.kill()
        if talker:
            talker.close()
        router.kill()
