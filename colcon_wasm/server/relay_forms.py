# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The message forms of the rosbridge relay (relay.py), built without a bus.

The relay has no CDR codec: CDR bytes pass through it as they come. What it
builds from a message's JSON form, with the install space's type
descriptions (types.json), is what the Node.js server
(``packages/wasm_js/src/bridges/rosbridge/``) builds from the decoded
value, byte for byte, so that roslibjs reads both the same:

* ``cbor`` (``convert.mjs`` cborWriter, ``cbor.mjs``): fields in their
  declared order, missing fields at their defaults, floats as float64,
  ``uint8[]``/``char[]``/``byte[]`` as byte strings, other numeric arrays
  as RFC 8746 little-endian typed arrays;
* ``cbor-raw`` (``topics.mjs``): ``{"op": "publish", "topic", "msg":
  {"secs", "nsecs", "bytes"}}`` around the CDR bytes;
* ``png`` (``png.mjs``): the UTF-8 JSON text as the pixels of an RGB PNG,
  base64'd, in a ``{"op": "png", "data"}`` message;
* fragments of a long JSON text (``session.mjs`` sendText).

Incoming binary requests are CBOR (``cbor2``); ``decode_request`` reads one
and ``jsonable`` turns what is not JSON in it (byte strings, typed arrays)
into rosbridge's JSON conventions (base64, lists).
"""

import base64
import io
import json
import math
import struct
import time
import zlib

import cbor2
from colcon_wasm.error import ColconWasmError

NUMERIC = {'byte': 'B', 'char': 'B', 'uint8': 'B', 'int8': 'b', 'int16': 'h', 'uint16': 'H',
           'int32': 'i', 'uint32': 'I', 'int64': 'q', 'uint64': 'Q', 'float32': 'f',
           'float64': 'd'}
FLOATS = {'float32', 'float64'}
BYTES = {'byte', 'char', 'uint8'}
"""The primitive field types of ROS 2 messages."""
PRIMITIVES = {'bool', 'byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32',
              'int64', 'uint64', 'float32', 'float64', 'string', 'wstring'}
# RFC 8746 little-endian typed-array tags, as cbor.mjs writes them
TAGS = {'int8': 72, 'int16': 77, 'uint16': 69, 'int32': 78, 'uint32': 70, 'int64': 79,
        'uint64': 71, 'float32': 85, 'float64': 86}
TAG_FORMATS = {64: 'B', 68: 'B', 69: 'H', 70: 'I', 71: 'Q', 72: 'b', 77: 'h', 78: 'i',
               79: 'q', 85: 'f', 86: 'd'}
HEADER = 'std_msgs/msg/Header'
TIME = 'builtin_interfaces/msg/Time'
COMPRESSION_RANK = {'none': 0, 'png': 1, 'cbor': 2, 'cbor-raw': 3}


class FormError(ColconWasmError):
    """A message that does not fit its type description; the text names the field."""


def normalize(type_name, kind='msg'):
    """Return ``pkg/msg/Name`` for ``pkg/Name`` (other names unchanged)."""
    parts = type_name.strip().split('/')
    return f'{parts[0]}/{kind}/{parts[1]}' if len(parts) == 2 else type_name.strip()


def _now():
    t = time.time()
    return {'sec': int(t), 'nanosec': int(round((t % 1) * 1000)) * 1000000}


class CborWriter:
    """The subset of RFC 8949 that cbor.mjs writes, with its choices (float64, minimal heads)."""

    def __init__(self):  # noqa: D107
        self.out = io.BytesIO()

    def head(self, major, n):
        """Write a major type with its argument, in the shortest form."""
        m = major << 5
        if n < 24:
            self.out.write(bytes((m | n,)))
        elif n < 0x100:
            self.out.write(bytes((m | 24, n)))
        elif n < 0x10000:
            self.out.write(struct.pack('>BH', m | 25, n))
        elif n <= 0xffffffff:
            self.out.write(struct.pack('>BI', m | 26, n))
        else:
            self.out.write(struct.pack('>BQ', m | 27, n))

    def int(self, v):
        """Write an integer."""
        if v >= 0:
            self.head(0, v)
        else:
            self.head(1, -1 - v)

    def float64(self, v):
        """Write a float64; NaN is a float64 too, as cbor.mjs writes it."""
        self.out.write(b'\xfb' + struct.pack('>d', v))

    def string(self, s):
        """Write a text string."""
        b = s.encode('utf-8')
        self.head(3, len(b))
        self.out.write(b)

    def byte_string(self, b):
        """Write a byte string."""
        self.head(2, len(b))
        self.out.write(b)

    def value(self, v):
        """Write a JSON-like value: dicts as maps, lists, bytes, numbers (ints exact)."""
        if v is None:
            self.out.write(b'\xf6')
        elif v is True or v is False:
            self.out.write(b'\xf5' if v else b'\xf4')
        elif isinstance(v, int):
            self.int(v)
        elif isinstance(v, float):
            if v.is_integer() and abs(v) <= 2 ** 53:
                self.int(int(v))
            else:
                self.float64(v)
        elif isinstance(v, str):
            self.string(v)
        elif isinstance(v, (bytes, bytearray, memoryview)):
            self.byte_string(bytes(v))
        elif isinstance(v, (list, tuple)):
            self.head(4, len(v))
            for x in v:
                self.value(x)
        elif isinstance(v, dict):
            self.head(5, len(v))
            for k, x in v.items():
                self.string(str(k))
                self.value(x)
        else:
            raise TypeError(f'CBOR cannot encode a {type(v).__name__}')

    def result(self):
        """Return the bytes written."""
        return self.out.getvalue()


def _publish_head(topic, ttl):
    """Start a CBOR ``publish`` op: its map head and keys up to ``msg`` (``ttl`` comes last)."""
    w = CborWriter()
    w.head(5, 3 if ttl is None else 4)
    w.string('op')
    w.string('publish')
    w.string('topic')
    w.string(topic)
    w.string('msg')
    return w


def _publish_tail(w, ttl):
    if ttl is not None:
        w.string('ttl')
        w.value(ttl)
    return w.result()


def cbor_raw_publish(topic, cdr, secs, nsecs, ttl=None):
    """Return rosbridge's cbor-raw ``publish`` of CDR bytes (topics.mjs's form, ``ttl`` last)."""
    w = _publish_head(topic, ttl)
    w.head(5, 3)
    w.string('secs')
    w.int(secs)
    w.string('nsecs')
    w.int(nsecs)
    w.string('bytes')
    w.byte_string(cdr)
    return _publish_tail(w, ttl)


class Forms:
    """The cbor form of JSON messages, from the type descriptions (types.json ``messages``)."""

    def __init__(self, messages):  # noqa: D107
        self.messages = messages

    def has(self, type_name):
        """Whether the type (and so its cbor form) is described."""
        return normalize(type_name) in self.messages

    def cbor_publish(self, topic, type_name, msg, ttl=None):
        """Return the bytes of a ``publish`` op with ``msg`` in rosbridge's cbor form."""
        w = _publish_head(topic, ttl)
        self._message(w, normalize(type_name), msg, '')
        return _publish_tail(w, ttl)

    def cbor_message(self, type_name, msg):
        """Return the rosbridge cbor form of one message (a JSON object) alone."""
        w = CborWriter()
        self._message(w, normalize(type_name), msg, '')
        return w.result()

    def _message(self, w, full, msg, path):
        if full == TIME and msg == 'now':
            msg = _now()
        description = self.messages.get(full)
        if description is None:
            raise FormError(f"field '{path or '.'}': type {full} has no type description")
        if not isinstance(msg, dict):
            raise FormError(f"field '{path or '.'}': expected a JSON object for {full}, got "
                            f'{type(msg).__name__}')
        fields = description.get('fields', [])
        w.head(5, len(fields))
        for f in fields:
            name = f['name']
            p = f'{path}.{name}' if path else name
            w.string(name)
            if name in msg:
                value = msg[name]
            elif full == HEADER and name == 'stamp':
                value = _now()
            else:
                value = self._default(f)
            self._field(w, f, value, p)

    def _default(self, f):
        if 'default' in f:
            return f['default']
        if f.get('sequence'):
            return []
        kind = f['type']
        if kind in NUMERIC:
            zero = 0.0 if kind in FLOATS else 0
        elif kind == 'bool':
            zero = False
        elif kind in ('string', 'wstring'):
            zero = ''
        else:
            zero = {}
        return [zero] * f['array_size'] if 'array_size' in f else zero

    def _field(self, w, f, value, path):
        kind = f['type']
        if f.get('sequence') or 'array_size' in f:
            if kind in BYTES:
                w.byte_string(_bytes(value, kind, path))
            elif kind in NUMERIC:
                items = _list(value, kind, path)
                fmt = NUMERIC[kind]
                try:
                    data = struct.pack(f'<{len(items)}{fmt}', *[
                        _float(x, kind, path) if kind in FLOATS else _int(x, kind, path)
                        for x in items])
                except struct.error as e:
                    raise FormError(f"field '{path}': {e} does not fit {kind}")
                w.head(6, TAGS[kind])
                w.byte_string(data)
            else:
                items = _list(value, kind, path)
                w.head(4, len(items))
                for i, x in enumerate(items):
                    self._one(w, kind, x, f'{path}[{i}]')
            return
        self._one(w, kind, value, path)

    def _one(self, w, kind, v, path):
        if kind in ('string', 'wstring'):
            if not isinstance(v, str):
                raise FormError(f"field '{path}': expected a string")
            w.string(v)
        elif kind == 'bool':
            w.out.write(b'\xf5' if v else b'\xf4')
        elif kind in FLOATS:
            w.float64(_float(v, kind, path))
        elif kind in ('int64', 'uint64'):
            # cdr.mjs decodes them as BigInt, which cbor.mjs writes with an 8-byte argument
            n = _int(v, kind, path)
            w.out.write(struct.pack('>BQ', 0x1b if n >= 0 else 0x3b, n if n >= 0 else -1 - n))
        elif kind in NUMERIC:
            w.int(_int(v, kind, path))
        else:
            self._message(w, normalize(kind), v, path)


