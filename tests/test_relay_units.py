# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The relay's message forms (colcon_wasm/server/relay_forms.py) against the Node.js server's.

For the same messages, the relay's cbor form (built from JSON with the type
descriptions) must be the bytes the Node.js server writes (from the decoded
CDR; tests/js/relay_forms.mjs runs convert.mjs and cbor.mjs), its png the
PNG of png.mjs, and the client's CDR publish (client_topics.mjs) a request
the relay reads as one. Needs Node.js, no build. Then the relay's
subscription rules (relay_topics.py) over a socket pair.
"""

import base64
import json
from pathlib import Path
import shutil
import socket
import struct
import subprocess
import sys
import time
import zlib

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from colcon_wasm.server import relay_forms  # noqa: E402, I100, I202
from colcon_wasm.server.relay import Relay  # noqa: E402

JS = Path(__file__).resolve().parent / 'js'
SCALARS = ['bool', 'byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32',
           'int64', 'uint64', 'float32', 'float64', 'string']
TYPES = {
    'schema': 1, 'package': 't',
    'messages': {
        't/msg/Time': {'fields': [{'name': 'sec', 'type': 'int32'},
                                  {'name': 'nanosec', 'type': 'uint32'}]},
        't/msg/All': {'fields': (
            [{'name': f'{k}_v', 'type': k} for k in SCALARS]
            + [{'name': f'{k}_seq', 'type': k, 'sequence': True} for k in SCALARS]
            + [{'name': f'{k}_arr', 'type': k, 'array_size': 2} for k in SCALARS]
            + [{'name': 'time', 'type': 't/msg/Time'},
               {'name': 'times', 'type': 't/msg/Time', 'sequence': True},
               {'name': 'fixed_times', 'type': 't/msg/Time', 'array_size': 2},
               {'name': 'defaulted', 'type': 'int64', 'default': '-40000000'},
               {'name': 'defaulted_f', 'type': 'float32', 'array_size': 2,
                'default': [1.125, -1.125]}])},
    },
}
FULL = {
    'bool_v': True, 'byte_v': 255, 'char_v': 65, 'int8_v': -128, 'uint8_v': 200,
    'int16_v': -30000, 'uint16_v': 60000, 'int32_v': -2 ** 31, 'uint32_v': 2 ** 32 - 1,
    'int64_v': -2 ** 62 - 5, 'uint64_v': 2 ** 64 - 1, 'float32_v': 0.5, 'float64_v': None,
    'string_v': 'héllo ☃', 'bool_seq': [True, False], 'byte_seq': [1, 2, 250],
    'char_seq': base64.b64encode(b'AB').decode(), 'int8_seq': [-1, 2],
    'uint8_seq': base64.b64encode(bytes(range(256))).decode(), 'int16_seq': [-2, 3],
    'uint16_seq': [65535], 'int32_seq': [7, -7], 'uint32_seq': [1, 2, 3],
    'int64_seq': [2 ** 63 - 1, -2 ** 63], 'uint64_seq': ['18446744073709551615', 0],
    'float32_seq': [1.5, -2.25], 'float64_seq': [3.141592653589793, None, 1e300],
    'string_seq': ['a', ''], 'bool_arr': [False, True], 'byte_arr': [0, 1], 'char_arr': 'AAE=',
    'int8_arr': [1, -1], 'uint8_arr': 'CQo=', 'int16_arr': [1, 2], 'uint16_arr': [3, 4],
    'int32_arr': [5, 6], 'uint32_arr': [7, 8], 'int64_arr': [9, 10], 'uint64_arr': [11, 12],
    'float32_arr': [0.25, 8], 'float64_arr': [1, 2.5], 'string_arr': ['x', 'y'],
    'time': {'sec': 12, 'nanosec': 34}, 'times': [{'sec': 1, 'nanosec': 2}],
    'fixed_times': [{'sec': 3, 'nanosec': 4}, {'sec': 5, 'nanosec': 6}], 'defaulted': 3,
    'defaulted_f': [0.5, 0.75],
}


def _node(payload):
    node = shutil.which('node')
    if not node:
        pytest.skip('Node.js 20 is needed (apt-get install nodejs)')
    result = subprocess.run([node, str(JS / 'relay_forms.mjs')], input=json.dumps(payload),
                            cwd=str(JS), capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stderr[-3000:]
    return json.loads(result.stdout)


@pytest.fixture(scope='module')
def node_forms():
    """Get the Node.js server's forms of the cases below."""
    cases = [{'type': 't/msg/All', 'json': FULL}, {'type': 't/msg/All', 'json': {}},
             {'type': 't/msg/All', 'json': {'int64_v': '123', 'times': [{}, {'sec': -1}]}}]
    texts = ['{"op":"publish","topic":"/chatter","msg":{"data":"hello world 7"}}', '', 'x',
             json.dumps({'op': 'publish', 'msg': {'data': 'ü' * 5000}}, ensure_ascii=False)]
    cdr = [{'topic': '/chatter', 'hex': '000100000e00000068656c6c6f20776f726c64203700',
            'timeMs': 1700000000123.5, 'ttl': None},
           {'topic': '/t', 'hex': '', 'timeMs': 5, 'ttl': 250}]
    return cases, texts, cdr, _node({'types': TYPES, 'cases': cases, 'texts': texts, 'cdr': cdr})


