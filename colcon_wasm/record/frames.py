# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The frames between the Node host and the launcher (one pipe each way).

Every frame is ``u32 length`` (of what follows), ``u8 kind``, then the body
(little endian). packages/wasm_js/src/bridges/record/frames.mjs is the other
side.

Recording (host to launcher):

- ``CHANNEL``: JSON ``{"id", "topic", "type", "qos": [profile, ...]}``, the
  offered QoS of the topic's publishers in the JS form of qos.mjs; the host
  subscribes once the launcher answered ``READY``;
- ``WRITTEN``: JSON, a list of what one write of the host put into the bag
  itself (chunks without compression, bridges/record/file_sink.mjs), in
  file order: ``{"kind": "records", "offset", "end"}`` or ``{"kind": "chunk",
  "offset", "chunkLength", "indexLength", "size", "start", "end" (ns, as
  text), "messages", "channels": [[id, count, index length], ...]}``;
- ``FAILED``: JSON ``{"code", "message", "kept"}``: a write of the host
  failed (a full disk); the bag was cut back to ``kept`` bytes;
- ``CHUNK``: ``u32 n``, ``n`` bytes of JSON ``{"records": R, "start",
  "end" (ns, as text), "messages", "channels": [[id, count, index length],
  ...]}``, then ``R`` bytes of the chunk's MCAP Message records, then its
  MessageIndex records (built by the host's recording worker,
  bridges/record/chunk_builder.mjs), for the launcher to compress;
- ``NOTE``: JSON ``{"dropped": N, "lost": M}`` when the host dropped
  messages (the launcher did not keep up) or the bus lost some before the
  recorder took them (a publisher's history overwritten).

Replies to recording (launcher to host, a pipe of their own):

- ``READY``: ``u32 channel id``, then the Schema and Channel records the
  host writes into the bag before the channel's first chunk (none when the
  launcher writes the bag itself);
- ``REFUSED``: JSON ``{"id", "reason"}``: the topic is not recorded.

Playing (launcher to host):

- ``CHANNEL``: JSON ``{"id", "topic", "type", "qos": profile}``;
- ``MESSAGE``: ``u32 channel, u32 sec, u32 nanosec, f64 offset_ns`` then the
  CDR bytes: the log time, and its distance from the first message played
  (loops add the length of the bag to it);
- ``END``: JSON ``{"messages": N}``: nothing more comes.
"""

import json
import struct

CHANNEL = 1
MESSAGE = 2
NOTE = 3
END = 4
CHUNK = 5
READY = 6
REFUSED = 7
WRITTEN = 8
FAILED = 9

_HEAD = struct.Struct('<IB')
_RECORDED = struct.Struct('<Idd')
_META_LENGTH = struct.Struct('<I')
_PLAYED = struct.Struct('<IIId')
_CHANNEL_ID = struct.Struct('<I')


def encode_json(kind, value):
    """Frame a JSON body."""
    body = json.dumps(value).encode('utf-8')
    return _HEAD.pack(len(body) + 1, kind) + body


def encode_ready(channel, records):
    """Frame the answer to a recorded CHANNEL: its records for the host to write (or none)."""
    return _HEAD.pack(1 + _CHANNEL_ID.size + len(records), READY) + \
        _CHANNEL_ID.pack(channel) + bytes(records)


def encode_played(channel, log_time_ns, offset_ns, data):
    """Frame one message to play."""
    sec, nsec = divmod(int(log_time_ns), 1000000000)
    head = _PLAYED.pack(channel, sec & 0xffffffff, nsec, float(offset_ns))
    return _HEAD.pack(1 + len(head) + len(data), MESSAGE) + head + bytes(data)


def decode_recorded(body):
    """
    Decode a recorded message (the page's frames to serve's /bag socket).

    Its body is ``u32 channel, f64 log_ms, f64 publish_ms`` then the CDR
    bytes (milliseconds since the epoch, sub-millisecond fraction kept).

    :returns: ``(channel, log_time_ns, publish_time_ns, data)``
    """
    channel, log_ms, publish_ms = _RECORDED.unpack_from(body)
    data = memoryview(body)[_RECORDED.size:]  # no copy: an image is a megabyte
    return channel, round(log_ms * 1e6), round(publish_ms * 1e6), data


def decode_chunk(body):
    """
    Decode the body of a recorded CHUNK frame (no copy of its records).

    :returns: ``(records, start_ns, end_ns, indexes, channels)`` as
      :meth:`colcon_wasm.record.bag_writer.BagWriter.write_chunk` takes them
    """
    view = memoryview(body)
    (n,) = _META_LENGTH.unpack_from(view)
    meta = json.loads(bytes(view[4:4 + n]))
    at = 4 + n + meta['records']
    channels = [tuple(c) for c in meta['channels']]
    return view[4 + n:at], int(meta['start']), int(meta['end']), view[at:], channels


def read_frames(stream):
    """
    Yield ``(kind, body)`` from a binary stream until it ends.

    A frame cut off by the end of the stream (the host died) ends it too.
    Every body is read into one buffer that grows as needed, and is yielded
    as a memoryview of it, valid until the next frame is read: no
    allocation (and no page faults) per megabyte chunk. Copy what is kept.
    """
    buffer = bytearray(0)
    head = bytearray(_HEAD.size)
    while True:
        if not _read_into(stream, memoryview(head)):
            return
        length, kind = _HEAD.unpack(head)
        if len(buffer) < length - 1:
            buffer = bytearray(max(length - 1, 2 * len(buffer)))
        body = memoryview(buffer)[:length - 1]
        if not _read_into(stream, body):
            return
        yield kind, body


def _read_into(stream, view):
    """Fill ``view`` from the stream; False when it ends first."""
    while view:
        n = stream.readinto(view)
        if not n:
            return False
        view = view[n:]
    return True
