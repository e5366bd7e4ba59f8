# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Where the relay (relay.py) meets HTTP: ``/rosbridge`` of serve, and the ``--rosbridge`` port.

The pages of serve connect to ``ws://HOST:PORT/rosbridge`` of serve itself
(same origin only: a WebSocket is not bound by the browser's same-origin
policy, so the Origin header is checked). Other rosbridge clients connect to
the ``--rosbridge [HOST:]PORT`` listener, with ``--rosbridge-token`` when
one is set (``?token=`` or ``Authorization: Bearer``).
"""

import hmac
from http.server import BaseHTTPRequestHandler
from http.server import ThreadingHTTPServer
import socket
from urllib.parse import parse_qs
from urllib.parse import urlsplit

from colcon_wasm.server.http import bind_error
from colcon_wasm.server.websocket import handshake_response

RELAY_PATH = '/rosbridge'


def refuse(handler, status, text):
    """Answer an HTTP request that is not let in with a plain-text status and close it."""
    body = (text + '\n').encode('utf-8')
    handler.send_response(status)
    handler.send_header('Content-Type', 'text/plain; charset=utf-8')
    handler.send_header('Content-Length', str(len(body)))
    handler.send_header('Connection', 'close')
    handler.end_headers()
    handler.wfile.write(body)
    handler.close_connection = True


def _token(handler):
    auth = handler.headers.get('Authorization') or ''
    if auth.lower().startswith('bearer '):
        return auth[7:].strip()
    values = parse_qs(urlsplit(handler.path).query).get('token')
    return values[-1] if values else ''


def upgrade(handler, endpoint, *, token=None, same_origin=False, path=RELAY_PATH):
    """
    Turn a request into a WebSocket of ``endpoint`` (or refuse it); blocks until it ends.

    :param endpoint: what serves the socket: ``endpoint.serve(sock, peer)`` (the
      relay, or the page's bag service at ``/bag``)
    :param path: the URL path, for the messages
    """
    if same_origin:
        origin = handler.headers.get('Origin')
        host = handler.headers.get('Host', '')
        if origin is not None and urlsplit(origin).netloc != host:
            other = ('; other rosbridge clients connect to the --rosbridge port'
                     if path == RELAY_PATH else '')
            refuse(handler, 403, f'only the pages of this colcon-wasm serve may use {path}'
                                 f'{other}')
            return
    if token and not hmac.compare_digest(_token(handler), token):
        refuse(handler, 401, 'this rosbridge relay needs a token: connect to '
                             'ws://HOST:PORT/?token=TOKEN (or send Authorization: Bearer TOKEN)')
        return
    response = handshake_response(handler.headers)
    if response is None:
        refuse(handler, 400, f'{path} is a WebSocket endpoint: connect with a WebSocket '
                             'client (ws://)')
        return
    handler.connection.sendall(response)
    handler.close_connection = True
    host, port = handler.client_address[:2]
    endpoint.serve(handler.connection, f'{host}:{port}')


class RelayRequestHandler(BaseHTTPRequestHandler):
    """The --rosbridge port: every GET is a rosbridge WebSocket."""

    protocol_version = 'HTTP/1.1'
    server_version = 'colcon-wasm'

    def setup(self):
        """No Nagle delay: rosbridge messages are small and many."""
        super().setup()
        self.connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def do_GET(self):  # noqa: N802
        """Upgrade to the relay."""
        upgrade(self, self.server.relay, token=self.server.token)

    def log_message(self, format, *args):  # noqa: A002
        """Log nothing: the relay logs what matters."""


class RelayServer(ThreadingHTTPServer):
    """The listener of ``serve --rosbridge [HOST:]PORT``."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, relay, host, port, token=None):
        """
        Bind to ``host:port`` (port 0 picks a free port).

        :raises ServeError: when the address is taken or cannot be bound
        """
        self.relay = relay
        self.token = token
        if ':' in host:
            self.address_family = socket.AF_INET6
        try:
            super().__init__((host, port), RelayRequestHandler)
        except OSError as e:
            raise bind_error(e, host, port, other='another rosbridge server, or another server?',
                             fix='--rosbridge HOST:PORT (port 0 picks a free port)',
                             option='--rosbridge') from None

    @property
    def url(self):
        """Return ws://host:port of the relay."""
        host, port = self.server_address[:2]
        return f"ws://{(f'[{host}]' if ':' in host else host)}:{port}"
