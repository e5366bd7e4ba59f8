# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""WebSocket connections (RFC 6455) for ``colcon-wasm serve``'s relay, and its clients.

Standard library only, one thread reading each connection (the server's
handler thread) and one writing it, so that a peer that stops reading never
blocks whoever sends to it: what waits for it is counted, and past
``max_queued_bytes`` the peer is cut off. Text and binary messages,
fragmentation, ping/pong and close; no extensions. A message larger than
``max_message_bytes`` is skipped and reported to ``on_oversize``; the
connection stays up. A control frame (close, ping, pong) over 125 bytes, or
fragmented, closes the connection (1002) before its payload is read.
:func:`connect` opens the client side (``colcon-wasm record`` against a
rosbridge server): the same connection, with masked frames out and unmasked
frames in.
"""

import base64
import hashlib
import os
import queue
import socket
import struct
import threading
from urllib.parse import urlsplit

from colcon_wasm.error import ColconWasmError

GUID = '258EAFA5-E914-47DA-95CA-C5AB0DC85B11'
TEXT, BINARY, CLOSE, PING, PONG = 0x1, 0x2, 0x8, 0x9, 0xA
MAX_CONTROL_BYTES = 125  # RFC 6455 5.5: close, ping and pong carry at most 125 bytes
CLOSE_TIMEOUT = 2.0  # seconds what is queued (and the close frame) may take to go out at the end


class WebSocketError(ColconWasmError):
    """The peer broke the protocol; ``code`` is the close code to send."""

    def __init__(self, code, message):  # noqa: D107
        super().__init__(message)
        self.code = code


def accept_key(key):
    """Return the Sec-WebSocket-Accept value of a Sec-WebSocket-Key."""
    digest = hashlib.sha1((key + GUID).encode('ascii')).digest()
    return base64.b64encode(digest).decode('ascii')


def handshake_response(headers, subprotocol=None):
    """
    Return the 101 response to an upgrade request, or None if it is not one.

    :param headers: a mapping of the request's headers (case-insensitive get)
    :param subprotocol: the subprotocol accepted (Sec-WebSocket-Protocol), if any
    """
    key = headers.get('Sec-WebSocket-Key')
    if 'websocket' not in (headers.get('Upgrade') or '').lower() or not key:
        return None
    protocol = f'Sec-WebSocket-Protocol: {subprotocol}\r\n' if subprotocol else ''
    return ('HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n'
            f'Sec-WebSocket-Accept: {accept_key(key.strip())}\r\n{protocol}\r\n').encode('ascii')


def encode_frame(opcode, payload, masked=False):
    """Return a frame: unmasked (server to client), or ``masked`` (client to server)."""
    n = len(payload)
    bit = 0x80 if masked else 0
    if n < 126:
        header = struct.pack('!BB', 0x80 | opcode, bit | n)
    elif n < 65536:
        header = struct.pack('!BBH', 0x80 | opcode, bit | 126, n)
    else:
        header = struct.pack('!BBQ', 0x80 | opcode, bit | 127, n)
    if not masked:
        return header + payload
    key = os.urandom(4)
    return header + key + _unmask(payload, key)


def connect(url, *, timeout, max_message_bytes, max_queued_bytes):
    """
    Open a client connection to ``ws://HOST:PORT/PATH`` (wss is not supported).

    :param timeout: seconds for the TCP connection and the handshake
    :returns: a :class:`Connection` (client side)
    :raises WebSocketError: naming the URL, when it cannot connect or the
      server does not accept the upgrade
    """
    parts = urlsplit(url)
    if parts.scheme != 'ws' or not parts.hostname:
        raise WebSocketError(1002, f"'{url}' is not a ws://HOST:PORT URL (wss is not supported)")
    port = parts.port or 80
    try:
        sock = socket.create_connection((parts.hostname, port), timeout=timeout)
    except OSError as e:
        raise WebSocketError(
            1006, f'cannot connect to {url}: {e.strerror or e}') from None
    key = base64.b64encode(os.urandom(16)).decode('ascii')
    path = (parts.path or '/') + (f'?{parts.query}' if parts.query else '')
    host = f'[{parts.hostname}]' if ':' in parts.hostname else parts.hostname
    request = (f'GET {path} HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\n'
               f'Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n'
               'Sec-WebSocket-Version: 13\r\n\r\n')
    try:
        sock.sendall(request.encode('ascii'))
        response = b''
        while b'\r\n\r\n' not in response:
            chunk = sock.recv(1)
            if not chunk:
                raise ConnectionError('the server closed the connection')
            response += chunk
            if len(response) > 16384:
                raise ConnectionError('the handshake response has no end')
    except OSError as e:
        sock.close()
        raise WebSocketError(1006, f'{url}: the WebSocket handshake failed: {e}') from None
    status, *lines = response.decode('latin-1').split('\r\n')
    headers = {k.strip().lower(): v.strip() for k, _, v in
               (line.partition(':') for line in lines if ':' in line)}
    if ' 101 ' not in f'{status} ' or headers.get('sec-websocket-accept') != accept_key(key):
        sock.close()
        raise WebSocketError(
            1002, f'{url} did not accept a WebSocket connection ({status.strip()}): is it a '
                  'rosbridge server?')
    sock.settimeout(None)
    return Connection(sock, max_message_bytes=max_message_bytes,
                      max_queued_bytes=max_queued_bytes, client=True)


class Connection:
    """One WebSocket peer: ``run(on_message)`` reads, ``send()`` queues."""

    def __init__(self, sock, *, max_message_bytes, max_queued_bytes, on_oversize=None,
                 on_cut_off=None, on_drain=None, client=False):
        """
        Wrap a socket whose handshake is done; ``on_drain()``: see ``watch_drain``.

        :param client: True on the client side (frames out masked, in unmasked)
        """
        self.sock = sock
        self.client = client
        self.max_message_bytes = max_message_bytes
        self.max_queued_bytes = max_queued_bytes
        self.on_oversize = on_oversize
        self.on_cut_off = on_cut_off
        self.on_drain = on_drain
        self.queued_bytes = 0
        self._drain_level = None
        self.closed = False
        self._lock = threading.Lock()
        self._queue = queue.Queue()
        self._writer = threading.Thread(target=self._write_loop, daemon=True)
        self._writer.start()

    def _recv_exact(self, n):
        chunks = []
        while n:
            chunk = self.sock.recv(min(n, 1 << 20))
            if not chunk:
                raise ConnectionError('the peer closed the connection')
            chunks.append(chunk)
            n -= len(chunk)
        return b''.join(chunks)

    def _skip(self, n):
        while n:
            chunk = self.sock.recv(min(n, 1 << 20))
            if not chunk:
                raise ConnectionError('the peer closed the connection')
            n -= len(chunk)

    def _frame(self):
        b0, b1 = self._recv_exact(2)
        opcode, fin, masked, n = b0 & 0x0F, bool(b0 & 0x80), bool(b1 & 0x80), b1 & 0x7F
        if b0 & 0x70:
            raise WebSocketError(1002, 'RSV bits set, but no extension was negotiated')
        if masked == self.client:
            raise WebSocketError(1002, 'a server frame is masked (RFC 6455 5.1)' if self.client
                                 else 'a client frame is not masked (RFC 6455 5.1)')
        if n == 126:
            n, = struct.unpack('!H', self._recv_exact(2))
        elif n == 127:
            n, = struct.unpack('!Q', self._recv_exact(8))
        key = self._recv_exact(4) if masked else b''
        return opcode, fin, n, key

    def run(self, on_message):
        """Read messages until the peer closes; ``on_message(data, binary)`` for each."""
        parts, parts_opcode, parts_bytes, skipping = None, 0, 0, False
        try:
            while not self.closed:
                opcode, fin, n, key = self._frame()
                if opcode >= 0x8:
                    if not fin or n > MAX_CONTROL_BYTES:
                        # refused before reading it: a ping that claims 2^63 bytes is no
                        # allocation of that size
                        raise WebSocketError(1002, 'a control frame is fragmented or longer '
                                                   'than 125 bytes (RFC 6455 5.5)')
                    payload = _unmask(self._recv_exact(n), key)
                    if opcode == PING:
                        self._enqueue(encode_frame(PONG, payload, self.client))
                    elif opcode == CLOSE:
                        self.close(struct.unpack('!H', payload[:2])[0] if len(payload) >= 2
                                   else 1000)
                        break
                    continue
                if skipping or n > self.max_message_bytes or \
                        parts_bytes + n > self.max_message_bytes:
                    self._skip(n)
                    if not skipping and self.on_oversize:
                        self.on_oversize(parts_bytes + n)
                    skipping = not fin
                    parts, parts_bytes = None, 0
                    continue
                payload = _unmask(self._recv_exact(n), key)
                if opcode == 0:
                    if parts is None:
                        raise WebSocketError(1002, 'a continuation frame without a message')
                    parts.append(payload)
                    parts_bytes += n
                else:
                    parts, parts_opcode, parts_bytes = [payload], opcode, n
                if fin:
                    data = b''.join(parts)
                    parts, parts_bytes = None, 0
                    if parts_opcode == TEXT:
                        try:
                            text = data.decode('utf-8')
                        except UnicodeDecodeError:
                            raise WebSocketError(1007, 'a text message is not UTF-8') from None
                        on_message(text, False)
                    else:
                        on_message(data, True)
        except WebSocketError as e:
            self.close(e.code, str(e))
        except (ConnectionError, OSError):
            pass
        finally:
            self.close()
            # the close frame goes out before the caller closes the socket (the server's
            # handler closes it as soon as this returns)
            self._writer.join(timeout=CLOSE_TIMEOUT)

    def send(self, data):
        """Queue a text (str) or binary (bytes) message; False once closed or cut off."""
        if isinstance(data, str):
            frame = encode_frame(TEXT, data.encode('utf-8'), self.client)
        else:
            frame = encode_frame(BINARY, bytes(data), self.client)
        return self._enqueue(frame)

    def watch_drain(self, level):
        """
        Call ``on_drain()`` (from the writer thread) once fewer than ``level`` bytes wait.

        Return False (and call nothing) when fewer wait already.
        """
        with self._lock:
            if self.queued_bytes < level or self.closed:
                return False
            self._drain_level = level
            return True

    def _enqueue(self, frame):
        with self._lock:
            if self.closed:
                return False
            if self.queued_bytes + len(frame) > self.max_queued_bytes:
                cut = True
            else:
                cut = False
                self.queued_bytes += len(frame)
                self._queue.put(frame)
        if cut:
            if self.on_cut_off:
                self.on_cut_off(self.queued_bytes)
            self.close(1008, 'the client did not read', now=True)
            return False
        return True

    def _write_loop(self):
        while True:
            frame = self._queue.get()
            if frame is None:
                break
            try:
                self.sock.sendall(frame)
            except OSError:
                break
            with self._lock:
                self.queued_bytes -= len(frame)
                drained = self._drain_level is not None and self.queued_bytes < self._drain_level
                if drained:
                    self._drain_level = None
            if drained and self.on_drain:
                self.on_drain()
        self.closed = True
        try:
            self.sock.shutdown(2)
        except OSError:
            pass

    def close(self, code=None, reason='', now=False):
        """
        End the connection: what is queued is sent first, then a close frame (with a code).

        With ``now`` (a peer that does not read) the socket is shut at once.
        """
        with self._lock:
            if self.closed:
                return
            self.closed = True
            if code is not None and not now:
                payload = struct.pack('!H', code) + reason.encode('utf-8')[:120]
                self._queue.put(encode_frame(CLOSE, payload, self.client))
            self._queue.put(None)
        if now:
            try:
                self.sock.shutdown(2)
            except OSError:
                pass


def _unmask(payload, key):
    if not payload or not key:
        return payload
    n = len(payload)
    mask = (key * (n // 4 + 1))[:n]
    return (int.from_bytes(payload, 'little') ^ int.from_bytes(mask, 'little')).to_bytes(
        n, 'little')
