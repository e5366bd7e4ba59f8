# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Messages larger than one Zenoh batch: fragmented by zenoh-pico, carried whole and reliably.

zenoh-pico fragments a message larger than the batch size the router agreed
(65535 bytes on ws/, 49152 on the router's tcp/ links). The gateway's link
(packages/wasm_js/src/bridges/zenoh/link.mjs) sends each fragment reliably
(zenoh-pico 1.9 marks them best effort) and, on tcp/, counts the 2 bytes of
each batch's length in the batch size. The router and the subscriber are
eclipse-zenoh's, with shared memory off (on one host zenoh would carry large
messages in shared memory: a remote subscriber's path is the network). The
install is test_zenoh_gateway's (zenoh-pico of the corpus on the demo).
"""

import json
from pathlib import Path
import struct
import subprocess
import threading
import time

import pytest
from test_zenoh_gateway import _launch
from test_zenoh_gateway import install  # noqa: F401 (the module fixture)
import zenoh_peers
from zenoh_peers import ZenohRouter

SCRIPT = Path(__file__).resolve().parent / 'js' / 'zenoh_burst.mjs'
NO_SHM = {'transport/shared_memory/enabled': False}


@pytest.fixture
def router():
    """Run a router with tcp and ws listeners on loopback, shared memory off."""
    with ZenohRouter(config=NO_SHM) as r:
        yield r


class Subscriber:
    """An eclipse-zenoh subscriber (shared memory off) that keeps the payloads' first bytes."""

    def __init__(self, endpoint, key):
        """Open a client session and subscribe to `key`."""
        import zenoh
        conf = zenoh.Config()
        conf.insert_json5('mode', '"client"')
        conf.insert_json5('connect/endpoints', json.dumps([endpoint]))
        conf.insert_json5('transport/shared_memory/enabled', 'false')
        self.session = zenoh.open(conf)
        self.lock = threading.Lock()
        self.heads = []
        self.sizes = []
        self.sub = self.session.declare_subscriber(key, self._sample)

    def _sample(self, sample):
        payload = sample.payload.to_bytes()
        with self.lock:
            self.heads.append(payload[:16])
            self.sizes.append(len(payload))

    def close(self):
        """Close the session."""
        self.sub.undeclare()
        self.session.close()


@pytest.mark.parametrize('scheme', ['ws', 'tcp'])
def test_a_burst_of_large_reliable_messages_arrives_whole_and_in_order(
        install, router, scheme):  # noqa: F811
    key = 'test/large'
    subscriber = Subscriber(router.tcp, key)
    module = (Path(install) / 'zenoh_wasm_gateway' / 'share' / 'zenoh_wasm_gateway'
              / 'zenoh_session.mjs')
    try:
        done = subprocess.run(
            ['node', str(SCRIPT), json.dumps({
                'endpoint': getattr(router, scheme), 'module': str(module), 'key': key,
                'size': 65536, 'count': 300})],
            capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr[-2000:]
        assert json.loads(done.stdout.strip().splitlines()[-1]) == {'sent': 300, 'failed': 0}
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            with subscriber.lock:
                if len(subscriber.heads) >= 300:
                    break
            time.sleep(0.1)
        with subscriber.lock:
            indexes = [struct.unpack_from('<I', h)[0] for h in subscriber.heads]
            sizes = set(subscriber.sizes)
        assert indexes == list(range(300)), f'{len(indexes)} of 300 arrived'
        assert sizes == {65536}
    finally:
        subscriber.close()


def test_camera_frames_cross_a_tcp_endpoint_whole(install, router):  # noqa: F811
    # 160 x 120 rgb8 frames of 57.6 kB: more than one batch of the router's tcp/ link
    peer = zenoh_peers.RmwZenohPeer(router.tcp)
    key = zenoh_peers.data_key('/camera/image', 'demo_interfaces/msg/Frame')
    peer.listen(key)
    try:
        run, _ = _launch(install, 'demo_nodes/camera', endpoint=router.tcp)
        with run:
            deadline = time.monotonic() + 30
            while len(peer.samples(key)) < 5:
                assert time.monotonic() < deadline, 'five camera frames did not come'
                time.sleep(0.2)
            assert run.count('lost the Zenoh router') == 0
        for _, payload, _ in peer.samples(key)[:5]:
            assert len(payload) > 160 * 120 * 3
            height, width = struct.unpack_from('<II', payload, 4)
            assert (height, width) == (120, 160)
    finally:
        peer.close()
