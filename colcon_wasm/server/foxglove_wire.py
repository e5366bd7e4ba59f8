# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Foxglove WebSocket protocol's binary messages and its subprotocols.

As foxglove/ws-protocol ``docs/spec.md`` defines them (the Node.js server of
``run``/``launch --foxglove`` speaks the same, in
packages/wasm_js/src/bridges/foxglove/protocol.mjs): little endian, one
opcode byte first. Wire format only: no logic.
"""

import struct

from colcon_wasm.error import ColconWasmError

SUBPROTOCOLS = ('foxglove.websocket.v1', 'foxglove.sdk.v1')

# server to client
MESSAGE_DATA = 0x01
TIME = 0x02
SERVICE_CALL_RESPONSE = 0x03
# client to server
CLIENT_PUBLISH = 0x01
SERVICE_CALL_REQUEST = 0x02

_MESSAGE_HEAD = struct.Struct('<BIQ')
_TIME = struct.Struct('<BQ')
_CALL_HEAD = struct.Struct('<BIII')
_PUBLISH_HEAD = struct.Struct('<BI')

# status levels
INFO, WARNING, ERROR = 0, 1, 2


class WireError(ColconWasmError):
    """A binary client message that is not one of the protocol's."""


def message_data(subscription, timestamp_ns, payload):
    """Encode a messageData message."""
    return _MESSAGE_HEAD.pack(MESSAGE_DATA, subscription, timestamp_ns) + bytes(payload)


def time_message(timestamp_ns):
    """Encode a time message."""
    return _TIME.pack(TIME, timestamp_ns)


def service_call_response(service, call, encoding, payload):
    """Encode a serviceCallResponse message."""
    name = encoding.encode('utf-8')
    return _CALL_HEAD.pack(SERVICE_CALL_RESPONSE, service, call, len(name)) + name + \
        bytes(payload)


def decode_client_binary(data):
    """
    Decode a binary client message.

    :returns: ``('publish', channel, payload)`` or ``('call', service, call,
      encoding, payload)``
    :raises WireError: naming what is wrong with it
    """
    if not data:
        raise WireError('an empty binary message')
    op = data[0]
    if op == CLIENT_PUBLISH:
        if len(data) < _PUBLISH_HEAD.size:
            raise WireError('a clientPublish message shorter than its 5-byte head')
        _, channel = _PUBLISH_HEAD.unpack_from(data)
        return ('publish', channel, memoryview(data)[_PUBLISH_HEAD.size:])
    if op == SERVICE_CALL_REQUEST:
        if len(data) < _CALL_HEAD.size:
            raise WireError('a serviceCallRequest message shorter than its 13-byte head')
        _, service, call, length = _CALL_HEAD.unpack_from(data)
        end = _CALL_HEAD.size + length
        if len(data) < end:
            raise WireError('a serviceCallRequest whose encoding runs past its end')
        return ('call', service, call, bytes(data[_CALL_HEAD.size:end]).decode('utf-8', 'replace'),
                memoryview(data)[end:])
    raise WireError(f'unknown binary opcode 0x{op:02x} (clientPublish is 0x01, '
                    'serviceCallRequest 0x02)')


def choose_subprotocol(headers):
    """Return the first of the client's offered subprotocols that is Foxglove's, or None."""
    offered = [p.strip() for p in (headers.get('Sec-WebSocket-Protocol') or '').split(',')]
    return next((p for p in offered if p in SUBPROTOCOLS), None)
