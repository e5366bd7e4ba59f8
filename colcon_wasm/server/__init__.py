# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The HTTP server of ``colcon-wasm serve`` and what it serves."""

from pathlib import Path

from colcon_wasm.server.http import LauncherServer
from colcon_wasm.server.http import ServeError
from colcon_wasm.server.site import Site

__all__ = ['LauncherServer', 'ServeError', 'Site', 'find_runtime', 'make_server',
           'runtime_entry']

# The module that exports Runtime: docs/design.md names index.mjs, runtime.mjs is the module.
RUNTIME_ENTRIES = ('index.mjs', 'runtime.mjs')


def find_runtime(install_space, bundled_dir):
    """
    Find the wasm_js runtime to serve.

    The install space's ``share/wasm_js`` (the runtime the executables were
    built with) wins over the copy inside colcon-wasm.

    :returns: ``(directory holding index.mjs, description of its origin)``
    :raises ServeError: when neither has the runtime
    """
    candidates = []
    packages = install_space.packages()
    if 'wasm_js' in packages:
        share = packages['wasm_js'].share
        candidates += [(share, 'install space'), (share / 'src', 'install space')]
    candidates.append((Path(bundled_dir), 'colcon-wasm'))
    for directory, origin in candidates:
        if any((directory / entry).is_file() for entry in RUNTIME_ENTRIES):
            return directory, f'{origin} ({directory})'
    entries = "' or '".join(RUNTIME_ENTRIES)
    raise ServeError(
        'the wasm_js runtime was not found: neither the install space '
        f"'{install_space.base}' nor colcon-wasm has '{entries}'; rebuild with "
        "'colcon build --wasm' or reinstall colcon-wasm")


def runtime_entry(runtime_dir):
    """Return the file name of the runtime module in a runtime directory."""
    for entry in RUNTIME_ENTRIES:
        if (Path(runtime_dir) / entry).is_file():
            return entry
    return RUNTIME_ENTRIES[0]


def make_server(install_space, *, host, port, launcher_dir, runtime_dir, runtime_origin,
                page_modules_dir=None, bases=None):
    """
    Create (and bind) the server for an install space.

    :param bases: the install bases the page's programs see read-only, highest
      priority first (default: the install space's base and underlays)
    """
    site = Site(install_space, launcher_dir=launcher_dir, runtime_dir=runtime_dir,
                runtime_origin=runtime_origin, runtime_entry=runtime_entry(runtime_dir),
                page_modules_dir=page_modules_dir, bases=bases)
    return LauncherServer(site, host, port)