def test_cbor_form_is_the_node_servers(node_forms):
    """Every kind of field (scalars, sequences, arrays, nested, defaults) in the same bytes."""
    cases, _, _, out = node_forms
    forms = relay_forms.Forms(TYPES['messages'])
    for case, expected in zip(cases, out['cbor']):
        got = forms.cbor_message(case['type'], case['json']).hex()
        assert got == expected, (case, got, expected)
    # the publish op around it is topics.mjs's cborPublish: {op, topic, msg}
    whole = forms.cbor_publish('/x', 't/msg/All', FULL)
    head = bytes([0xa3, 0x62]) + b'op' + bytes([0x67]) + b'publish' + bytes([0x65]) + b'topic'
    assert whole.startswith(head + bytes([0x62]) + b'/x' + bytes([0x63]) + b'msg')
    assert whole.endswith(bytes.fromhex(out['cbor'][0]))


def test_cbor_form_errors_name_the_field():
    """A value that does not fit is a FormError naming the field."""
    forms = relay_forms.Forms(TYPES['messages'])
    with pytest.raises(relay_forms.FormError, match="field 'int32_seq': expected an array"):
        forms.cbor_message('t/msg/All', {'int32_seq': 5})
    with pytest.raises(relay_forms.FormError, match=r"field 'times\[0\].sec': expected an int"):
        forms.cbor_message('t/msg/All', {'times': [{'sec': 'x'}]})
    with pytest.raises(relay_forms.FormError, match='no type description'):
        forms.cbor_message('t/msg/Nope', {})


def _png_parts(b64):
    png = base64.b64decode(b64)
    assert png[:8] == b'\x89PNG\r\n\x1a\n'
    chunks, pos = [], 8
    while pos < len(png):
        n, = struct.unpack('>I', png[pos:pos + 4])
        kind, data = png[pos + 4:pos + 8], png[pos + 8:pos + 8 + n]
        assert struct.unpack('>I', png[pos + 8 + n:pos + 12 + n])[0] == zlib.crc32(kind + data)
        chunks.append((kind, zlib.decompress(data) if kind == b'IDAT' else data))
        pos += 12 + n
    return chunks


def test_png_is_png_mjs(node_forms):
    """
    png.mjs' PNG: the same chunks, IHDR and (inflated) rows; the text padded with newlines.

    The deflate streams themselves differ (Node.js bundles Chromium's zlib,
    Python links the system's); both inflate to the same bytes.
    """
    _, texts, _, out = node_forms
    for text, expected in zip(texts, out['png']):
        got = _png_parts(relay_forms.png_encode_text(text))
        assert got == _png_parts(expected), text[:40]
        assert [k for k, _ in got] == [b'IHDR', b'IDAT', b'IEND']
        width, height = struct.unpack('>II', got[0][1][:8])
        raw = got[1][1]
        pixels = b''.join(raw[y * (width * 3 + 1) + 1:(y + 1) * (width * 3 + 1)]
                          for y in range(height))
        assert pixels.rstrip(b'\n') == text.encode('utf-8').rstrip(b'\n')