def _list(value, kind, path):
    if not isinstance(value, (list, tuple)):
        raise FormError(f"field '{path}': expected an array of {kind}")
    return value


def _bytes(value, kind, path):
    if isinstance(value, (bytes, bytearray)):
        return bytes(value)
    if isinstance(value, str):
        try:
            return base64.b64decode(value, validate=True)
        except ValueError:
            raise FormError(f"field '{path}': expected base64 text or an array of "
                            f'{kind}') from None
    try:
        return bytes(_int(x, kind, path) for x in _list(value, kind, path))
    except ValueError:
        raise FormError(f"field '{path}': an element does not fit {kind}") from None


def _int(v, kind, path):
    if isinstance(v, bool):
        raise FormError(f"field '{path}': expected an integer ({kind}), got a boolean")
    if isinstance(v, int):
        return v
    if isinstance(v, float) and v.is_integer():
        return int(v)
    if isinstance(v, str) and v.strip().lstrip('-').isdigit():
        return int(v)
    raise FormError(f"field '{path}': expected an integer ({kind}), got {json.dumps(v)[:40]}")


def _float(v, kind, path):
    if v is None:
        return math.nan
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise FormError(f"field '{path}': expected a number ({kind})")
    return float(v)


# ------------------------------------------------------------------ png, fragments

