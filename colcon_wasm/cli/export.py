# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm export`."""

import sys

from colcon_wasm import resources
from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_space import InstallSpaceError


class ExportCommand(CliExtensionPoint):
    """Write the launcher page and the install space's nodes as a static site."""

    def add_arguments(self, *, parser):  # noqa: D102
        parser.add_argument(
            'target', metavar='DIR',
            help='The folder to write the site into (new, empty, or an earlier export)')
        parser.add_argument(
            '--install-base', default='install_wasm',
            help='The install space to export (default: install_wasm); its underlays come too')
        parser.add_argument(
            '--run', action='append', default=[], metavar='"PKG/EXE [ARGS]"',
            help='An executable the page starts when it opens, as ?run= does (repeatable)')
        parser.add_argument(
            '--launch', action='append', default=[], metavar='"PKG FILE [NAME:=VALUE ...]"',
            help='An XML or YAML launch file the page starts when it opens, planned now '
                 '(repeatable; a path works too, as for ros2 launch)')
        parser.add_argument('--title', help='The page title (default: the workspace name)')
        parser.add_argument(
            '--packages-select', nargs='+', default=[], metavar='PKG',
            help='Export only these packages (type descriptions of all stay, for the page)')
        parser.add_argument(
            '--packages-up-to', nargs='+', default=[], metavar='PKG',
            help='Export these packages and what they depend on (as they were built)')
        parser.add_argument(
            '--python', nargs='?', const='', default=None, metavar='PYODIDE_DIR',
            help='Copy Pyodide into the site, so that Python nodes and the console run '
                 '(the folder as serve --pyodide takes it; default: as serve finds it)')
        parser.add_argument(
            '--base-url', metavar='/PATH/',
            help='Where the site will live, for a host that serves it under a sub-path '
                 '(GitHub Pages: /REPOSITORY/); the page then also works opened without '
                 'its final slash')

    def main(self, *, args):  # noqa: D102
        from colcon_wasm.server import find_runtime
        from colcon_wasm.server import ServeError
        from colcon_wasm.server import Site
        from colcon_wasm.server import runtime_entry
        from colcon_wasm.server.export import export_site
        from colcon_wasm.launch import LaunchError
        from colcon_wasm.launch.python_nodes import find_pyodide
        from colcon_wasm.server.export import ExportError
        try:
            install_space = InstallSpace(args.install_base)
            bundled = resources.path('packages') / 'wasm_js' / 'src'
            runtime_dir, origin = find_runtime(install_space, bundled)
            site = Site(install_space, launcher_dir=resources.path('templates') / 'launcher',
                        runtime_dir=runtime_dir, runtime_origin=origin,
                        runtime_entry=runtime_entry(runtime_dir), page_modules_dir=bundled,
                        title=args.title)
            pyodide = None
            if args.python is not None:
                pyodide = find_pyodide(args.python or None)
            done = export_site(site, args.target, runs=args.run, base_url=args.base_url,
                               select=args.packages_select, up_to=args.packages_up_to,
                               pyodide=pyodide, launches=args.launch)
        except (ExportError, InstallSpaceError, ServeError, LaunchError) as e:
            print(f'colcon-wasm export: {e}', file=sys.stderr)
            return 1
        plain, gz, br = done.first_visit
        print(f'Exported {done.executables} executable(s) of '
              f'{install_space.base} into {args.target}: {done.files} files, '
              f'{done.bytes / 1e6:.1f} MB ({done.plain_bytes / 1e6:.1f} MB without the '
              '.gz and .br forms)')
        print(f'A first visit downloads {plain / 1e6:.2f} MB: {gz / 1e6:.2f} MB gzip, '
              f'{br / 1e6:.2f} MB brotli (the page, its modules, the types'
              f"{', the --run programs' if args.run else ''})")
        print(f'Serve the folder from any static host, e.g. python3 -m http.server -d '
              f'{args.target} 8000, and open http://localhost:8000/')
        return 0
