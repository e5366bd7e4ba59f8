# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm serve`."""

import ipaddress
import sys

from colcon_wasm import resources
from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.server import find_runtime
from colcon_wasm.server import make_server
from colcon_wasm.server import ServeError


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

    def main(self, *, args):  # noqa: D102
        try:
            install_space = InstallSpace(args.install_base)
            bundled = resources.path('packages') / 'wasm_js' / 'src'
            runtime_dir, runtime_origin = find_runtime(install_space, bundled)
            server = make_server(
                install_space, host=args.host, port=args.port,
                launcher_dir=resources.path('templates') / 'launcher',
                runtime_dir=runtime_dir, runtime_origin=runtime_origin,
                page_modules_dir=bundled)
        except (InstallSpaceError, ServeError) as e:
            print('colcon-wasm serve: {}'.format(e), file=sys.stderr)
            return 1
        if not _is_loopback(args.host):
            print('colcon-wasm serve: warning: listening on {}: other machines can open the '
                  'page, run your nodes and read the files of the install space'.format(
                      args.host), file=sys.stderr)
        executables = install_space.executables()
        print('Serving {} executable(s) of {}'.format(len(executables), install_space.base))
        print('Runtime: {}'.format(runtime_origin))
        print('Open {}  (Ctrl-C stops the server)'.format(server.url), flush=True)
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            print('\nStopped.')
        finally:
            server.server_close()
        return 0