def test_client_cdr_publish_is_a_raw_publish_for_the_relay(node_forms):
    """client_topics.mjs' CBOR publish of CDR decodes as one raw publish; cbor-raw out matches."""
    from colcon_wasm.server.relay import _raw_publish
    _, _, cdr, out = node_forms
    for item, hexed in zip(cdr, out['cdr']):
        msg = relay_forms.decode_request(bytes.fromhex(hexed))
        assert _raw_publish(msg), msg
        assert msg['topic'] == item['topic'] and msg['msg']['bytes'] == bytes.fromhex(item['hex'])
        assert msg['msg']['secs'] == int(item['timeMs'] // 1000)
        assert msg.get('ttl') == item['ttl']
    raw = relay_forms.cbor_raw_publish('/c', b'\x01\x02', 3, 4)
    assert relay_forms.decode_request(raw) == {
        'op': 'publish', 'topic': '/c', 'msg': {'secs': 3, 'nsecs': 4, 'bytes': b'\x01\x02'}}


def test_bad_binary_and_cbor_requests():
    """Not CBOR, or more than one item: ValueError saying so; CBOR bytes become base64."""
    for bad in (b'\xff\xfe', b'\x82\x01', b'\x01\x02'):
        with pytest.raises(ValueError, match='not CBOR|not one CBOR item'):
            relay_forms.decode_request(bad)
    value = relay_forms.decode_request(bytes.fromhex('a2616142010261624401000000'))
    assert value == {'a': b'\x01\x02', 'b': b'\x01\x00\x00\x00'}
    tagged = relay_forms.decode_request(bytes.fromhex('a16176d84e4808000000f9ffffff'))
    assert relay_forms.jsonable(tagged) == {'v': [8, -7]}
    assert relay_forms.jsonable(value) == {'a': 'AQI=', 'b': 'AQAAAA=='}


def test_fragments_join_to_the_text():
    """fragment_size: ops whose data joins to the text (session.mjs's form)."""
    text = json.dumps({'op': 'publish', 'msg': {'data': 'y' * 95}})
    parts = [json.loads(p) for p in relay_forms.fragments(text, 30, 'f1')]
    assert [p['num'] for p in parts] == list(range(len(parts)))
    assert len(parts) == (len(text) + 29) // 30
    assert {p['total'] for p in parts} == {len(parts)} and {p['id'] for p in parts} == {'f1'}
    assert ''.join(p['data'] for p in parts) == text
    assert relay_forms.fragments(text, None, None) == [text]


# ------------------------------------------------------------ subscriptions over a socket


class Client:
    """The client end of a relay connection: masked frames out, frames in."""

    def __init__(self, relay=None, sock=None):
        """Serve one end of a socket pair with ``relay``, or use a connected ``sock``."""
        import threading
        if sock is None:
            sock, server_side = socket.socketpair()
            threading.Thread(target=relay.serve, args=(server_side, 'test'),
                             daemon=True).start()
        self.sock = sock
        self.sock.settimeout(5)
        self.buffer = b''

    @classmethod
    def connect(cls, url):
        """Open ws://HOST:PORT (the WebSocket handshake, then frames)."""
        host, port = url[len('ws://'):].rstrip('/').rsplit(':', 1)
        sock = socket.create_connection((host, int(port)), timeout=5)
        sock.sendall(('GET / HTTP/1.1\r\nHost: {}:{}\r\nUpgrade: websocket\r\n'
                      'Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n'
                      'Sec-WebSocket-Version: 13\r\n\r\n').format(host, port).encode())
        client = cls(sock=sock)
        response = b''
        while b'\r\n\r\n' not in response:
            chunk = sock.recv(4096)
            assert chunk, f'the relay closed during the handshake: {response!r}'
            response += chunk
        head, client.buffer = response.split(b'\r\n\r\n', 1)
        assert head.startswith(b'HTTP/1.1 101'), head
        return client

    def send(self, obj, binary=False):
        """Send one message (a dict as JSON text, bytes as binary)."""
        payload = obj if binary else json.dumps(obj).encode('utf-8')
        n = len(payload)
        head = bytes([0x82 if binary else 0x81])
        if n < 126:
            head += bytes([0x80 | n])
        elif n < 65536:
            head += struct.pack('>BH', 0x80 | 126, n)
        else:
            head += struct.pack('>BQ', 0x80 | 127, n)
        self.sock.sendall(head + b'\0\0\0\0' + payload)

    def _read(self, n):
        while len(self.buffer) < n:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionError('closed')
            self.buffer += chunk
        out, self.buffer = self.buffer[:n], self.buffer[n:]
        return out

    def receive(self, timeout=5):
        """Return the next message (dict), or None within ``timeout``."""
        self.sock.settimeout(timeout)
        try:
            b0, b1 = self._read(2)
        except socket.timeout:
            return None
        n = b1 & 0x7f
        if n == 126:
            n, = struct.unpack('>H', self._read(2))
        elif n == 127:
            n, = struct.unpack('>Q', self._read(8))
        payload = self._read(n)
        if b0 & 0x0f == 2:
            return relay_forms.decode_request(payload)
        return json.loads(payload)

    def until(self, predicate, timeout=5):
        """Return the first message that matches, skipping others."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            m = self.receive(deadline - time.monotonic())
            if m is not None and predicate(m):
                return m
        return None


@pytest.fixture
def relay():
    """Make a relay of the test types."""
    r = Relay(types=[TYPES])
    yield r
    r.close()


def test_queue_length_and_throttle_send_the_newest_one_per_period(relay):
    """queue_length 1 with throttle_rate 300: the newest waits, one per 300 ms."""
    pub, sub = Client(relay), Client(relay)
    for c in (pub, sub):
        assert c.receive()['op'] == 'colcon_wasm_relay'
    sub.send({'op': 'subscribe', 'topic': '/q', 'type': 't/msg/Time', 'throttle_rate': 300,
              'queue_length': 1})
    pub.send({'op': 'advertise', 'topic': '/q', 'type': 't/msg/Time'})
    time.sleep(0.2)
    got = []

    def read():
        while True:
            m = sub.receive(1.0)
            if m is None:
                return
            got.append((time.monotonic(), m['msg']['sec']))

    import threading
    reader = threading.Thread(target=read)
    reader.start()
    started = time.monotonic()
    for i in range(30):
        pub.send({'op': 'publish', 'topic': '/q', 'msg': {'sec': i, 'nanosec': 0}})
        time.sleep(0.03)
    span = time.monotonic() - started  # about 1 s, more on a loaded machine
    reader.join(10)
    secs = [s for _, s in got]
    assert secs[0] == 0 and secs[-1] == 29, secs
    # one per 0.3 s of the span, and the newest after it
    assert 3 <= len(secs) <= span / 0.3 + 2, (secs, span)
    gaps = [b[0] - a[0] for a, b in zip(got, got[1:])]
    assert all(g >= 0.25 for g in gaps), gaps
    steps = [b - a for a, b in zip(secs, secs[1:])]
    assert all(s > 1 for s in steps), steps  # the newest, not the next


def test_forms_cdr_routing_and_cbor_raw_fallback(relay):
    """colcon_wasm_forms follow the subscribers; CDR goes to cbor-raw, JSON to the rest."""
    wasm, raw, js = Client(relay), Client(relay), Client(relay)
    for c in (wasm, raw, js):
        c.receive()
    wasm.send({'op': 'advertise', 'topic': '/f', 'type': 't/msg/Time'})
    wasm.send({'op': 'colcon_wasm_graph', 'nodes': ['/n'], 'version': 2})
    forms = wasm.until(lambda m: m['op'] == 'colcon_wasm_forms')
    assert (forms['json'], forms['cdr']) == (False, False), forms
    raw.send({'op': 'subscribe', 'topic': '/f', 'compression': 'cbor-raw', 'id': 's1'})
    assert wasm.until(lambda m: m['op'] == 'colcon_wasm_forms')['cdr'] is True
    js.send({'op': 'subscribe', 'topic': '/f', 'compression': 'cbor', 'id': 's2'})
    forms = wasm.until(lambda m: m['op'] == 'colcon_wasm_forms')
    assert (forms['json'], forms['cdr']) == (True, True), forms
    cdr = b'\0\1\0\0\5\0\0\0\6\0\0\0'
    wasm.send(_cbor({'op': 'publish', 'topic': '/f', 'msg': {
        'bytes': cdr, 'secs': 1, 'nsecs': 2}, 'ttl': 5000}), binary=True)
    wasm.send({'op': 'publish', 'topic': '/f', 'msg': {'sec': 5, 'nanosec': 6}})
    got_raw = raw.until(lambda m: m.get('op') == 'publish')
    assert got_raw['msg'] == {'secs': 1, 'nsecs': 2, 'bytes': cdr} and 0 < got_raw['ttl'] <= 5000
    got_js = js.until(lambda m: m.get('op') == 'publish')
    assert got_js == {'op': 'publish', 'topic': '/f', 'msg': {'sec': 5, 'nanosec': 6}}
    assert raw.receive(0.3) is None  # the JSON copy does not reach the cbor-raw subscriber
    # a JSON-only publisher (a third-party client): JSON to cbor-raw, with one warning
    js.send({'op': 'set_level', 'level': 'warning'})
    raw.send({'op': 'set_level', 'level': 'warning'})
    js.send({'op': 'advertise', 'topic': '/g', 'type': 't/msg/Time'})
    raw.send({'op': 'subscribe', 'topic': '/g', 'compression': 'cbor-raw', 'id': 'g1'})
    time.sleep(0.1)
    for i in range(2):
        js.send({'op': 'publish', 'topic': '/g', 'msg': {'sec': i, 'nanosec': 0}})
    seen = [raw.receive(), raw.receive(), raw.receive()]
    assert [m['op'] for m in seen].count('status') == 1, seen
    assert [m['msg'] for m in seen if m['op'] == 'publish'] == [
        {'sec': 0, 'nanosec': 0}, {'sec': 1, 'nanosec': 0}], seen
    status = next(m for m in seen if m['op'] == 'status')
    assert 'gives no CDR form' in status['msg'] and status['id'] == 'g1', status
    # not CBOR: a status error, and the connection stays
    raw.send(b'\xff\xfe', binary=True)
    error = raw.until(lambda m: m.get('op') == 'status')
    assert 'not CBOR' in error['msg'] and error['level'] == 'error', error
    js.send({'op': 'publish', 'topic': '/g', 'msg': {'sec': 9, 'nanosec': 0}})
    assert raw.until(lambda m: m.get('op') == 'publish')['msg']['sec'] == 9


def _cbor(obj):
    w = relay_forms.CborWriter()
    w.value(obj)
    return w.result()


def test_png_fragments_and_binary_limits_on_subscriptions():
    """Check png and fragment_size subscriptions, and the binary size limit."""
    relay = Relay(types=[TYPES], max_message_bytes=400)
    try:
        pub, png, frag = Client(relay), Client(relay), Client(relay)
        for c in (pub, png, frag):
            c.receive()
        pub.send({'op': 'advertise', 'topic': '/p', 'type': 't/msg/Time'})
        png.send({'op': 'subscribe', 'topic': '/p', 'compression': 'png'})
        frag.send({'op': 'subscribe', 'topic': '/p', 'fragment_size': 100, 'id': 'a'})
        frag.send({'op': 'subscribe', 'topic': '/p', 'fragment_size': 20, 'id': 'b'})
        time.sleep(0.1)
        pub.send({'op': 'publish', 'topic': '/p', 'msg': {'sec': 7, 'nanosec': 8}})
        m = png.until(lambda m: m.get('op') == 'png')
        chunks = _png_parts(m['data'])
        width = struct.unpack('>II', chunks[0][1][:8])[0]
        rows = chunks[1][1]
        text = b''.join(rows[i + 1:i + 1 + width * 3] for i in range(0, len(rows), width * 3 + 1))
        assert json.loads(text.rstrip(b'\n'))['msg'] == {'sec': 7, 'nanosec': 8}
        parts = [frag.until(lambda m: m.get('op') == 'fragment')]
        parts += [frag.receive() for _ in range(parts[0]['total'] - 1)]
        assert all(len(p['data']) <= 20 for p in parts) and parts[0]['total'] > 2, parts
        assert json.loads(''.join(p['data'] for p in parts))['msg'] == {'sec': 7, 'nanosec': 8}
        pub.send({'op': 'set_level', 'level': 'warning'})
        pub.send(_cbor({'op': 'publish', 'topic': '/p', 'msg': {'bytes': b'\0' * 500}}),
                 binary=True)
        error = pub.until(lambda m: m.get('op') == 'status')
        assert 'larger than the limit of 400 bytes' in error['msg'], error
        pub.send(_cbor({'op': 'publish', 'topic': '/p', 'msg': {'sec': 9, 'nanosec': 0}}),
                 binary=True)
        assert png.until(lambda m: m.get('op') == 'png') is not None
    finally:
        relay.close()


def _rosapi(client, service, args, rid):
    """Call a rosapi service of the relay; return its values."""
    client.send({'op': 'call_service', 'id': rid, 'service': f'/rosapi/{service}',
                 'args': args})
    reply = client.until(lambda m: m.get('op') == 'service_response' and m.get('id') == rid)
    assert reply and reply['result'], reply
    return reply['values']


def test_rosapi_node_details_answers_for_a_client_that_is_one_node(relay):
    """node_details: a one-node client's endpoints; a reporting tab's, node by node."""
    one, many, caller = Client(relay), Client(relay), Client(relay)
    for c in (one, many, caller):
        c.receive()
    one.send({'op': 'colcon_wasm_graph', 'nodes': ['/talker'], 'version': 2})
    one.send({'op': 'advertise', 'topic': '/chatter', 'type': 't/msg/Time'})
    one.send({'op': 'subscribe', 'topic': '/cmd', 'type': 't/msg/Time', 'id': 'c'})
    one.send({'op': 'advertise_service', 'service': '/talker/reset', 'type': 't/srv/Reset'})
    # a tab of two nodes that says which holds which endpoint (all of them, bridged or not)
    many.send({'op': 'colcon_wasm_graph', 'nodes': ['/a', '/b'], 'version': 2, 'endpoints': {
        '/a': {'publishing': ['/other', '/rosout'], 'subscribing': [], 'services': []},
        '/b': {'publishing': ['/rosout'], 'subscribing': ['/other', '/cmd'],
               'services': ['/b/reset']}}})
    many.send({'op': 'advertise', 'topic': '/other', 'type': 't/msg/Time'})
    many.send({'op': 'subscribe', 'topic': '/cmd', 'type': 't/msg/Time', 'id': 'c'})
    many.send({'op': 'advertise_service', 'service': '/b/reset', 'type': 't/srv/Reset'})
    # each client's requests are handled in order: these answers follow what they sent
    _rosapi(one, 'get_time', {}, 'sync')
    _rosapi(many, 'get_time', {}, 'sync')

    def details(node, rid):
        return _rosapi(caller, 'node_details', {'node': node}, rid)

    assert details('/talker', 'd1') == {'subscribing': ['/cmd'], 'publishing': ['/chatter'],
                                        'services': ['/talker/reset']}
    assert details('talker', 'd2')['publishing'] == ['/chatter']  # a relative name
    assert details('/a', 'd3') == {'subscribing': [], 'publishing': ['/other', '/rosout'],
                                   'services': []}
    assert details('/b', 'd4') == {'subscribing': ['/cmd', '/other'], 'publishing': ['/rosout'],
                                   'services': ['/b/reset']}
    assert details('/nobody', 'd5') == {'subscribing': [], 'publishing': [], 'services': []}
    assert '/rosapi/node_details' in details('/rosapi', 'd6')['services']
    # publishers, subscribers and providers name the nodes that hold the endpoint
    assert _rosapi(caller, 'publishers', {'topic': '/other'}, 'p') == {'publishers': ['/a']}
    assert _rosapi(caller, 'subscribers', {'topic': '/cmd'}, 's') == {
        'subscribers': ['/b', '/talker']}
    assert _rosapi(caller, 'service_providers', {'service': '/b/reset'}, 'v') == {
        'providers': ['/b']}
    # the caller reported nothing: a node of its own (numbered as it connected)
    nodes = _rosapi(caller, 'nodes', {}, 'n')['nodes']
    assert [n for n in nodes if not n.startswith('/rosbridge_relay/client_')] == [
        '/a', '/b', '/rosapi', '/rosbridge_websocket', '/talker'], nodes
    assert len(nodes) == 6, nodes


def test_rosapi_type_services_of_the_relay():
    """topics_and_raw_types, services_for_type, service_node and the service details."""
    types = {'messages': {
        'p/msg/Point': {'fields': [{'name': 'x', 'type': 'float64'}],
                        'definition': 'float64 x\n'},
        'p/msg/Path': {'fields': [{'name': 'points', 'type': 'p/msg/Point', 'sequence': True}],
                       'definition': 'p/Point[] points\n'},
        'p/msg/Lost': {'fields': [{'name': 'x', 'type': 'int32'}]},
        'p/srv/Add_Request': {'fields': [{'name': 'a', 'type': 'int64'}]},
        'p/srv/Add_Response': {'fields': [{'name': 'sum', 'type': 'p/msg/Point'}]}},
        'services': {'p/srv/Add': {'request': 'p/srv/Add_Request',
                                   'response': 'p/srv/Add_Response'}}}
    relay = Relay(types=[types])
    try:
        node, caller = Client(relay), Client(relay)
        for c in (node, caller):
            c.receive()
        node.send({'op': 'colcon_wasm_graph', 'nodes': ['/adder'], 'version': 2})
        node.send({'op': 'advertise', 'topic': '/path', 'type': 'p/Path'})
        node.send({'op': 'advertise', 'topic': '/lost', 'type': 'p/msg/Lost'})
        node.send({'op': 'advertise_service', 'service': '/add', 'type': 'p/Add'})
        _rosapi(node, 'get_time', {}, 'sync')
        raw = _rosapi(caller, 'topics_and_raw_types', {}, 'r')
        assert raw['topics'] == ['/lost', '/path'] and raw['types'] == ['p/msg/Lost', 'p/msg/Path']
        # the complete definition as rosbag2 writes it; rosapi's comment for one the relay lacks
        assert raw['typedefs_full_text'][1] == (
            'p/Point[] points\n\n' + '=' * 80 + '\nMSG: p/Point\nfloat64 x\n')
        assert raw['typedefs_full_text'][0].startswith(
            '# failed to get full definition text for p/msg/Lost: ')
        assert _rosapi(caller, 'services_for_type', {'type': 'p/Add'}, 's') == {
            'services': ['/add']}
        assert _rosapi(caller, 'service_node', {'service': '/add'}, 'n') == {'node': '/adder'}
        assert _rosapi(caller, 'service_node', {'service': '/rosapi/topics'}, 'n2') == {
            'node': '/rosapi'}
        assert _rosapi(caller, 'service_node', {'service': '/none'}, 'n3') == {'node': ''}
        assert _rosapi(caller, 'service_type', {'service': '/rosapi/get_param'}, 't') == {
            'type': 'rosapi_msgs/srv/GetParam'}
        request = _rosapi(caller, 'service_request_details', {'type': 'p/srv/Add'}, 'q')
        assert [(t['type'], t['fieldnames']) for t in request['typedefs']] == [
            ('p/srv/Add_Request', ['a'])]
        response = _rosapi(caller, 'service_response_details', {'type': 'p/Add'}, 'a')
        assert [t['type'] for t in response['typedefs']] == ['p/srv/Add_Response', 'p/Point']
        assert _rosapi(caller, 'service_request_details', {'type': 'p/None'}, 'x') == {
            'typedefs': []}
        # parameters of a node that has no parameter services: the reason comes back
        got = _rosapi(caller, 'get_param', {'name': '/adder:x'}, 'g')
        assert got == {'value': 'null', 'successful': False, 'reason': (
            'no node /adder with parameter services is on the graph of the pages (nobody '
            'serves /adder/get_parameters)')}
        assert _rosapi(caller, 'get_param_names', {}, 'names') == {'names': []}
    finally:
        relay.close()


def test_rosapi_parameters_through_a_client_that_serves_them(relay):
    """get_param, has_param, set_param and get_param_names call the node's services."""
    node, caller = Client(relay), Client(relay)
    for c in (node, caller):
        c.receive()
    for service in ('get_parameters', 'set_parameters', 'list_parameters'):
        node.send({'op': 'advertise_service', 'service': f'/n/{service}',
                   'type': f'rcl_interfaces/srv/{service.title().replace("_", "")}'})
    _rosapi(node, 'get_time', {}, 'sync')

    def ask(service, args, rid, answer):
        """Call rosapi; answer the node's call with ``answer``; return rosapi's values."""
        caller.send({'op': 'call_service', 'id': rid, 'service': f'/rosapi/{service}',
                     'args': args})
        call = node.until(lambda m: m.get('op') == 'call_service')
        assert call and call['id'].startswith('relay:'), call
        node.send({'op': 'service_response', 'id': call['id'], 'service': call['service'],
                   'result': True, 'values': answer})
        reply = caller.until(lambda m: m.get('op') == 'service_response' and m.get('id') == rid)
        assert reply and reply['result'], reply
        return call, reply['values']

    call, got = ask('get_param', {'name': '/n:greeting'}, 'g1',
                    {'values': [{'type': 4, 'string_value': 'hi'}]})
    assert (call['service'], call['args']) == ('/n/get_parameters', {'names': ['greeting']})
    assert got == {'value': '"hi"', 'successful': True, 'reason': ''}
    # rclcpp answers no values for a name it has not declared
    _, got = ask('get_param', {'name': 'n:nope', 'default_value': '[1, 2]'}, 'g2',
                 {'values': []})
    assert got == {'value': '[1, 2]', 'successful': True, 'reason': ''}
    _, got = ask('has_param', {'name': '/n:nope'}, 'h', {'values': []})
    assert got == {'exists': False}
    call, got = ask('set_param', {'name': '/n:rate', 'value': '2.5'}, 's1',
                    {'results': [{'successful': False, 'reason': 'rate is read-only'}]})
    assert call['args'] == {'parameters': [{'name': 'rate', 'value': {
        'type': 3, 'double_value': 2.5}}]}
    assert got == {'successful': False,
                   'reason': 'setting /n:rate failed: rate is read-only'}
    call, got = ask('get_param_names', {}, 'names',
                    {'result': {'names': ['a', 5, 'b'], 'prefixes': []}})
    assert call['service'] == '/n/list_parameters'
    assert got == {'names': ['/n:a', '/n:b']}
    # an answer that is no JSON object: a failure that says so, and the relay goes on
    _, got = ask('get_param', {'name': '/n:greeting'}, 'g3', [1, 2])
    assert got == {'value': 'null', 'successful': False,
                   'reason': 'the answer is no JSON object: [1, 2]'}
    assert _rosapi(caller, 'get_time', {}, 'after')['time']['sec'] > 0


def test_foxglove_parameter_values_both_ways():
    """Serve --foxglove: Foxglove parameters to rcl ParameterValues (JSON) and back."""
    from colcon_wasm.server.foxglove_parameters import from_rcl
    from colcon_wasm.server.foxglove_parameters import ParameterError
    from colcon_wasm.server.foxglove_parameters import split_name
    from colcon_wasm.server.foxglove_parameters import to_rcl
    cases = [
        ({'value': True}, {'type': 1, 'bool_value': True}),
        ({'value': 2 ** 53 + 1}, {'type': 2, 'integer_value': 2 ** 53 + 1}),
        ({'value': 2.5, 'type': 'float64'}, {'type': 3, 'double_value': 2.5}),
        ({'value': 'hi'}, {'type': 4, 'string_value': 'hi'}),
        ({'value': 'AAH/', 'type': 'byte_array'}, {'type': 5, 'byte_array_value': [0, 1, 255]}),
        ({'value': [True, False]}, {'type': 6, 'bool_array_value': [True, False]}),
        ({'value': [1, 2]}, {'type': 7, 'integer_array_value': [1, 2]}),
        ({'value': [1.0, 2.5], 'type': 'float64_array'},
         {'type': 8, 'double_array_value': [1.0, 2.5]}),
        ({'value': ['a', 'b']}, {'type': 9, 'string_array_value': ['a', 'b']}),
    ]
    for foxglove, rcl in cases:
        assert to_rcl({'name': '/n.p', **foxglove}) == rcl, foxglove
        assert from_rcl('/n.p', rcl) == {'name': '/n.p', **foxglove}, rcl
    # a double that looks like an integer stays a double; a value left out deletes
    assert to_rcl({'name': '/n.p', 'value': 3, 'type': 'float64'}) == {'type': 3,
                                                                       'double_value': 3.0}
    assert to_rcl({'name': '/n.p'}) == {'type': 0}
    assert from_rcl('/n.p', {'type': 0}) is None
    assert split_name('/ns/talker.rate.max') == ('/ns/talker', 'rate.max')
    assert split_name('talker.rate') == ('/talker', 'rate')
    for bad in ('/talker', '/talker.', 7):
        with pytest.raises(ParameterError, match='not'):
            split_name(bad)
    for bad in ({'value': {'a': 1}}, {'value': [1, 'a']}, {'value': 'no!', 'type': 'byte_array'}):
        with pytest.raises(ParameterError, match="parameter '/n.p'"):
            to_rcl({'name': '/n.p', **bad})
