# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The HTTP server of ``colcon-wasm serve``.

Every response carries the headers that make the page cross-origin isolated
(``SharedArrayBuffer`` needs them): COOP ``same-origin``, COEP
``require-corp`` and CORP ``same-origin``.  GET and HEAD only; no directory
listing; HTTP/1.1 keep-alive; one thread per connection. WebSockets:
``/rosbridge`` (serve --rosbridge, relay_http.py), ``/bag`` (the page's
record and replay, bag_socket.py), whose recordings are ``/bag/files/...``,
and ``/launch`` (the page's launch files, launch_socket.py).

Bound to a loopback address (the default), the server answers only requests
whose ``Host`` is a loopback name (``localhost``, ``127.0.0.1``, ``[::1]``):
a web page of another site that makes its own name resolve to 127.0.0.1
(DNS rebinding) would otherwise be same-origin with the answers, read the
install space and start its launch files (docs/security.md).
"""

import errno
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler
from http.server import ThreadingHTTPServer
import shutil
import socket
from urllib.parse import parse_qs
from urllib.parse import urlsplit

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.launch.rosbridge import is_loopback
from colcon_wasm.server.bag_socket import BAG_PATH
from colcon_wasm.server.bag_socket import BagService
from colcon_wasm.server.bag_socket import FILES_PREFIX
from colcon_wasm.server.files import choose_body
from colcon_wasm.server.files import CompressionCache
from colcon_wasm.server.files import content_type
from colcon_wasm.server.files import Refused
from colcon_wasm.server.files import split_url_path
from colcon_wasm.server.launch_socket import LAUNCH_PATH
from colcon_wasm.server.launch_socket import LaunchService

logger = colcon_logger.getChild(__name__)

ISOLATION_HEADERS = {
    'Cross-Origin-Opener-Policy': 'same-origin',
    'Cross-Origin-Embedder-Policy': 'require-corp',
    'Cross-Origin-Resource-Policy': 'same-origin',
}


class ServeError(ColconWasmError):
    """The server cannot start; the message says why and what to do."""


def bind_error(error, host, port, *, other, fix, option='', permission_fix=None):
    """
    Say why a listener could not bind ``host:port`` and what to do.

    :param error: the OSError of the bind
    :param other: who may hold the port (e.g. 'another rosbridge server, or another server?')
    :param fix: the option to pass instead (e.g. '--rosbridge HOST:PORT (port 0 picks ...)')
    :param option: the option the listener belongs to, for the other errors
    :param permission_fix: what to do when a low port is refused (None: no special message)
    :returns: the :class:`ServeError` to raise
    """
    if error.errno == errno.EADDRINUSE:
        return ServeError(f'port {port} on {host} is already in use ({other}): stop it, or '
                          f'pass {fix}')
    if error.errno == errno.EACCES and permission_fix:
        return ServeError(f'no permission to listen on port {port} of {host}: '
                          f'{permission_fix}')
    what = f' for {option}' if option else ''
    return ServeError(f'cannot listen on {host}:{port}{what}: {error.strerror or error}')


class LauncherRequestHandler(BaseHTTPRequestHandler):
    """Serve the Site of the server: files, the page and workspace.json."""

    protocol_version = 'HTTP/1.1'
    server_version = 'colcon-wasm'
    sys_version = ''

    def setup(self):
        """Send small responses at once: no Nagle delay between headers and body."""
        super().setup()
        self.connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def _misdirected(self):
        """
        Refuse a request for another name than this loopback server's (DNS rebinding).

        :returns: True when the request was answered with 403
        """
        if not self.server.loopback_only:
            return False  # --host: reached by names this server cannot know
        host = self.headers.get('Host')
        if host is None:
            return False  # HTTP/1.0 clients; browsers always send Host
        try:
            name = urlsplit('//' + host.strip()).hostname
        except ValueError:
            name = None
        if name is not None and is_loopback(name):
            return False
        where = self.server.server_address[0]
        self._error(HTTPStatus.FORBIDDEN,
                    f'this colcon-wasm serve listens on {where} and answers requests for '
                    f'localhost, 127.0.0.1 and [::1] only, not for {host!r} (a guard against '
                    'DNS rebinding: a web page of another site must not reach it under a name '
                    f'of its own); open {self.server.url}, or pass --host to serve other names')
        self.close_connection = True
        return True

    def do_GET(self):  # noqa: N802 the name http.server calls
        """Answer a GET request."""
        if self._misdirected():
            return
        path = urlsplit(self.path).path
        relay = getattr(self.server, 'relay', None)
        if relay is not None and path == '/rosbridge':
            from colcon_wasm.server.relay_http import upgrade  # serve --rosbridge
            upgrade(self, relay, same_origin=True)
            return
        if path == BAG_PATH:
            from colcon_wasm.server.relay_http import upgrade  # the page's record and replay
            upgrade(self, self.server.bags, same_origin=True, path=BAG_PATH)
            return
        if path == LAUNCH_PATH:
            from colcon_wasm.server.relay_http import upgrade  # the page's launch files
            upgrade(self, self.server.launches, same_origin=True, path=LAUNCH_PATH)
            return
        if path.startswith(FILES_PREFIX):
            self._send_recording(path)
            return
        self._respond(send_body=True)

    def _send_recording(self, path):
        recording = self.server.bags.download(path)
        if recording is None:
            self._error(HTTPStatus.NOT_FOUND, 'no such recording (recordings last as long as '
                                              'the colcon-wasm serve that made them)')
            return
        size = recording.stat().st_size
        self.send_response(HTTPStatus.OK)
        self._common_headers()
        self.send_header('Content-Type', 'application/octet-stream')
        self.send_header('Content-Disposition', f'attachment; filename="{recording.name}"')
        self.send_header('Content-Length', str(size))
        self.end_headers()
        with open(recording, 'rb') as f:
            shutil.copyfileobj(f, self.wfile)

    def do_HEAD(self):  # noqa: N802
        """Answer a HEAD request."""
        if self._misdirected():
            return
        self._respond(send_body=False)

    def _method_not_allowed(self):
        self._error(HTTPStatus.METHOD_NOT_ALLOWED, 'only GET and HEAD are served',
                    extra={'Allow': 'GET, HEAD'})

    do_POST = do_PUT = do_DELETE = do_PATCH = do_OPTIONS = _method_not_allowed  # noqa: N815

    def _common_headers(self):
        for name, value in ISOLATION_HEADERS.items():
            self.send_header(name, value)
        self.send_header('X-Content-Type-Options', 'nosniff')
        self.send_header('Cache-Control', 'no-cache')

    def _error(self, status, reason, extra=None):
        body = f'{int(status)} {HTTPStatus(status).phrase}: {reason}\n'.encode()
        self.send_response(status)
        self._common_headers()
        self.send_header('Content-Type', 'text/plain; charset=utf-8')
        self.send_header('Content-Length', str(len(body)))
        for name, value in (extra or {}).items():
            self.send_header(name, value)
        self.end_headers()
        if self.command != 'HEAD':
            self.wfile.write(body)

    def _respond(self, send_body):
        site = self.server.site
        try:
            url = urlsplit(self.path)
            segments = split_url_path(url.path)
            content = site.route(segments, parse_qs(url.query),
                                 directory=url.path.endswith('/'))
        except Refused as e:
            self._error(e.status, e.reason)
            return
        except UnicodeDecodeError:
            self._error(HTTPStatus.BAD_REQUEST, 'the path is not valid UTF-8')
            return
        except Exception as e:  # noqa: B902 a broken template or manifest must not kill the server
            logger.error(f'Serving {self.path}: {e}')
            self._error(HTTPStatus.INTERNAL_SERVER_ERROR, str(e))
            return
        if content.body is not None:
            self._send(content.body, None, content.content_type, None, send_body)
            return
        try:
            body_path, body, encoding, stat = choose_body(
                content.path, self.headers.get('Accept-Encoding'), self.server.compression,
                precompressed=content.precompressed)
        except OSError as e:
            self._error(HTTPStatus.NOT_FOUND, f'cannot read: {e.strerror}')
            return
        suffix = '-' + encoding if encoding else ''
        etag = f'"{stat.st_mtime_ns:x}-{stat.st_size:x}{suffix}"'
        if self.headers.get('If-None-Match') == etag:
            self.send_response(HTTPStatus.NOT_MODIFIED)
            self._common_headers()
            self.send_header('ETag', etag)
            self.send_header('Content-Length', '0')
            self.end_headers()
            return
        self._send(body, body_path, content.content_type or content_type(content.path),
                   encoding, send_body, etag=etag)

    def _send(self, body, body_path, mime, encoding, send_body, etag=None):
        length = len(body) if body is not None else body_path.stat().st_size
        self.send_response(HTTPStatus.OK)
        self._common_headers()
        self.send_header('Content-Type', mime)
        self.send_header('Content-Length', str(length))
        self.send_header('Vary', 'Accept-Encoding')
        if encoding:
            self.send_header('Content-Encoding', encoding)
        if etag:
            self.send_header('ETag', etag)
        self.end_headers()
        if not send_body:
            return
        if body is not None:
            self.wfile.write(body)
        else:
            with open(body_path, 'rb') as f:
                shutil.copyfileobj(f, self.wfile, 1 << 20)

    def log_message(self, format, *args):  # noqa: A002 the signature of http.server
        """Log requests at debug level (errors stay visible in the page)."""
        logger.debug(f'{self.address_string()} - {format % args}')


class LauncherServer(ThreadingHTTPServer):
    """A threading HTTP server for one Site."""

    daemon_threads = True
    request_queue_size = 512
    allow_reuse_address = True
    #: the rosbridge relay of ``serve --rosbridge`` (relay.py), served at /rosbridge
    relay = None

    def __init__(self, site, host, port):
        """
        Bind to ``host:port`` (port 0 picks a free port).

        :raises ServeError: when the address is taken or cannot be bound
        """
        self.site = site
        #: bound to a loopback address: requests must name a loopback host (_misdirected)
        self.loopback_only = is_loopback(host)
        self.compression = CompressionCache()
        #: the page's record and replay (/bag), bag_socket.py
        self.bags = BagService(site.install_space)
        #: the page's launch files (/launch), launch_socket.py
        from colcon_wasm import resources
        self.launches = LaunchService(
            site.install_space, resources.path('packages') / 'wasm_js' / 'src' / 'python')
        if ':' in host:
            self.address_family = socket.AF_INET6
        try:
            super().__init__((host, port), LauncherRequestHandler)
        except OSError as e:
            raise bind_error(
                e, host, port, other='another colcon-wasm serve, or another server?',
                fix='--port N (--port 0 picks a free port)',
                permission_fix='use a port above 1023, e.g. --port 8000') from None

    @property
    def url(self):
        """Return the URL of the page."""
        host, port = self.server_address[:2]
        if ':' in host:
            host = f'[{host}]'
        return f'http://{host}:{port}/'

    def server_close(self):
        """Close the socket and remove the recordings and uploads of this serve."""
        super().server_close()
        self.launches.close()
        self.bags.close()

    def handle_error(self, request, client_address):
        """Log a failed connection without a traceback on the console."""
        logger.debug(f'connection from {client_address} failed', exc_info=True)
