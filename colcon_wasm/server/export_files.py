# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
An exported site's precompressed files and its manifest of hashes.

Static hosts differ: nginx (``gzip_static``, ``brotli_static``), many
a CDN send a ``.gz`` or ``.br`` beside a file when the browser accepts it;
GitHub Pages compresses by itself; ``python3 -m http.server`` and an S3
bucket send the bytes as they are. So beside every large compressible file
of the site the export writes ``FILE.gz`` and ``FILE.br`` (brotli, when the
``brotli`` module is installed: it is a dependency of colcon-wasm), and
``files.json``, the manifest: each file's size, a hash of its content, and
which compressed forms it has.

The site's service worker (``templates/launcher/coi_sw.js``) reads the
manifest. It fetches a file's ``.gz`` and inflates it in the browser
(``DecompressionStream``; browsers have no brotli there), and keeps each
file in its cache under its hash: a second visit fetches nothing that did
not change, on any host, and a new export replaces only what changed. The
same bytes at two paths (an executable under ``ws/`` and in the ``fs/``
view) are fetched once.
"""

import gzip
import hashlib
import json
from pathlib import Path

try:
    import brotli
except ImportError:  # a source checkout without its dependencies: .gz only, and said so
    brotli = None

MANIFEST = 'files.json'
"""The manifest of the site's files, at its root."""

MIN_SIZE = 1024
"""Smaller files are sent as they are: a request costs more than their bytes."""

COMPRESSIBLE = ('.wasm', '.js', '.mjs', '.json', '.html', '.css', '.svg', '.py', '.txt',
                '.yaml', '.yml', '.xml', '.urdf', '.xacro', '.rviz', '.dae', '.stl', '.obj',
                '.msg', '.srv', '.action', '.idl', '.map')
"""Suffixes worth compressing (images, archives and meshes in binary formats are not)."""

_WORTH = 0.9
"""A compressed form is written only when it is at most this fraction of the file."""


def _compressible(path):
    return path.suffix.lower() in COMPRESSIBLE and path.stat().st_size >= MIN_SIZE


def content_hash(data):
    """Return the short hash of a file's bytes that keys it in the browser's cache."""
    return hashlib.sha256(data).hexdigest()[:20]


def compress_site(root, first=()):
    """
    Write the compressed forms and the manifest of the site in ``root``.

    Run after every other file is written; ``files.json`` lists them all.

    :param first: the paths a first visit loads: their brotli form is the
      smallest brotli makes (quality 11, seconds per MB); the others' is quick
      (quality 5), as a large install has many executables a visit may never load

    :returns: the manifest (``{path: {size, hash, gz?, br?}}``, sizes in bytes)
    """
    root = Path(root)
    files = {}
    paths = sorted(p for p in root.rglob('*') if p.is_file() and p.name != MANIFEST)
    taken = set(paths)
    packed_by_hash = {}  # the same bytes at two paths (ws/ and fs/) are compressed once
    for path in paths:
        data = path.read_bytes()
        entry = {'size': len(data), 'hash': content_hash(data)}
        if _compressible(path):
            for suffix, compress in _COMPRESSORS:
                packed_path = path.with_name(path.name + suffix)
                if packed_path in taken:  # a file of the install space has that name
                    continue
                best = path.relative_to(root).as_posix() in first
                key = (entry['hash'], suffix, best)
                if key not in packed_by_hash:
                    packed = compress(data, best)
                    packed_by_hash[key] = packed if len(packed) <= _WORTH * len(data) else None
                packed = packed_by_hash[key]
                if packed is not None:
                    packed_path.write_bytes(packed)
                    entry[suffix[1:]] = len(packed)
        files[path.relative_to(root).as_posix()] = entry
    (root / MANIFEST).write_text(json.dumps(
        {'version': 1, 'brotli': brotli is not None, 'files': files}, sort_keys=True))
    return files


def _gzip(data, best):
    return gzip.compress(data, compresslevel=9, mtime=0)


def _brotli(data, best):
    return brotli.compress(data, quality=11 if best else 5)


_COMPRESSORS = [('.gz', _gzip)] + ([('.br', _brotli)] if brotli is not None else [])


def download_sizes(files, paths):
    """
    Return the bytes a browser downloads for ``paths``: ``(plain, gzip, brotli)``.

    Each file counts with its smallest form of each kind; a file without one
    counts whole. Paths not in the site are left out.
    """
    plain = gz = br = 0
    for path in paths:
        entry = files.get(path)
        if entry is None:
            continue
        plain += entry['size']
        gz += entry.get('gz', entry['size'])
        br += entry.get('br', entry.get('gz', entry['size']))
    return plain, gz, br


def site_size(root):
    """Return ``(files, bytes)`` of everything in the site folder, compressed forms too."""
    paths = [p for p in Path(root).rglob('*') if p.is_file()]
    return len(paths), sum(p.stat().st_size for p in paths)
