# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm serve`."""

import ipaddress
import sys
import threading
import time

from colcon_wasm import resources
from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.rosbridge import parse_listen_address
from colcon_wasm.server import find_runtime
from colcon_wasm.server import make_server


def _is_loopback(host):
    if host == 'localhost':
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


class ServeCommand(CliExtensionPoint):
    """Serve the install space and the launcher page to run nodes in the browser."""

    def add_arguments(self, *, parser):  # noqa: D102
        parser.add_argument(
            '--install-base', default='install_wasm', metavar='DIR',
            help='The install space of colcon build --wasm (default: install_wasm)')
        parser.add_argument(
            '--host', default='127.0.0.1',
            help='The address to listen on (default: 127.0.0.1, this machine only)')
        parser.add_argument(
            '--port', type=int, default=8000,
            help='The port to listen on; 0 picks a free one (default: 8000)')
        parser.add_argument(
            '--rosbridge', nargs='?', const='127.0.0.1:9090', metavar='[HOST:]PORT',
            help='Relay the rosbridge v2 protocol between the pages (tabs share one graph) and '
                 'rosbridge clients (roslibjs, roslibpy) on HOST:PORT (default 127.0.0.1:9090; '
                 'port 0 picks a free one)')
        parser.add_argument(
            '--foxglove', nargs='?', const='127.0.0.1:8765', metavar='[HOST:]PORT',
            help='A Foxglove WebSocket server on the graph of the pages (through the relay at '
                 '/rosbridge) on HOST:PORT (default 127.0.0.1:8765; port 0 picks a free one)')
        parser.add_argument(
            '--foxglove-queue', type=int, default=10, metavar='N',
            help='Messages kept per Foxglove subscription while the client is behind '
                 '(default 10; older ones are dropped and counted)')
        parser.add_argument(
            '--pyodide', metavar='DIR',
            help='The npm package pyodide (its node_modules/pyodide folder) for Python nodes in '
                 'the page (default: $COLCON_WASM_PYODIDE, then the colcon-wasm cache)')
        parser.add_argument(
            '--rosbridge-token', metavar='TOKEN',
            help='rosbridge clients of the --rosbridge port must present TOKEN '
                 '(ws://HOST:PORT/?token=TOKEN)')
        parser.add_argument(
            '--rosbridge-max-message-bytes', type=int, default=16 << 20, metavar='N',
            help='The largest message a rosbridge client may send (default 16 MiB)')
        parser.add_argument(
            '--rosbridge-max-queued-bytes', type=int, default=64 << 20, metavar='N',
            help='Bytes waiting for one rosbridge client before it is cut off (default 64 MiB)')

    def main(self, *, args):  # noqa: D102
        install_space = InstallSpace(args.install_base)
        bundled = resources.path('packages') / 'wasm_js' / 'src'
        runtime_dir, runtime_origin = find_runtime(install_space, bundled)
        server = make_server(
            install_space, host=args.host, port=args.port,
            launcher_dir=resources.path('templates') / 'launcher',
            runtime_dir=runtime_dir, runtime_origin=runtime_origin,
            page_modules_dir=bundled)
        _python(args, server)
        relay_server = _relay(args, install_space, server) \
            if args.rosbridge or args.foxglove else None
        if not _is_loopback(args.host):
            print(f'colcon-wasm serve: warning: listening on {args.host}: other machines can '
                  'open the page, run your nodes, read the files of the install space and '
                  'start its launch files, which run programs on this machine (xacro, '
                  'ExecuteProcess)', file=sys.stderr)
        executables = install_space.executables()
        print(f'Serving {len(executables)} executable(s) of {install_space.base}')
        print(f'Runtime: {runtime_origin}')
        if relay_server is not None and args.rosbridge:
            threading.Thread(target=relay_server.serve_forever, daemon=True).start()
            print(f'rosbridge relay: {relay_server.url} (and /rosbridge for the pages)')
        threading.Thread(target=server.serve_forever, daemon=True).start()
        foxglove = _foxglove(args, install_space, server) if args.foxglove else None
        print(f'Open {server.url}  (Ctrl-C stops the server)', flush=True)
        try:
            while True:
                time.sleep(3600)
        except KeyboardInterrupt:
            print('\nStopped.')
        finally:
            if foxglove is not None:
                foxglove.server_close()
            if relay_server is not None:
                server.relay.close()
                relay_server.server_close()
            server.shutdown()
            server.server_close()
        return 0


def _python(args, server):
    """Serve Pyodide for the page's Python nodes, or tell the page why not."""
    from colcon_wasm.launch import LaunchError
    from colcon_wasm.launch.python_nodes import find_pyodide
    try:
        server.site.pyodide_dir = find_pyodide(args.pyodide)
        print(f'Python nodes: Pyodide from {server.site.pyodide_dir}')
    except LaunchError as e:
        server.site.pyodide_problem = str(e)
        if args.pyodide:
            raise


def _foxglove(args, install_space, server):
    """Start the Foxglove server of serve: a client of the relay at /rosbridge."""
    from colcon_wasm.server.foxglove_assets import Assets
    from colcon_wasm.server.foxglove_relay import FoxgloveRelayServer
    host, port = parse_listen_address(args.foxglove, option='--foxglove', default_port=8765)
    serve_host, serve_port = server.server_address[:2]
    if serve_host in ('0.0.0.0', '::'):
        serve_host = '127.0.0.1' if serve_host == '0.0.0.0' else '::1'
    serve_host = f'[{serve_host}]' if ':' in serve_host else serve_host
    foxglove = FoxgloveRelayServer(f'ws://{serve_host}:{serve_port}/rosbridge',
                                   install_space.ros2msg_schemas(), host, port,
                                   queue_messages=args.foxglove_queue,
                                   assets=Assets.of_install(install_space))
    threading.Thread(target=foxglove.serve_forever, daemon=True).start()
    if not _is_loopback(host):
        print(f'colcon-wasm serve: warning: the Foxglove server listens on {host}: other '
              "machines can see and drive the pages' nodes", file=sys.stderr)
    print(f'foxglove server: {foxglove.url} (the graph of the pages, through the relay)',
          flush=True)
    return foxglove


class _NoListener:
    """The relay without a --rosbridge port (serve --foxglove alone): nothing to close."""

    def server_close(self):
        """Close nothing."""


def _relay(args, install_space, server):
    """Start the rosbridge relay of the pages and, with --rosbridge, of its port."""
    import json
    from colcon_wasm.server.relay import Relay
    from colcon_wasm.server.relay_http import RelayServer
    host, port = parse_listen_address(args.rosbridge) if args.rosbridge else (None, None)
    types = []
    for path in install_space.type_description_files():
        try:
            types.append(json.loads(path.read_text(encoding='utf-8')))
        except (OSError, ValueError):
            pass
    relay = Relay(types=types, max_message_bytes=args.rosbridge_max_message_bytes,
                  max_queued_bytes=args.rosbridge_max_queued_bytes)
    server.relay = relay
    server.site.relay_path = '/rosbridge'
    if host is None:
        return _NoListener()
    relay_server = RelayServer(relay, host, port, token=args.rosbridge_token)
    if not _is_loopback(host):
        print(f'colcon-wasm serve: warning: the rosbridge relay listens on {host}: other '
              "machines can drive the pages' nodes", file=sys.stderr)
    return relay_server
