# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Files for the HTTP server: safe URL paths, MIME types, compression."""

from collections import OrderedDict
import gzip
import os
from pathlib import Path
import threading
from urllib.parse import unquote

from colcon_wasm.error import ColconWasmError

MIME_TYPES = {
    '.wasm': 'application/wasm',
    '.js': 'text/javascript; charset=utf-8',
    '.mjs': 'text/javascript; charset=utf-8',
    '.json': 'application/json',
    '.map': 'application/json',
    '.html': 'text/html; charset=utf-8',
    '.css': 'text/css; charset=utf-8',
    '.svg': 'image/svg+xml',
    '.png': 'image/png',
    '.ico': 'image/x-icon',
    '.txt': 'text/plain; charset=utf-8',
    '.md': 'text/plain; charset=utf-8',
    '.yaml': 'text/plain; charset=utf-8',
    '.xml': 'text/plain; charset=utf-8',
}
COMPRESSIBLE = {'.wasm', '.js', '.mjs', '.json', '.map', '.html', '.css', '.svg', '.txt',
                '.md', '.yaml', '.xml'}
MIN_COMPRESS_BYTES = 1024


class Refused(ColconWasmError):
    """A request for a path that is not served; ``status`` says why."""

    def __init__(self, status, reason):
        """Record the HTTP status and a one-line reason for the response body."""
        super().__init__(reason)
        self.status = status
        self.reason = reason


def content_type(path):
    """Return the Content-Type of a file name."""
    return MIME_TYPES.get(Path(path).suffix.lower(), 'application/octet-stream')


def split_url_path(url_path):
    """
    Split a URL path into decoded segments, refusing traversal in any form.

    ``..`` and ``.`` segments, encoded slashes and backslashes, NUL and empty
    segments are refused (403), whether written plainly or percent-encoded.

    :returns: the list of segments (``[]`` for ``/``)
    :raises Refused: for a path that tries to leave its root
    """
    if not url_path.startswith('/'):
        raise Refused(400, 'the request path must start with /')
    raw_segments = url_path[1:].split('/')
    if raw_segments and raw_segments[-1] == '':
        raw_segments.pop()  # a trailing slash
    segments = []
    for raw in raw_segments:
        segment = unquote(raw, errors='strict') if '%' in raw else raw
        if segment in ('', '.', '..') or any(c in segment for c in '/\\\0'):
            raise Refused(403, f'path traversal refused: {url_path!r}')
        segments.append(segment)
    return segments


def resolve_under(root, segments):
    """
    Return the real path of ``root/segments`` if it is a file inside root.

    Symbolic links are followed, and refused when they lead out of the root.

    :raises Refused: 404 when there is no such file (directories included:
      there is no directory listing), 403 when it is outside the root
    """
    root_real = Path(root).resolve()
    candidate = root_real.joinpath(*segments)
    try:
        real = candidate.resolve(strict=True)
    except (FileNotFoundError, NotADirectoryError):
        raise Refused(404, 'not found') from None
    except (OSError, RuntimeError):  # symlink loops
        raise Refused(403, 'cannot resolve the path') from None
    if real != root_real and root_real not in real.parents:
        raise Refused(403, 'the path leads out of the served directory (a symbolic link?)')
    if not real.is_file():
        raise Refused(404, 'not found (directories are not listed)')
    return real


def accepted_encodings(header):
    """Return the content codings an Accept-Encoding header allows (q > 0)."""
    accepted = set()
    for item in (header or '').split(','):
        token, _, params = item.strip().partition(';')
        token = token.strip().lower()
        quality = 1.0
        params = params.strip()
        if params.startswith('q='):
            try:
                quality = float(params[2:])
            except ValueError:
                quality = 0.0
        if token and quality > 0:
            accepted.add(token)
    return accepted


class CompressionCache:
    """gzip bodies computed on the fly, kept for unchanged files (LRU by bytes)."""

    def __init__(self, limit_bytes=128 << 20):
        """Create an empty cache holding at most ``limit_bytes`` of gzip data."""
        self.limit = limit_bytes
        self.entries = OrderedDict()
        self.size = 0
        self.lock = threading.Lock()
        self.pending = {}

    def gzip(self, path, stat):
        """Return the gzip body of a file, compressing it once per version."""
        key = (str(path), stat.st_mtime_ns, stat.st_size)
        with self.lock:
            if key in self.entries:
                self.entries.move_to_end(key)
                return self.entries[key]
            event = self.pending.get(key)
            owner = event is None
            if owner:
                event = self.pending[key] = threading.Event()
        if not owner:  # another thread is compressing the same file
            event.wait()
            with self.lock:
                if key in self.entries:
                    return self.entries[key]
            return self.gzip(path, stat)
        try:
            body = gzip.compress(Path(path).read_bytes(), compresslevel=6, mtime=0)
            with self.lock:
                self.entries[key] = body
                self.size += len(body)
                while self.size > self.limit and len(self.entries) > 1:
                    _, old = self.entries.popitem(last=False)
                    self.size -= len(old)
            return body
        finally:
            with self.lock:
                self.pending.pop(key, None)
            event.set()


def choose_body(path, accept_encoding, cache, precompressed=True):
    """
    Pick the representation of a file for a request.

    Precompressed siblings (``file.br``, ``file.gz``, not older than the file)
    win unless ``precompressed`` is false; otherwise compressible files of at
    least 1 KiB are gzipped on the fly.

    :returns: ``(body_path_or_None, body_bytes_or_None, encoding_or_None, stat)``
      (exactly one of path and bytes is set)
    """
    stat = os.stat(path)
    encodings = accepted_encodings(accept_encoding)
    for encoding, suffix in (('br', '.br'), ('gzip', '.gz')) if precompressed else ():
        if encoding not in encodings:
            continue
        try:
            sibling = Path(str(path) + suffix).resolve(strict=True)
            sibling_stat = sibling.stat()
        except (OSError, RuntimeError):
            continue
        # a precompressed file must sit beside the file (no link out of the root)
        if sibling.parent == Path(path).parent and sibling.is_file() and \
                sibling_stat.st_mtime_ns >= stat.st_mtime_ns:
            return sibling, None, encoding, stat
    if 'gzip' in encodings and Path(path).suffix.lower() in COMPRESSIBLE and \
            stat.st_size >= MIN_COMPRESS_BYTES:
        return None, cache.gzip(path, stat), 'gzip', stat
    return path, None, None, stat
