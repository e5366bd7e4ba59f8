# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A bag's written pages are let go of behind its writer (colcon_wasm/record/page_cache.py).

The page cache is read with mincore(2) on a private mapping of the file:
the pages it reports resident are the file's pages in the cache. A file
written the same way without WrittenPages keeps every page (the check of
the measure), the one written with it keeps about the last step and lag
(once the rest is on the disk), and its bytes read back whole.
"""

import ctypes
import hashlib
import mmap
import os

from colcon_wasm.record.page_cache import WrittenPages
import pytest

MIB = 1024 * 1024


def _file_system(path):
    """Return the type of the file system `path` is on (/proc/mounts, longest mount point)."""
    best, kind = '', None
    with open('/proc/mounts', encoding='utf-8') as mounts:
        for line in mounts:
            fields = line.split()
            point = fields[1].encode().decode('unicode_escape')
            if str(path).startswith(point.rstrip('/') + '/') and len(point) > len(best):
                best, kind = point, fields[2]
    return kind


def _resident_bytes(path):
    size = os.path.getsize(path)
    libc = ctypes.CDLL(None, use_errno=True)
    libc.mincore.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p]
    with open(path, 'rb') as f:
        m = mmap.mmap(f.fileno(), size, access=mmap.ACCESS_COPY)
    try:
        pages = (size + mmap.PAGESIZE - 1) // mmap.PAGESIZE
        vec = (ctypes.c_ubyte * pages)()
        start = ctypes.c_char.from_buffer(m)
        try:
            assert libc.mincore(ctypes.addressof(start), size, vec) == 0, ctypes.get_errno()
        finally:
            del start
        return sum(b & 1 for b in vec) * mmap.PAGESIZE
    finally:
        m.close()


def _write(path, megabytes, advised):
    """
    Write `megabytes` MiB of numbered blocks into a new file; return their SHA-256.

    The first 64 MiB are on the disk (fdatasync) before the rest is written.
    With `advised`, WrittenPages (16 MiB steps and lag) follows the writes.
    """
    digest = hashlib.sha256()
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    pages = WrittenPages(fd, step=16 * MIB, lag=16 * MIB) if advised else None
    try:
        for i in range(megabytes):
            block = i.to_bytes(4, 'little') * (MIB // 4)
            digest.update(block)
            os.write(fd, block)
            if i == 63:
                os.fdatasync(fd)  # the first 64 MiB on the disk: their pages may go
            if pages is not None:
                pages.wrote_up_to((i + 1) * MIB)
    finally:
        os.close(fd)
    return digest.hexdigest()


def test_written_pages_are_let_go_of_and_nothing_is_lost(tmp_path):
    if _file_system(tmp_path) in ('tmpfs', 'ramfs'):
        pytest.skip(f'{tmp_path} is in memory (tmpfs): its pages cannot be let go of; '
                    'run with --basetemp on a disk')
    kept = tmp_path / 'kept.bin'
    _write(kept, 80, advised=False)
    # the measure sees a file's pages: written without advice, they all stay
    assert _resident_bytes(kept) >= 79 * MIB

    let_go = tmp_path / 'let_go.bin'
    digest = _write(let_go, 80, advised=True)
    # the call at 80 MiB dropped [.., 64 MiB): what stays is the last 16 MiB
    assert _resident_bytes(let_go) <= 17 * MIB
    with open(let_go, 'rb') as f:
        assert hashlib.sha256(f.read()).hexdigest() == digest


def test_a_file_without_page_cache_advice_is_left_alone(tmp_path):
    read, write = os.pipe()
    try:
        pages = WrittenPages(write, step=1, lag=0)
        pages.wrote_up_to(10)  # ESPIPE: no advice on a pipe
        assert not pages._on
        pages.wrote_up_to(20)  # and no second try
    finally:
        os.close(read)
        os.close(write)
