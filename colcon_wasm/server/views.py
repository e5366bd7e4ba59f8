# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Read-only views of install bases over HTTP, for programs in the browser.

A program started by the page reads its install spaces through
``packages/wasm_js/src/view_source_http.mjs`` (synchronous XMLHttpRequest
from its worker).  Base ``n`` (highest priority first) is served under
``/fs/<n>/``:

==========================  ====================================================
``/fs/<n>/<path>/``         the directory's listing, JSON: ``{path, size,
                            mode, mtime_ms, entries: [{name, kind, size,
                            mode, mtime_ms}]}`` (``kind``: ``dir`` or ``file``;
                            symbolic links are followed)
``/fs/<n>/<path>/?walk=<k>``  the listings of the directories along the path,
                            from its ``k``-th (0: the base itself) down to the
                            last one that exists: ``{listings: {<relative
                            path>: listing}}``; one request where a lookup of
                            a deep path would list each directory
``/fs/<n>/<path>``          the file's bytes
==========================  ====================================================

A walk into a package's resource index (``<pkg>/share/ament_index/
resource_index/<type>`` in an isolated install) also walks the same path
in every other package of the base: ament_index_cpp, pluginlib and the
component manager read it in every prefix of ``AMENT_PREFIX_PATH``, so one
request answers what would be one per package.

Nothing outside the bases is served: ``..`` is refused before routing
(``files.split_url_path``), and a path whose real location (symbolic links
resolved) leaves its base is 404, as is anything missing; listings leave such
entries out, so a program sees the same tree it can read.
"""

import json
import os
from pathlib import Path
import stat

from colcon_wasm.launch.install_view import RESOURCE_INDEX
from colcon_wasm.server.files import Refused

URL_PREFIX = 'fs'
PERMISSION_BITS = 0o7777
RESOURCE_INDEX_PARTS = list(RESOURCE_INDEX.parts)


def _inside(root_real, real):
    return real == root_real or root_real in real.parents


class InstallViews:
    """The install bases the page's programs see, and their listings and files."""

    def __init__(self, bases):
        """
        Serve read-only views of ``bases`` (install base paths, highest priority first).

        :param bases: paths; their order is their number in ``/fs/<n>/``
        """
        self.bases = [Path(base).absolute() for base in bases]

    def mounts(self):
        """Describe the views for ``Runtime.spawn({mounts})``: ``[{path, url}]``."""
        return [{'path': str(base), 'url': f'/{URL_PREFIX}/{number}'}
                for number, base in enumerate(self.bases)]

    def content(self, number, segments, directory, walk=None):
        """
        Return ``(kind, value)`` for ``/fs/<number>/<segments>``.

        :param directory: the URL ended with ``/``: a listing was asked for
        :param walk: the ``walk`` query parameter (a number), or None
        :returns: ``('listing', bytes of JSON)`` or ``('file', real path)``
        :raises Refused: 404, saying what is missing
        """
        base = self._base(number)
        relative = '/'.join(segments)
        if walk is not None:
            return 'listing', json.dumps({'listings': self._walks(base, segments, walk)}).encode()
        real = self._resolve(base, segments)
        if directory:
            if not real.is_dir():
                raise Refused(404, f"'{relative}' in install base {number} is not a directory")
            return 'listing', json.dumps(self._listing(base, real, segments)).encode()
        if not real.is_file():
            raise Refused(404, f"'{relative or '.'}' in install base {number} is not a file (list "
                               'a directory with '
                               'a trailing slash)')
        return 'file', real

    def _base(self, number):
        if not number.isdigit() or int(number) >= len(self.bases):
            bases = ', '.join(f'/{URL_PREFIX}/{n}/ = {b}' for n, b in enumerate(self.bases))
            raise Refused(
                404, f'no install base {number!r}: this server has {len(self.bases)} ({bases})')
        return self.bases[int(number)]

    def _resolve(self, base, segments):
        """Return the real path of ``base/segments`` when it exists inside the base."""
        try:
            root_real = base.resolve(strict=True)
            real = root_real.joinpath(*segments).resolve(strict=True)
        except (OSError, RuntimeError):  # missing, not a directory on the way, link loops
            raise Refused(404, f"'{'/'.join(segments)}' is not in the install space "
                               f"'{base}'") from None
        if not _inside(root_real, real):
            raise Refused(404, f"'{'/'.join(segments)}' leads out of the install space '{base}' "
                               '(a symbolic link): '
                               'not served')
        return real

    def _walks(self, base, segments, walk):
        if not walk.isdigit():
            raise Refused(404, f'walk={walk!r}: give the number of leading directories to skip')
        listings = self._walk(base, segments, int(walk))
        if len(segments) > len(RESOURCE_INDEX_PARTS) and \
                segments[1:1 + len(RESOURCE_INDEX_PARTS)] == RESOURCE_INDEX_PARTS:
            index = segments[1:2 + len(RESOURCE_INDEX_PARTS)]  # share/.../resource_index/<type>
            for package in sorted(p.name for p in base.iterdir() if p.is_dir()):
                if package != segments[0]:
                    listings.update(self._walk(base, [package] + index, 1))
        return listings

    def _walk(self, base, segments, skip):
        """Return ``{relative path: listing}`` of the directories along a path, from ``skip``."""
        listings = {}
        try:
            root_real = base.resolve(strict=True)
        except (OSError, RuntimeError):
            return listings
        real = root_real
        for depth in range(len(segments) + 1):
            if depth:  # one step down, resolving only links (the path above is checked)
                real = real / segments[depth - 1]
                try:
                    if real.is_symlink():
                        real = real.resolve(strict=True)
                        if not _inside(root_real, real):
                            break
                    if not real.is_dir():
                        break
                except (OSError, RuntimeError):
                    break
            if depth >= skip:
                listings['/'.join(segments[:depth])] = self._listing(
                    base, real, segments[:depth], root_real)
        return listings

    def _listing(self, base, real, segments, root_real=None):
        """List a directory inside the base (``real``: its resolved path)."""
        root_real = root_real or base.resolve()
        entries = []
        with os.scandir(real) as scan:
            children = sorted(scan, key=lambda e: e.name)
        for child in children:
            try:
                if child.is_symlink():  # followed, when it stays inside the base
                    target = Path(child.path).resolve(strict=True)
                    if not _inside(root_real, target):
                        continue
                    info = target.stat()
                else:
                    info = child.stat(follow_symlinks=False)
            except (OSError, RuntimeError):
                continue  # dangling link, link loop, or removed meanwhile
            if stat.S_ISDIR(info.st_mode):
                kind = 'dir'
            elif stat.S_ISREG(info.st_mode):
                kind = 'file'
            else:
                continue
            entries.append({'name': child.name, 'kind': kind, 'size': info.st_size,
                            'mode': info.st_mode & PERMISSION_BITS,
                            'mtime_ms': info.st_mtime_ns // 1000000})
        info = real.stat()
        return {'path': str(base.joinpath(*segments)), 'size': info.st_size,
                'mode': info.st_mode & PERMISSION_BITS,
                'mtime_ms': info.st_mtime_ns // 1000000, 'entries': entries}
