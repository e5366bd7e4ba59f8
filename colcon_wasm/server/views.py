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
``/fs/<n>/<path>``          the file's bytes
==========================  ====================================================

Nothing outside the bases is served: ``..`` is refused before routing
(``files.split_url_path``), and a path whose real location (symbolic links
resolved) leaves its base is 404, as is anything missing; listings leave such
entries out, so a program sees the same tree it can read.
"""

import json
from pathlib import Path
import stat

from colcon_wasm.server.files import Refused

URL_PREFIX = 'fs'
PERMISSION_BITS = 0o7777


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
        return [{'path': str(base), 'url': '/{}/{}'.format(URL_PREFIX, number)}
                for number, base in enumerate(self.bases)]

    def content(self, number, segments, directory):
        """
        Return ``(kind, value)`` for ``/fs/<number>/<segments>``.

        :param directory: the URL ended with ``/``: a listing was asked for
        :returns: ``('listing', bytes of JSON)`` or ``('file', real path)``
        :raises Refused: 404, saying what is missing
        """
        base = self._base(number)
        relative = '/'.join(segments)
        real = self._resolve(base, segments)
        if directory:
            if not real.is_dir():
                raise Refused(404, "'{}' in install base {} is not a directory".format(
                    relative, number))
            return 'listing', json.dumps(self._listing(base, real, segments)).encode()
        if not real.is_file():
            raise Refused(404, "'{}' in install base {} is not a file (list a directory with "
                               'a trailing slash)'.format(relative or '.', number))
        return 'file', real

    def _base(self, number):
        if not number.isdigit() or int(number) >= len(self.bases):
            raise Refused(404, 'no install base {!r}: this server has {} ({})'.format(
                number, len(self.bases), ', '.join(
                    '/{}/{}/ = {}'.format(URL_PREFIX, n, b) for n, b in enumerate(self.bases))))
        return self.bases[int(number)]

    def _resolve(self, base, segments):
        """Return the real path of ``base/segments`` when it exists inside the base."""
        try:
            root_real = base.resolve(strict=True)
            real = root_real.joinpath(*segments).resolve(strict=True)
        except (OSError, RuntimeError):  # missing, not a directory on the way, link loops
            raise Refused(404, "'{}' is not in the install space '{}'".format(
                '/'.join(segments), base)) from None
        if not _inside(root_real, real):
            raise Refused(404, "'{}' leads out of the install space '{}' (a symbolic link): "
                               'not served'.format('/'.join(segments), base))
        return real

    def _listing(self, base, real, segments):
        root_real = base.resolve()
        entries = []
        for child in sorted(real.iterdir(), key=lambda p: p.name):
            try:
                target = child.resolve(strict=True)
                info = target.stat()
            except (OSError, RuntimeError):
                continue  # dangling link, or removed meanwhile
            if not _inside(root_real, target):
                continue
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
