# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Link closures: what linking one library into an executable needs.

A plugin or component library is not linked by the executables that load
it: natively they `dlopen` it, and the dynamic loader brings its
dependencies. Statically, its archive and every archive it depends on must
be on the link line. CMake knows that list; colcon-wasm asks CMake for it
once, when the library's package is built, by linking a throw-away
executable against the library with the launcher in *capture* mode
(`colcon_wasm_capture_link_closure()` in toolchains/wasm-ros.cmake). The
launcher then writes the archives of that link line to
`share/<pkg>/colcon_wasm/closures/<stem>.json` instead of linking.

Archives inside an install base are stored relative to it, so closures
stay valid when an underlay is moved or downloaded elsewhere; the library's
own archive, still in the build folder at capture time, is stored where it
is installed.
"""

import json
import os

from colcon_wasm.error import ColconWasmError

CLOSURE_SCHEMA = 1

"""Folder of closure files inside a package's share folder."""
CLOSURES_FOLDER = os.path.join('colcon_wasm', 'closures')


class ClosureError(ColconWasmError):
    """A closure that is missing, unreadable or names a missing archive."""


def relative_entry(path, *, bases, build_dir, install_prefix):
    """
    Describe one archive of a captured link line.

    :param str path: the archive as CMake put it on the link line
    :param bases: install bases (current first, then underlays)
    :param str build_dir: the capturing package's build folder
    :param str install_prefix: the capturing package's install prefix
    :returns: {'base_path': ...} relative to an install base, or
      {'absolute': ...} for an archive outside every base
    """
    real = os.path.realpath(path)
    if build_dir and _is_under(real, os.path.realpath(build_dir)):
        # the package's own library: take the installed copy
        real = os.path.join(os.path.realpath(install_prefix), 'lib',
                            os.path.basename(real))
    for base in bases:
        base_real = os.path.realpath(base)
        if _is_under(real, base_real):
            return {'base_path': os.path.relpath(real, base_real)}
    return {'absolute': real}


def _is_under(path, folder):
    return path == folder or path.startswith(folder.rstrip(os.sep) + os.sep)


def write_closure(destination, *, library, package, entries, flags):
    """Write a closure file (atomically)."""
    os.makedirs(os.path.dirname(destination) or '.', exist_ok=True)
    staging = f'{destination}.{os.getpid()}'
    with open(staging, 'w') as handle:
        json.dump({'schema': CLOSURE_SCHEMA, 'library': library,
                   'package': package, 'archives': entries,
                   'link_flags': flags}, handle, indent=1)
        handle.write('\n')
    os.replace(staging, destination)


def closure_file(prefix, package, stem):
    """Get where a package installs the closure of the library `stem`."""
    return os.path.join(prefix, 'share', package, CLOSURES_FOLDER, stem + '.json')


def read_closure(path, bases):
    """
    Resolve a closure file to archive paths of this machine.

    :param str path: the closure file
    :param bases: the install chain of the link being made
    :returns: (archives, flags)
    :raises ClosureError: naming the closure and the archive that is missing
    """
    try:
        with open(path, encoding='utf-8') as handle:
            data = json.load(handle)
    except (OSError, ValueError) as e:
        raise ClosureError(f"cannot read the link closure '{path}': {e}") from e
    if data.get('schema') != CLOSURE_SCHEMA:
        raise ClosureError(
            f"the link closure '{path}' has schema {data.get('schema')!r}, this "
            f'colcon-wasm reads schema {CLOSURE_SCHEMA}: rebuild its package '
            f"('{data.get('package')}') with this colcon-wasm")
    archives = []
    for entry in data.get('archives', []):
        if 'absolute' in entry:
            candidates = [entry['absolute']]
        else:
            candidates = [os.path.join(b, entry['base_path']) for b in bases]
        found = next((c for c in candidates if os.path.isfile(c)), None)
        if found is None:
            raise ClosureError(
                f"library '{data.get('library')}' of package '{data.get('package')}' "
                f"needs '{entry.get('absolute') or entry.get('base_path')}', which is "
                'in none of the install bases ' + ', '.join(bases) +
                f" (closure '{path}'): build the package that installs it, or "
                "rebuild the library's package")
        archives.append(found)
    return archives, list(data.get('link_flags', []))
