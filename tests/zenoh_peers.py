# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A Zenoh router and rmw_zenoh participants played by eclipse-zenoh, for the Zenoh tests.

    with ZenohRouter() as router:          # tcp and ws listeners on loopback
        peer = RmwZenohPeer(router.tcp)    # a zenoh session in client mode
        peer.announce_node('/py_talker')   # NN token, rmw_zenoh's format
        peer.publish('/chatter', 'demo_interfaces/msg/Chatter', cdr)
        peer.samples('0/chatter/**')       # what arrived, with attachments

The router is a child Python process (``python -m`` of this file) so a test
can kill and restart it. The key, token and attachment formats here are
written from rmw_zenoh's sources (rmw_zenoh_cpp 0.1.9, the Humble release),
independently of packages/wasm_js/src/bridges/zenoh/keys.mjs; the attachment
goes through zenoh.ext's own serializer.
"""

import json
import os
import socket
import struct
import subprocess
import sys
import threading
import time


def free_port():
    """Return a TCP port free on loopback now."""
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def _wait_listening(port, timeout=20):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with socket.socket() as s:
            if s.connect_ex(('127.0.0.1', port)) == 0:
                return
        time.sleep(0.1)
    raise AssertionError(f'the Zenoh router did not listen on 127.0.0.1:{port} within {timeout} s')


class ZenohRouter:
    """eclipse-zenoh's router in a child process, with a TCP and a WebSocket listener."""

    def __init__(self, tcp_port=None, ws_port=None, config=None):
        """Pick the ports; start() runs it; `config`: more settings (key: JSON value)."""
        self.tcp_port = tcp_port or free_port()
        self.ws_port = ws_port or free_port()
        self.config = dict(config or {})
        self.process = None

    @property
    def tcp(self):
        """The TCP endpoint (tcp/127.0.0.1:PORT)."""
        return f'tcp/127.0.0.1:{self.tcp_port}'

    @property
    def ws(self):
        """The WebSocket endpoint (ws/127.0.0.1:PORT)."""
        return f'ws/127.0.0.1:{self.ws_port}'

    def start(self):
        """Start the router and wait for both listeners."""
        self.process = subprocess.Popen(
            [sys.executable, __file__, 'router', json.dumps(self.config), self.tcp, self.ws],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        _wait_listening(self.tcp_port)
        _wait_listening(self.ws_port)
        return self

    def kill(self):
        """Kill the router (as a crash: no goodbye to the sessions)."""
        if self.process and self.process.poll() is None:
            self.process.kill()
            self.process.wait(timeout=10)

    def __enter__(self):  # noqa: D105
        return self.start()

    def __exit__(self, *exc):  # noqa: D105
        self.kill()


def _router_main(config, endpoints):
    import zenoh
    conf = zenoh.Config()
    conf.insert_json5('mode', '"router"')
    conf.insert_json5('listen/endpoints', json.dumps(endpoints))
    conf.insert_json5('scouting/multicast/enabled', 'false')
    for key, value in json.loads(config).items():
        conf.insert_json5(key, json.dumps(value))
    session = zenoh.open(conf)
    print(f'router {session.info.zid()} on {endpoints}', flush=True)
    while True:
        time.sleep(3600)


# ---------------------------------------------------------------- rmw_zenoh's formats

def dds_type(ros_type):
    """Return rmw_zenoh's type name: pkg/msg/Type -> pkg::msg::dds_::Type_."""
    pkg, kind, name = ros_type.split('/')
    return f'{pkg}::{kind}::dds_::{name}_'


def data_key(name, ros_type, domain=0):
    """Return the key of a topic or service on Humble (no type hash)."""
    return f'{domain}/{name.strip("/")}/{dds_type(ros_type)}/TypeHashNotSupported'


def attachment(sequence, gid, timestamp_ns=None):
    """Serialize the 33-byte attachment with zenoh.ext (int64, int64, 16 uint8)."""
    from zenoh.ext import Int64, UInt8, z_serialize
    stamp = time.time_ns() if timestamp_ns is None else timestamp_ns
    return z_serialize((Int64(sequence), Int64(stamp), [UInt8(b) for b in gid])).to_bytes()


def parse_attachment(data):
    """(sequence, timestamp ns, gid bytes) of an attachment, by zenoh.ext's deserializer."""
    from zenoh.ext import Int64, UInt8, z_deserialize
    import zenoh
    seq, stamp, gid = z_deserialize(tuple[Int64, Int64, list[UInt8]], zenoh.ZBytes(data))
    return int(seq), int(stamp), bytes(int(b) for b in gid)


def cdr_chatter(text, count):
    """Encode a demo_interfaces/msg/Chatter in CDR (little-endian, with its header)."""
    raw = text.encode() + b'\0'
    body = struct.pack('<I', len(raw)) + raw
    body += b'\0' * (-len(body) % 4)
    return b'\x00\x01\x00\x00' + body + struct.pack('<I', count)


def parse_chatter(cdr):
    """(text, count) of a demo_interfaces/msg/Chatter in CDR."""
    assert cdr[:4] == b'\x00\x01\x00\x00', cdr[:4].hex()
    (n,) = struct.unpack_from('<I', cdr, 4)
    text = cdr[8:8 + n - 1].decode()
    at = 8 + n
    at += -at % 4
    (count,) = struct.unpack_from('<I', cdr, at)
    return text, count


class RmwZenohPeer:
    """A zenoh session that behaves as an rmw_zenoh participant (Humble)."""

    def __init__(self, endpoint, domain=0):
        """Open a client session to the router at ``endpoint``."""
        import zenoh
        conf = zenoh.Config()
        conf.insert_json5('mode', '"client"')
        conf.insert_json5('connect/endpoints', json.dumps([endpoint]))
        conf.insert_json5('scouting/multicast/enabled', 'false')
        self.session = zenoh.open(conf)
        self.zid = str(self.session.info.zid())
        self.domain = domain
        self._lock = threading.Lock()
        self._samples = {}
        self._keep = []
        self._next_id = 0
        self._gids = {}

    def _entity_id(self):
        self._next_id += 1
        return self._next_id

    def token_key(self, kind, node, node_id, entity_id, name=None, ros_type=None,
                  qos='::,10:,:,:,,', namespace='/'):
        """Return an rmw_zenoh liveliness token key."""
        def mangle(text):
            return (text or '').replace('/', '%') or '%'
        fields = ['@ros2_lv', str(self.domain), self.zid, str(node_id), str(entity_id), kind,
                  '%', mangle('' if namespace == '/' else namespace), mangle(node)]
        if kind != 'NN':
            fields += [mangle(name), dds_type(ros_type), 'TypeHashNotSupported', qos]
        return '/'.join(fields)

    def announce(self, key):
        """Declare a liveliness token (kept until close)."""
        token = self.session.liveliness().declare_token(key)
        self._keep.append(token)
        return token

    def announce_node(self, node):
        """Declare a node's NN token; returns the node id."""
        node_id = self._entity_id()
        self.announce(self.token_key('NN', node, node_id, node_id))
        return node_id

    def advertise(self, node, node_id, topic, ros_type, transient_local_depth=None):
        """
        Declare a publisher (MP token and a zenoh publisher); returns publish(cdr).

        With ``transient_local_depth``, a TRANSIENT_LOCAL one as rmw_zenoh declares
        it: zenoh.ext's advanced publisher with a cache of that depth, detectable,
        sporadic heartbeats every 500 ms.
        """
        entity = self._entity_id()
        key = data_key(topic, ros_type, self.domain)
        if transient_local_depth:
            from zenoh.ext import CacheConfig, declare_advanced_publisher, MissDetectionConfig
            qos = f':1:,{transient_local_depth}:,:,:,,'
            publisher = declare_advanced_publisher(
                self.session, key, cache=CacheConfig(max_samples=transient_local_depth),
                sample_miss_detection=MissDetectionConfig(sporadic_heartbeat=0.5),
                publisher_detection=True)
        else:
            qos = '::,10:,:,:,,'
            publisher = self.session.declare_publisher(key)
        self.announce(self.token_key('MP', node, node_id, entity, topic, ros_type, qos=qos))
        self._keep.append(publisher)
        gid = os.urandom(16)
        counter = [0]

        def publish(cdr, with_attachment=True):
            counter[0] += 1
            publisher.put(cdr, attachment=attachment(counter[0], gid) if with_attachment else None)
        return publish

    def _recorder(self, key):
        """Return a sample callback that keeps (key, payload, attachment) for samples(key)."""
        def on_sample(sample):
            att = sample.attachment.to_bytes() if sample.attachment is not None else None
            with self._lock:
                self._samples.setdefault(key, []).append(
                    (str(sample.key_expr), sample.payload.to_bytes(), att))
        return on_sample

    def listen(self, key):
        """Subscribe to a key expression; samples() lists what came."""
        self._keep.append(self.session.declare_subscriber(key, self._recorder(key)))

    def listen_transient_local(self, key, depth):
        """Subscribe as a TRANSIENT_LOCAL rmw_zenoh subscription (the caches' history first)."""
        from zenoh.ext import declare_advanced_subscriber, HistoryConfig, RecoveryConfig
        self._keep.append(declare_advanced_subscriber(
            self.session, key, self._recorder(key),
            history=HistoryConfig(detect_late_publishers=True, max_samples=depth),
            recovery=RecoveryConfig(heartbeat=True), subscriber_detection=True))

    def samples(self, key):
        """Return the samples heard on a listened key: (key, payload, attachment)."""
        with self._lock:
            return list(self._samples.get(key, []))

    def serve(self, node, node_id, service, ros_type, handler):
        """Serve a service: SS token and a complete queryable; handler(payload) -> payload."""
        entity = self._entity_id()
        self.announce(self.token_key('SS', node, node_id, entity, service, ros_type))

        def on_query(query):
            seq, _, gid = parse_attachment(query.attachment.to_bytes())
            response = handler(query.payload.to_bytes())
            query.reply(query.key_expr, response, attachment=attachment(seq, gid))
        self._keep.append(self.session.declare_queryable(
            data_key(service, ros_type, self.domain), on_query, complete=True))

    def call(self, service, ros_type, request, sequence=1, timeout=10.0):
        """Call a service as an rmw_zenoh client: [(payload, attachment)] of the replies."""
        import zenoh
        gid = os.urandom(16)
        replies = self.session.get(
            data_key(service, ros_type, self.domain), payload=request,
            attachment=attachment(sequence, gid), target=zenoh.QueryTarget.ALL_COMPLETE,
            consolidation=zenoh.ConsolidationMode.NONE, timeout=timeout)
        out = []
        for reply in replies:
            if reply.ok is not None:
                out.append((reply.ok.payload.to_bytes(), reply.ok.attachment.to_bytes(), gid))
        return out

    def tokens(self, timeout=3.0):
        """List the liveliness tokens alive on the domain (rmw_zenoh's graph cache query)."""
        replies = self.session.liveliness().get(f'@ros2_lv/{self.domain}/**', timeout=timeout)
        return sorted(str(r.ok.key_expr) for r in replies if r.ok is not None)

    def close(self):
        """Close the session (its tokens go)."""
        self._keep.clear()
        self.session.close()


if __name__ == '__main__':
    if sys.argv[1:2] == ['router']:
        _router_main(sys.argv[2], sys.argv[3:])
