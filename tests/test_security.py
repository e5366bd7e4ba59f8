# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
What listens, and what it lets in: each claim of docs/security.md, against the real servers.

`colcon-wasm serve` of the demo build (with its rosbridge relay port and
Foxglove server) and `colcon-wasm launch` of the demo talker (with the
Node.js rosbridge and Foxglove servers) run once per module, on loopback,
every wait bounded. Requests are made with raw sockets, so that headers a
browser would send (Host, Origin) and frames a hostile peer would send can be
written as they are; a headless Chromium page of another origin tries the
listeners as a hostile web page would (tests/js/security_probe.mjs), and an
exported site's service worker is checked in it too.
"""

import argparse
import base64
import contextlib
import functools
import http.server
import io
import ipaddress
import json
import os
from pathlib import Path
import re
import socket
import struct
import subprocess
import sys
import threading
import time
import types

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from served_page import browser_skip_reason  # noqa: E402
from served_page import CHROMIUM  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
JS = REPO / 'tests' / 'js'
DOC = REPO / 'docs' / 'security.md'
TOKEN = 's3cret-token'
LIMIT = 4096  # --rosbridge-max-message-bytes of both fixtures
FOXGLOVE_URL = re.compile(r'foxglove server listening on (ws://\S+)')
EVIL = 'http://evil.example'


# ------------------------------------------------------------------ helpers

def _port(url):
    return int(url.rstrip('/').rsplit(':', 1)[1])


def listening_addresses(port):
    """
    Return the local addresses of the TCP sockets listening on ``port`` (/proc/net/tcp{,6}).

    This is the address the server bound, read from the kernel: ``127.0.0.1``
    (loopback only) or ``0.0.0.0`` (every interface).
    """
    found = set()
    for name in ('tcp', 'tcp6'):
        for line in Path('/proc/net', name).read_text().splitlines()[1:]:
            fields = line.split()
            address, port_hex = fields[1].split(':')
            if fields[3] == '0A' and int(port_hex, 16) == port:  # 0A: LISTEN
                found.add(_proc_address(address))
    return found


def _process_tree(pid):
    """Return ``pid`` and every process below it."""
    children = {}
    for stat_file in Path('/proc').glob('[0-9]*/stat'):
        try:
            fields = stat_file.read_text().rsplit(')', 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(stat_file.parent.name))
    tree, pending = [], [pid]
    while pending:
        current = pending.pop()
        tree.append(current)
        pending += children.get(current, [])
    return tree


def listeners_of(pid):
    """
    Return what the process tree of ``pid`` listens on: ``({(address, port)}, unix paths)``.

    Read from the kernel (/proc/PID/fd, /proc/net/tcp{,6}, /proc/net/unix):
    every listening socket, whoever opened it (a debugger's port too).
    """
    socket_ids = set()
    for process in _process_tree(pid):
        try:
            fds = os.listdir(f'/proc/{process}/fd')
        except OSError:
            continue
        for fd in fds:
            try:
                target = os.readlink(f'/proc/{process}/fd/{fd}')
            except OSError:
                continue
            if target.startswith('socket:['):
                socket_ids.add(target[len('socket:['):-1])
    tcp = set()
    for name in ('tcp', 'tcp6'):
        for line in Path('/proc/net', name).read_text().splitlines()[1:]:
            fields = line.split()
            if fields[3] == '0A' and fields[9] in socket_ids:
                address, port_hex = fields[1].split(':')
                tcp.add((_proc_address(address), int(port_hex, 16)))
    unix = set()
    for line in Path('/proc/net/unix').read_text().splitlines()[1:]:
        fields = line.split()
        if int(fields[3], 16) & 0x10000 and fields[6] in socket_ids:  # the listening flag
            unix.add(fields[7] if len(fields) > 7 else '(unnamed)')
    return tcp, unix


def _proc_address(text):
    raw = bytes.fromhex(text)
    # the kernel writes each 32-bit word in host (little endian) order
    raw = b''.join(raw[i:i + 4][::-1] for i in range(0, len(raw), 4))
    return str(ipaddress.ip_address(raw))


def non_loopback_address():
    """Return an IPv4 address of this machine that is not loopback, or None."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        try:
            s.connect(('192.0.2.254', 9))  # no packet is sent: it picks the outgoing address
            address = s.getsockname()[0]
        except OSError:
            return None
    return None if address.startswith('127.') else address


def assert_loopback_only(port):
    """Check that ``port`` is bound to 127.0.0.1: another address of the machine is refused."""
    assert listening_addresses(port) == {'127.0.0.1'}, listening_addresses(port)
    other = non_loopback_address()
    if other is not None:
        with pytest.raises(ConnectionRefusedError):
            socket.create_connection((other, port), timeout=5).close()


def _mask(payload, key):
    if key == b'\0\0\0\0' or not payload:
        return payload
    n = len(payload)
    mask = (key * (n // 4 + 1))[:n]
    return (int.from_bytes(payload, 'little') ^ int.from_bytes(mask, 'little')).to_bytes(
        n, 'little')


def client_frame(opcode, payload=b'', *, length=None, fin=True, key=None):
    """Return a masked client frame; ``length`` claims another length than the payload's."""
    n = len(payload) if length is None else length
    b0 = (0x80 if fin else 0) | opcode
    if n < 126:
        header = struct.pack('!BB', b0, 0x80 | n)
    elif n < 65536:
        header = struct.pack('!BBH', b0, 0x80 | 126, n)
    else:
        header = struct.pack('!BBQ', b0, 0x80 | 127, n)
    key = os.urandom(4) if key is None else key
    return header + key + _mask(payload, key)


def send_large(ws, opcode, n):
    """Send one masked frame of ``n`` zero bytes, a MiB at a time (a zero mask key)."""
    ws.sock.sendall(client_frame(opcode, b'', length=n, key=b'\0\0\0\0'))
    chunk = bytes(1 << 20)
    while n:
        ws.sock.sendall(chunk[:min(n, len(chunk))])
        n -= min(n, len(chunk))


class RawSocket:
    """One WebSocket (or refused upgrade) over a plain socket, every read bounded."""

    def __init__(self, port, path, headers=None, host=None):
        """Send the upgrade request with ``headers`` (Host: 127.0.0.1:PORT unless ``host``)."""
        self.sock = socket.create_connection(('127.0.0.1', port), timeout=15)
        key = base64.b64encode(os.urandom(16)).decode()
        lines = [f'GET {path} HTTP/1.1', f"Host: {f'127.0.0.1:{port}' if host is None else host}",
                 'Upgrade: websocket', 'Connection: Upgrade', f'Sec-WebSocket-Key: {key}',
                 'Sec-WebSocket-Version: 13']
        lines += [f'{k}: {v}' for k, v in (headers or {}).items()]
        self.sock.sendall(('\r\n'.join(lines) + '\r\n\r\n').encode())
        self.buffer = b''
        while b'\r\n\r\n' not in self.buffer:
            chunk = self.sock.recv(65536)
            if not chunk:
                break
            self.buffer += chunk
        head, _, self.buffer = self.buffer.partition(b'\r\n\r\n')
        status_line, *header_lines = head.decode('latin-1').split('\r\n')
        self.status = int(status_line.split()[1]) if status_line else 0
        self.headers = {k.strip().lower(): v.strip() for k, _, v in
                        (line.partition(':') for line in header_lines)}
        self.body = b''
        if self.status != 101:
            length = int(self.headers.get('content-length', '0'))
            while len(self.buffer) < length:
                chunk = self.sock.recv(65536)
                if not chunk:
                    break
                self.buffer += chunk
            self.body, self.buffer = self.buffer[:length], self.buffer[length:]

    def _exact(self, n, deadline):
        while len(self.buffer) < n:
            self.sock.settimeout(max(0.01, deadline - time.monotonic()))
            chunk = self.sock.recv(1 << 20)
            if not chunk:
                raise ConnectionError('closed')
            self.buffer += chunk
        data, self.buffer = self.buffer[:n], self.buffer[n:]
        return data

    def frame(self, timeout=10):
        """Read one server frame: ``(opcode, payload)``."""
        deadline = time.monotonic() + timeout
        b0, b1 = self._exact(2, deadline)
        n = b1 & 0x7F
        if n == 126:
            n, = struct.unpack('!H', self._exact(2, deadline))
        elif n == 127:
            n, = struct.unpack('!Q', self._exact(8, deadline))
        return b0 & 0x0F, self._exact(n, deadline)

    def close_code(self, timeout=10):
        """Read frames until a close frame; return its code."""
        deadline = time.monotonic() + timeout
        while True:
            opcode, payload = self.frame(max(0.1, deadline - time.monotonic()))
            if opcode == 0x8:
                return struct.unpack('!H', payload[:2])[0] if len(payload) >= 2 else None

    def send(self, data, opcode=None):
        """Send a text (str, JSON-encoded when not a str) or binary message."""
        if isinstance(data, bytes):
            self.sock.sendall(client_frame(opcode or 0x2, data))
            return
        text = data if isinstance(data, str) else json.dumps(data)
        self.sock.sendall(client_frame(opcode or 0x1, text.encode()))

    def json_until(self, predicate, timeout=20):
        """Read text messages until ``predicate(message)``; return that message."""
        deadline = time.monotonic() + timeout
        while True:
            opcode, payload = self.frame(max(0.1, deadline - time.monotonic()))
            if opcode == 0x1:
                message = json.loads(payload)
                if predicate(message):
                    return message
            elif opcode == 0x8:
                raise AssertionError(f'closed: {payload!r}')

    def close(self):
        """Close the socket."""
        self.sock.close()

    def __enter__(self):  # noqa: D105
        return self

    def __exit__(self, *exc):  # noqa: D105
        self.close()


def _http(port, path, host=None, headers=None, method='GET'):
    """One plain HTTP request with a Host header of our choice: ``(status, headers, body)``."""
    with socket.create_connection(('127.0.0.1', port), timeout=15) as sock:
        host = f'127.0.0.1:{port}' if host is None else host
        lines = [f'{method} {path} HTTP/1.1', f'Host: {host}', 'Connection: close']
        lines += [f'{k}: {v}' for k, v in (headers or {}).items()]
        sock.sendall(('\r\n'.join(lines) + '\r\n\r\n').encode())
        data = b''
        while True:
            chunk = sock.recv(1 << 20)
            if not chunk:
                break
            data += chunk
    head, _, body = data.partition(b'\r\n\r\n')
    status_line, *header_lines = head.decode('latin-1').split('\r\n')
    return (int(status_line.split()[1]),
            {k.strip().lower(): v.strip() for k, _, v in (h.partition(':') for h in header_lines)},
            body)


@contextlib.contextmanager
def static_site(folder):
    """Serve a folder with http.server on a free loopback port (no isolation headers)."""
    handler = functools.partial(_QuietHandler, directory=str(folder))
    server = http.server.ThreadingHTTPServer(('127.0.0.1', 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f'http://127.0.0.1:{server.server_address[1]}/'
    finally:
        server.shutdown()
        server.server_close()
        thread.join(10)


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):  # noqa: A002
        pass


def _probe(options):
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    completed = subprocess.run(
        ['node', str(JS / 'security_probe.mjs'), json.dumps(dict(options, chromium=CHROMIUM))],
        capture_output=True, text=True, timeout=240, cwd=str(JS))
    lines = completed.stdout.strip().splitlines()
    assert lines, completed.stderr[-3000:]
    result = json.loads(lines[-1])
    assert result['ok'], result.get('error', '') + completed.stderr[-2000:]
    return result


# ----------------------------------------------------------------- fixtures

@pytest.fixture(scope='module')
def install():
    """Build the demo workspace."""
    return demo_build.demo_install()


@pytest.fixture(scope='module')
def serve(install, tmp_path_factory):
    """`colcon-wasm serve` with its defaults, a relay port and a Foxglove server (bare ports)."""
    stderr = tmp_path_factory.mktemp('serve') / 'stderr.txt'
    process = subprocess.Popen(
        [str(demo_build.venv_tool('colcon-wasm')), 'serve', '--install-base', str(install),
         '--port', '0', '--rosbridge', '0', '--foxglove', '0',
         '--rosbridge-max-message-bytes', str(LIMIT)],
        stdout=subprocess.PIPE, stderr=stderr.open('w'), text=True)
    watchdog = threading.Timer(90, process.kill)  # a serve that never says 'Open' fails
    watchdog.start()
    info = types.SimpleNamespace(stderr=stderr, process=process)
    for line in process.stdout:
        if line.startswith('rosbridge relay: '):
            info.relay_url = line.split()[2]
        if line.startswith('foxglove server: '):
            info.foxglove_url = line.split()[2]
        if line.startswith('Open '):
            info.url = line.split()[1]
            break
    watchdog.cancel()
    assert getattr(info, 'url', None), f'serve did not start: {stderr.read_text()}'
    info.port = _port(info.url)
    info.relay_port = _port(info.relay_url)
    info.foxglove_port = _port(info.foxglove_url)
    try:
        yield info
    finally:
        process.terminate()
        process.wait(10)


@pytest.fixture(scope='module')
def launch(install):
    """`colcon-wasm launch` of the talker with a token-guarded rosbridge server and Foxglove."""
    with BackgroundLaunch(install, '--rosbridge', '0', '--rosbridge-token', TOKEN,
                          '--rosbridge-max-message-bytes', str(LIMIT), '--foxglove', '0',
                          'demo_nodes/talker', duration=240) as run:
        run.foxglove_url = run.wait_for(FOXGLOVE_URL, timeout=60).group(1)
        run.wait_for("Publishing: 'Hello World: 2'", timeout=60)
        yield run


# ---------------------------------------------------------- the inventory

PY_LISTENER = re.compile(r'\b(?:ThreadingHTTPServer|HTTPServer|TCPServer|UDPServer|'
                         r'UnixStreamServer|create_server|start_server)\b|\.listen\(\d*\)')
JS_LISTENER = re.compile(r'\bcreateServer\(|\bWebSocketServer\b|\bcreateSocket\(|'
                         r'\bserver\.listen\(')
KNOWN_LISTENERS = {
    'colcon_wasm/server/http.py', 'colcon_wasm/server/relay_http.py',
    'colcon_wasm/server/foxglove_relay.py', 'colcon_wasm/server/launch_socket.py',
    'packages/wasm_js/src/bridges/rosbridge/server.mjs',
    'packages/wasm_js/src/bridges/foxglove/server.mjs',
    'packages/wasm_js/src/bridges/common/listen.mjs',
    'packages/wasm_js/src/launch/process_server.mjs',
}


def test_every_listener_of_the_code_is_in_the_document():
    """Each file that opens a server socket is named in docs/security.md (and no other does)."""
    found = set()
    for root, pattern, suffixes in (('colcon_wasm', PY_LISTENER, ('.py',)),
                                    ('packages/wasm_js/src', PY_LISTENER, ('.py',)),
                                    ('packages/wasm_js/src', JS_LISTENER, ('.mjs', '.js')),
                                    ('templates', JS_LISTENER, ('.mjs', '.js'))):
        for path in (REPO / root).rglob('*'):
            if path.suffix in suffixes and path.is_file() and \
                    pattern.search(path.read_text(encoding='utf-8', errors='replace')):
                found.add(path.relative_to(REPO).as_posix())
    assert found == KNOWN_LISTENERS, found ^ KNOWN_LISTENERS
    text = DOC.read_text(encoding='utf-8')
    assert [f for f in sorted(found) if f'`{f}`' not in text] == []
    # the Zenoh gateway, the rosbridge client and the page open no listener: clients only
    assert not any('/zenoh/' in f or f.startswith('templates/') for f in found)


# -------------------------------------------------------------- serve: HTTP

def test_serve_binds_loopback_by_default(serve):
    """The page's port, the relay port and the Foxglove port: 127.0.0.1 only, no warning."""
    for url in (serve.url, serve.relay_url, serve.foxglove_url):
        assert '//127.0.0.1:' in url, url
    for port in (serve.port, serve.relay_port, serve.foxglove_port):
        assert_loopback_only(port)
    assert 'warning' not in serve.stderr.read_text()


def test_serve_opens_these_ports_and_no_other(serve):
    """Every socket serve listens on: the page's, the relay's, Foxglove's; no Unix socket."""
    tcp, unix = listeners_of(serve.process.pid)
    assert tcp == {('127.0.0.1', serve.port), ('127.0.0.1', serve.relay_port),
                   ('127.0.0.1', serve.foxglove_port)}, tcp
    assert unix == set(), unix


def test_serve_warns_when_it_listens_beyond_loopback(install, monkeypatch, capsys):
    """`--host 0.0.0.0`: the warning names what other machines could do (the bind is faked)."""
    from colcon_wasm.cli import serve as serve_command
    from colcon_wasm.server import make_server
    monkeypatch.setattr(serve_command, 'make_server',
                        lambda space, host, **kw: make_server(space, host='127.0.0.1', **kw))

    def interrupt(seconds):
        raise KeyboardInterrupt

    monkeypatch.setattr(serve_command, 'time', types.SimpleNamespace(sleep=interrupt))
    command = serve_command.ServeCommand()
    parser = argparse.ArgumentParser()
    command.add_arguments(parser=parser)
    for host, warned in (('0.0.0.0', True), ('127.0.0.1', False), ('::1', False)):
        args = parser.parse_args(['--install-base', str(install), '--host', host,
                                  '--port', '0'])
        assert command.main(args=args) == 0
        err = capsys.readouterr().err
        assert ('warning: listening on 0.0.0.0: other machines can open the page, run your '
                'nodes, read the files of the install space and start its launch files, '
                'which run programs on this machine') in err if warned else err == '', err


@pytest.mark.parametrize('host,allowed', [
    ('127.0.0.1:{port}', True), ('localhost:{port}', True), ('LOCALHOST:{port}', True),
    ('[::1]:{port}', True), ('127.0.0.2:{port}', True),
    ('evil.example:{port}', False), ('127.0.0.1.evil.example:{port}', False),
    ('localhost.evil.example', False), ('192.0.2.2:{port}', False), ('', False),
])
def test_serve_answers_only_requests_for_a_loopback_name(serve, host, allowed):
    """DNS rebinding: a request for another name than a loopback one is 403, saying why."""
    host = host.format(port=serve.port)
    for path in ('/', '/workspace.json', '/fs/0/'):
        status, headers, body = _http(serve.port, path, host=host)
        if allowed:
            assert status == 200, (host, path, status, body[:200])
            continue
        assert status == 403, (host, path, status)
        assert b'answers requests for localhost, 127.0.0.1 and [::1] only' in body, body
        assert b'DNS rebinding' in body and b'demo_nodes' not in body
        assert headers['cross-origin-resource-policy'] == 'same-origin'


def test_a_rebound_page_cannot_open_launch_or_bag(serve):
    """The rebinding form of an upgrade (Origin and Host both the attacker's name): 403."""
    name = f'evil.example:{serve.port}'
    for path in ('/launch', '/bag', '/rosbridge'):
        with RawSocket(serve.port, path, {'Origin': f'http://{name}'}, host=name) as ws:
            assert ws.status == 403, (path, ws.status)
            assert b'DNS rebinding' in ws.body


@pytest.mark.parametrize('path', ['/launch', '/bag', '/rosbridge'])
def test_serve_sockets_take_their_own_pages_only(serve, path):
    """A foreign or null Origin is refused (403); the page's own Origin, or none, gets in."""
    for origin in (EVIL, f'http://127.0.0.1:{serve.port + 1}', 'null'):
        with RawSocket(serve.port, path, {'Origin': origin}) as ws:
            assert ws.status == 403, (origin, ws.status)
            assert f'only the pages of this colcon-wasm serve may use {path}'.encode() in ws.body
    for host, headers in ((None, {'Origin': f'http://127.0.0.1:{serve.port}'}),
                          (f'localhost:{serve.port}',
                           {'Origin': f'http://localhost:{serve.port}'}),
                          (None, {})):
        with RawSocket(serve.port, path, headers, host=host) as ws:
            assert ws.status == 101, (headers, ws.status, ws.body)
            if path == '/rosbridge':
                ws.json_until(lambda m: m.get('op') == 'colcon_wasm_relay')
            else:
                ws.send({'op': 'no_such_op'})
                error = ws.json_until(lambda m: m.get('op') == 'error')
                assert "unknown op 'no_such_op'" in error['msg'], error


def test_serve_files_the_pages_can_read(serve, install):
    """Every file of the install bases under /fs/, share folders under /package/, nothing out."""
    package_xml = install / 'demo_nodes' / 'share' / 'demo_nodes' / 'package.xml'
    status, _, body = _http(serve.port, '/fs/0/demo_nodes/share/demo_nodes/package.xml')
    assert status == 200 and body == package_xml.read_bytes()
    status, _, body = _http(serve.port, '/package/demo_nodes/package.xml')
    assert status == 200 and body == package_xml.read_bytes()
    status, _, body = _http(serve.port, '/ws/demo_nodes/share/demo_nodes/package.xml')
    assert status == 404 and b'only files listed in the manifests' in body
    for path, expected in (('/fs/0/..%2f..%2fetc/passwd', 403), ('/fs/0/%2e%2e/', 403),
                           ('/package/demo_nodes/../../../etc/passwd', 403),
                           ('/fs/1/', 404), ('/launcher/index.html', 404),
                           ('/bag/files/0123456789012345/bag.mcap', 404), ('/etc/passwd', 404)):
        status, _, body = _http(serve.port, path)
        assert status == expected, (path, status, body[:200])
        assert b'root:' not in body


def test_serve_sends_no_cors_headers_to_other_origins(serve):
    """A cross-origin request gets the page's headers: CORP same-origin, no Access-Control-*."""
    status, headers, _ = _http(serve.port, '/workspace.json', headers={'Origin': EVIL})
    assert status == 200
    assert headers['cross-origin-resource-policy'] == 'same-origin'
    assert not [h for h in headers if h.startswith('access-control-')], headers
    status, headers, _ = _http(serve.port, '/workspace.json', method='OPTIONS',
                               headers={'Origin': EVIL, 'Access-Control-Request-Method': 'GET'})
    assert status == 405 and not [h for h in headers if h.startswith('access-control-')]


def test_serve_relay_drops_oversize_messages_and_goes_on(serve):
    """/rosbridge: a message over --rosbridge-max-message-bytes is a status; the next is served."""
    with RawSocket(serve.port, '/rosbridge') as ws:
        ws.json_until(lambda m: m.get('op') == 'colcon_wasm_relay')
        ws.send('{"op": "publish", "topic": "/x", "msg": {"data": "' + 'x' * LIMIT + '"}}')
        status = ws.json_until(lambda m: m.get('op') == 'status')
        assert f'larger than the limit of {LIMIT} bytes' in status['msg'], status
        ws.send({'op': 'call_service', 'service': '/rosapi/topics', 'id': 'after'})
        answer = ws.json_until(lambda m: m.get('op') == 'service_response')
        assert answer['id'] == 'after' and answer['result'] is True


@pytest.mark.parametrize('path,limit', [('/launch', 64 << 20), ('/bag', 256 << 20)])
def test_serve_skips_a_message_over_its_limit(serve, path, limit):
    """/launch 64 MiB, /bag 256 MiB: one byte more is read past and dropped; the rest is served."""
    with RawSocket(serve.port, path) as ws:
        assert ws.status == 101
        send_large(ws, 0x2, limit + 1)
        ws.send({'op': 'no_such_op'})
        error = ws.json_until(lambda m: m.get('op') == 'error', timeout=60)
        assert "unknown op 'no_such_op'" in error['msg']


@pytest.mark.parametrize('path', ['/launch', '/bag', '/rosbridge'])
def test_serve_closes_on_a_control_frame_over_125_bytes(serve, path):
    """A ping that claims 2^40 bytes is refused at its header (1002), not read."""
    with RawSocket(serve.port, path) as ws:
        assert ws.status == 101
        ws.sock.sendall(client_frame(0x9, b'', length=1 << 40))
        assert ws.close_code(timeout=10) == 1002
    assert _http(serve.port, '/workspace.json')[0] == 200  # the server goes on


def test_serve_relay_port_and_foxglove_take_any_origin(serve):
    """Not guarded: the relay port (without --rosbridge-token) and Foxglove let any page in."""
    with RawSocket(serve.relay_port, '/', {'Origin': EVIL}) as ws:
        assert ws.status == 101
        ws.json_until(lambda m: m.get('op') == 'colcon_wasm_relay')
    with RawSocket(serve.foxglove_port, '/', {'Origin': EVIL,
                                              'Sec-WebSocket-Protocol': 'foxglove.websocket.v1'}
                   ) as ws:
        assert ws.status == 101
        assert ws.json_until(lambda m: m.get('op') == 'serverInfo')['name']
        send_large(ws, 0x1, (64 << 20) + 1)  # over its 64 MiB: skipped, the connection stays
        ws.send('not JSON')
        status = ws.json_until(lambda m: m.get('op') == 'status', timeout=60)
        assert status['message'].startswith('malformed JSON'), status


# ------------------------------------------------------- launch: Node.js

def test_launch_bridges_bind_loopback_by_default(launch):
    """`--rosbridge 0` and `--foxglove 0` (bare ports) listen on 127.0.0.1 only."""
    for url in (launch.url, launch.foxglove_url):
        assert url.startswith('ws://127.0.0.1:'), url
        assert_loopback_only(_port(url))


def test_launch_opens_these_ports_and_no_other(launch):
    """The launch's processes (Python, the Node.js host) listen on the two bridge ports only."""
    tcp, unix = listeners_of(launch.process.pid)
    ports = {_port(launch.url), _port(launch.foxglove_url)}
    assert tcp == {('127.0.0.1', port) for port in ports}, tcp
    assert unix == set(), unix  # no inspector, no host socket (no Python launch file here)


def test_launch_warns_for_a_bridge_beyond_loopback():
    """A non-loopback --rosbridge or --foxglove host is named in a warning (no bind needed)."""
    from colcon_wasm.launch.foxglove import foxglove_plan
    from colcon_wasm.launch.rosbridge import bridge_plan

    def rosbridge(host, token=None):
        err = io.StringIO()
        bridge_plan(argparse.Namespace(rosbridge=host, rosbridge_token=token,
                                       rosbridge_capabilities=None, rosbridge_connect=None,
                                       rosbridge_max_message_bytes=None,
                                       rosbridge_max_queued_bytes=None), err=err)
        return err.getvalue()

    assert rosbridge('0.0.0.0:9090') == ('warning: --rosbridge listens on 0.0.0.0: other '
                                         'machines can drive your nodes (no --rosbridge-token)\n')
    assert 'no --rosbridge-token' not in rosbridge('0.0.0.0:9090', token='t')
    assert rosbridge('9090') == rosbridge('127.0.0.1:9090') == rosbridge('[::1]:9090') == ''
    err = io.StringIO()
    foxglove_plan(argparse.Namespace(foxglove='0.0.0.0:8765', foxglove_queue=None), err=err)
    assert 'the Foxglove protocol has no authentication' in err.getvalue()


def test_launch_rosbridge_token_and_origin(launch):
    """Without the token: 401 whatever the Origin; with it, any Origin (the token is the guard)."""
    port = _port(launch.url)
    for path, headers in (('/', {}), ('/', {'Origin': f'http://127.0.0.1:{port}'}),
                          ('/?token=wrong', {'Origin': EVIL}),
                          ('/', {'Authorization': 'Bearer wrong'})):
        with RawSocket(port, path, headers) as ws:
            assert ws.status == 401, (path, headers, ws.status)
            assert b'needs a token' in ws.body
    for path, headers in ((f'/?token={TOKEN}', {'Origin': EVIL}),
                          ('/', {'Authorization': f'Bearer {TOKEN}', 'Origin': 'null'})):
        with RawSocket(port, path, headers) as ws:
            assert ws.status == 101, (path, headers, ws.status)
            ws.send({'op': 'call_service', 'service': '/rosapi/topics', 'id': 'in'})
            assert ws.json_until(lambda m: m.get('op') == 'service_response')['result'] is True


def test_launch_rosbridge_drops_oversize_and_closes_on_big_control_frames(launch):
    """A message over the limit is a status error and the next is served; a big ping: 1002."""
    port = _port(launch.url)
    with RawSocket(port, f'/?token={TOKEN}') as ws:
        ws.send('{"op": "publish", "topic": "/x", "msg": {"data": "' + 'x' * LIMIT + '"}}')
        status = ws.json_until(lambda m: m.get('op') == 'status')
        assert f'larger than the limit of {LIMIT} bytes' in status['msg'], status
        ws.send({'op': 'call_service', 'service': '/rosapi/nodes', 'id': 'after'})
        answer = ws.json_until(lambda m: m.get('op') == 'service_response')
        assert answer['id'] == 'after' and '/talker' in answer['values']['nodes']
        ws.sock.sendall(client_frame(0x9, b'', length=1 << 40))
        assert ws.close_code() == 1002
    with RawSocket(port, f'/?token={TOKEN}') as ws:
        assert ws.status == 101  # the server goes on


def test_launch_foxglove_any_origin_and_its_bounds(launch):
    """Foxglove takes any Origin (its protocol has no authentication); 64 MiB and 125 B bounds."""
    port = _port(launch.foxglove_url)
    protocol = {'Sec-WebSocket-Protocol': 'foxglove.websocket.v1'}
    with RawSocket(port, '/', {'Origin': EVIL, **protocol}) as ws:
        assert ws.status == 101
        assert ws.json_until(lambda m: m.get('op') == 'serverInfo')
        ws.sock.sendall(client_frame(0x2, b'', length=(64 << 20) + 1))
        assert ws.close_code() == 1009  # refused at the header: nothing is buffered
    with RawSocket(port, '/', {'Origin': EVIL, **protocol}) as ws:
        ws.json_until(lambda m: m.get('op') == 'serverInfo')
        ws.sock.sendall(client_frame(0xA, b'', length=1 << 40))
        assert ws.close_code() == 1002
    with RawSocket(port, '/', {'Origin': EVIL}) as ws:
        assert ws.status == 400 and b'foxglove.websocket.v1' in ws.body


def test_launch_host_link_socket_is_in_a_private_folder(install, tmp_path):
    """The node shims' Unix socket lives in a folder only this user can enter (0700)."""
    from colcon_wasm.launch.install_space import InstallSpace
    from colcon_wasm.launch.python_launch import HostLaunch
    launch = HostLaunch(tmp_path / 'x.launch.py', {})
    launch.prepare({'types': []}, InstallSpace(install), None,
                   runtime_python=REPO / 'packages' / 'wasm_js' / 'src' / 'python',
                   ready_pipe=False)
    try:
        assert launch.folder.stat().st_mode & 0o7777 == 0o700
        assert Path(launch.prefix.config['socket']).parent == launch.folder
    finally:
        launch.cleanup()
    assert not launch.folder.exists()


# ------------------------------------------------------- a hostile web page

def test_a_page_of_another_origin(serve, launch, tmp_path):
    """In Chromium: what a page of another origin reaches of serve and of the launch."""
    (tmp_path / 'hostile.html').write_text('<!doctype html><title>elsewhere</title>')
    s = serve.url
    probes = [
        {'name': 'read workspace.json', 'kind': 'fetch', 'url': s + 'workspace.json'},
        {'name': 'no-cors workspace.json', 'kind': 'no-cors', 'url': s + 'workspace.json'},
        {'name': 'read a view', 'kind': 'fetch', 'url': s + 'fs/0/'},
        {'name': 'serve /launch', 'kind': 'ws', 'url': s.replace('http', 'ws') + 'launch'},
        {'name': 'serve /bag', 'kind': 'ws', 'url': s.replace('http', 'ws') + 'bag'},
        {'name': 'serve /rosbridge', 'kind': 'ws', 'url': s.replace('http', 'ws') + 'rosbridge'},
        {'name': 'relay port', 'kind': 'ws', 'url': serve.relay_url},
        {'name': 'serve foxglove', 'kind': 'ws', 'url': serve.foxglove_url,
         'protocols': ['foxglove.websocket.v1']},
        {'name': 'launch rosbridge', 'kind': 'ws', 'url': launch.url},
        {'name': 'launch foxglove', 'kind': 'ws', 'url': launch.foxglove_url,
         'protocols': ['foxglove.websocket.v1']},
    ]
    with static_site(tmp_path) as site:
        page = site.replace('127.0.0.1', 'localhost') + 'hostile.html'
        result = _probe({'mode': 'hostile', 'page': page, 'probes': probes})
    r = result['results']
    assert result['origin'].startswith('http://localhost:'), result
    for name in ('read workspace.json', 'read a view', 'serve /launch', 'serve /bag',
                 'serve /rosbridge', 'launch rosbridge'):
        assert r[name].startswith('refused'), (name, r)
    assert r['no-cors workspace.json'] == 'opaque' or r['no-cors workspace.json'].startswith(
        'refused'), r
    for name in ('relay port', 'serve foxglove', 'launch foxglove'):
        assert r[name] == 'open', (name, r)


# ----------------------------------------------- the exported site's worker

def test_the_service_worker_of_an_export(install, tmp_path):
    """Its scope is the site's folder; it caches the site's listed files only, by hash."""
    site = tmp_path / 'host' / 'demo'
    done = subprocess.run([str(demo_build.venv_tool('colcon-wasm')), 'export', str(site),
                           '--install-base', str(install), '--base-url', '/demo/'],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    (tmp_path / 'host' / 'outside.html').write_text('<!doctype html><title>outside</title>')
    (tmp_path / 'foreign').mkdir()
    (tmp_path / 'foreign' / 'data.txt').write_text('of another origin')
    hashes = {e['hash'] for e in
              json.loads((site / 'files.json').read_text())['files'].values()}
    with static_site(tmp_path / 'host') as host, static_site(tmp_path / 'foreign') as foreign:
        result = _probe({'mode': 'sw', 'site': host + 'demo/', 'outside': host + 'outside.html',
                         'foreign': foreign + 'data.txt'})
    scope = host + 'demo/'
    assert result['registration'] == {'scope': scope, 'script': scope + 'coi_sw.js'}, result
    assert result['after']['names'] == ['colcon-wasm-site:/demo/'], result['after']
    keys = result['after']['keys']['colcon-wasm-site:/demo/']
    assert keys, result
    for key in keys:
        assert key.startswith(scope + '.colcon-wasm-cache/'), key
        assert key[len(scope + '.colcon-wasm-cache/'):].split('/')[0] in hashes, key
    assert not [k for k in keys if k.startswith(foreign) or 'probe=' in k]
    assert result['fetches']['queried'] == 200
    assert result['outside'] == {'controlled': False, 'isolated': False}, result


# ---------------------------------------------------------- hostile files

def test_a_zstd_chunk_is_inflated_to_the_size_it_declares(tmp_path):
    """Not bounded: a small bag can hold a chunk that inflates ~1000-fold (docs/security.md)."""
    from colcon_wasm.record.bag_reader import read_messages
    from mcap.writer import CompressionType
    from mcap.writer import Writer
    path = tmp_path / 'bomb.mcap'
    size = 64 << 20
    with open(path, 'wb') as f:
        writer = Writer(f, compression=CompressionType.ZSTD, chunk_size=size * 2)
        writer.start(profile='ros2', library='test')
        schema = writer.register_schema('std_msgs/msg/String', 'ros2msg', b'string data')
        channel = writer.register_channel('/big', 'cdr', schema)
        writer.add_message(channel, log_time=1, data=bytes(size), publish_time=1)
        writer.finish()
    assert path.stat().st_size < 16 << 10  # 2.7 KB with zstd 1.5
    messages = list(read_messages(path, lambda topic: True))
    assert [len(m[3]) for m in messages] == [size]


def test_zenoh_peer_tokens():
    """Malformed tokens: counted, 32 named; valid ones of a peer: each held (no bound)."""
    completed = subprocess.run(['node', str(JS / 'security_zenoh.mjs')], capture_output=True,
                               text=True, timeout=60, cwd=str(JS))
    result = json.loads(completed.stdout.strip().splitlines()[-1])
    assert result['malformed'] == 500 and result['warnings'] == 32, result
    assert 'the next malformed tokens are counted, not named: 32 were' in result['lastWarning']
    assert result['otherDomain'] == 0  # another domain's and the gateway's own: not taken
    assert result['entities'] == 2000 and result['afterDeletes'] == 0
