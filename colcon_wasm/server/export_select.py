# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The packages an export writes: ``--packages-select`` and ``--packages-up-to``.

As colcon's options of the same names: ``--packages-select`` takes the
packages named, ``--packages-up-to`` them and what they depend on, as the
install space records it (colcon's ``share/colcon-core/packages/<name>``,
the dependencies each package was built with). Without either, the export
writes every package, as the page under ``serve`` lists them.

A package left out has no executables in the page, no files under ``ws/``
and ``package/``, and no folder in the ``fs/`` views; a node that opens one
of its files gets ENOENT, and the page's log says which option would have
included it (``view_source_http.mjs``). Type descriptions are kept for
every package, so that the page shows every message its nodes send.
"""

from pathlib import Path

from colcon_wasm.error import ColconWasmError


class SelectionError(ColconWasmError):
    """A package selection that names a package the install space has not."""


def recorded_dependencies(package):
    """Return the dependencies colcon recorded for an installed package (names)."""
    path = Path(package.prefix) / 'share' / 'colcon-core' / 'packages' / package.name
    try:
        text = path.read_text(encoding='utf-8').strip()
    except OSError:
        return []
    return [name for name in text.split(':') if name] if text else []


def select_packages(install_space, select=(), up_to=()):
    """
    Return the names of the packages to export, or None for every package.

    :param select: ``--packages-select`` names
    :param up_to: ``--packages-up-to`` names (with their recorded dependencies)
    :raises SelectionError: for a name that is no package of the install space
      or its underlays, with the packages there are
    """
    if not select and not up_to:
        return None
    packages = install_space.packages()
    for option, names in (('--packages-select', select), ('--packages-up-to', up_to)):
        unknown = [name for name in names if name not in packages]
        if unknown:
            raise SelectionError(
                f"{option} {' '.join(unknown)}: no such package in the install space "
                f'{install_space.base} or its underlays; there are: '
                f"{', '.join(sorted(packages)) or 'none'}; nothing was written")
    chosen = set(select)
    pending = list(up_to)
    while pending:
        name = pending.pop()
        if name in chosen or name not in packages:
            continue  # a dependency without an install (a host tool, a system library)
        chosen.add(name)
        pending.extend(recorded_dependencies(packages[name]))
    return chosen


def left_out_prefixes(install_space, chosen):
    """
    Return ``{prefix: name}`` of the packages the export leaves out.

    Only isolated prefixes (``install_wasm/<name>``) can be left out; a
    merged install's packages share one prefix, and are written whole.
    """
    if chosen is None:
        return {}
    bases = {Path(install_space.base).resolve(),
             *(Path(u).resolve() for u in install_space.underlays)}
    left = {}
    for name, package in install_space.packages().items():
        if name not in chosen and Path(package.prefix).resolve() not in bases:
            left[str(Path(package.prefix).absolute())] = name  # as the programs see it
    return left