def _chunk(kind, data):
    body = kind + data
    return struct.pack('>I', len(data)) + body + struct.pack('>I', zlib.crc32(body))


def png_encode_text(text):
    """Return the base64 PNG of a text, as png.mjs (rosbridge's png compression) makes it."""
    data = text.encode('utf-8')
    width = max(1, int(math.floor(math.sqrt(len(data) / 3))))
    height = max(1, int(math.ceil(len(data) / 3 / width)))
    row = width * 3
    raw = bytearray(b'\n' * ((row + 1) * height))
    for y in range(height):
        start = y * (row + 1)
        raw[start] = 0  # filter: none
        part = data[y * row:(y + 1) * row]
        raw[start + 1:start + 1 + len(part)] = part
    ihdr = struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)
    png = b'\x89PNG\r\n\x1a\n' + _chunk(b'IHDR', ihdr) + _chunk(
        b'IDAT', zlib.compress(bytes(raw))) + _chunk(b'IEND', b'')
    return base64.b64encode(png).decode('ascii')


def png_message(text):
    """Return rosbridge's ``png`` op carrying a JSON text."""
    return json.dumps({'op': 'png', 'data': png_encode_text(text)}, separators=(',', ':'))


def fragments(text, size, fid):
    """Return the ``fragment`` ops of a text longer than ``size`` (else the text alone)."""
    if not size or len(text) <= size:
        return [text]
    total = (len(text) + size - 1) // size
    return [json.dumps({'op': 'fragment', 'id': fid, 'data': text[i * size:(i + 1) * size],
                        'num': i, 'total': total}, separators=(',', ':'))
            for i in range(total)]


# ------------------------------------------------------------------ incoming CBOR

def decode_request(data):
    """
    Return the value of one binary (CBOR) request.

    :raises ValueError: naming what is wrong, when it is not exactly one CBOR item
    """
    stream = io.BytesIO(data)
    try:
        value = cbor2.CBORDecoder(stream).decode()
    except (cbor2.CBORDecodeError, EOFError, ValueError, TypeError, OverflowError) as e:
        raise ValueError(f'a binary message is not CBOR ({e}); the relay reads '
                         'rosbridge requests as JSON text or CBOR') from None
    if stream.tell() != len(data):
        raise ValueError(f'a binary message is not one CBOR item: {len(data) - stream.tell()} '
                         'bytes follow it')
    return value


def jsonable(value):
    """Return a CBOR-decoded value in JSON's terms: bytes as base64, typed arrays as lists."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, (bytes, bytearray)):
        return base64.b64encode(value).decode('ascii')
    if isinstance(value, cbor2.CBORTag):
        fmt = TAG_FORMATS.get(value.tag)
        if fmt and isinstance(value.value, bytes):
            size = struct.calcsize(fmt)
            if len(value.value) % size:
                raise ValueError(f'a typed array of tag {value.tag} has {len(value.value)} '
                                 f'bytes, not a multiple of {size}')
            if fmt == 'B':
                return base64.b64encode(value.value).decode('ascii')
            return list(struct.unpack(f'<{len(value.value) // size}{fmt}',
                                      value.value))
        return jsonable(value.value)
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if value is None or isinstance(value, (str, int, float)):
        return value
    if isinstance(value, (set, frozenset)):
        return [jsonable(v) for v in value]
    if isinstance(value, cbor2.CBORSimpleValue) or value is cbor2.undefined:
        return None
    # what else cbor2 decodes (dates, decimals, fractions, UUIDs, ...): its text
    return str(value)
