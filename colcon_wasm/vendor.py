# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The third-party JavaScript libraries the launcher page ships, pinned.

The page's 3D view uses three.js and urdf-loader from npm. They are not part
of the repository: the wheel's build (``setup.py``) downloads the pinned
tarballs from the npm registry, checks their sha512 integrity, and copies
the files the page imports into ``colcon_wasm/_data/vendor/<library>/``, so
that an installed colcon-wasm never fetches anything at run time. A source
checkout (an editable install, the tests) unpacks the same files into the
cache folder instead, on first use (:func:`vendor_dir`).

This module uses the standard library only (and colcon_wasm/error.py,
which does too): ``setup.py`` imports it from the source tree, before
colcon-wasm or its dependencies are installed.
"""

import base64
import hashlib
import io
import json
import os
from pathlib import Path
import shutil
import tarfile
import tempfile
import urllib.error
import urllib.request

from colcon_wasm.error import ColconWasmError

REGISTRY = 'https://registry.npmjs.org'

"""Per library: its npm version, the tarball's sha512 (npm's `integrity`),
and the files of the tarball (under `package/`) the page serves. Kept in
vendor_pins.json beside this file (package data of the wheel)."""
LIBRARIES = json.loads((Path(__file__).resolve().parent / 'vendor_pins.json').read_text())

# written last into a complete vendor folder: the pins it holds
COMPLETE = '.complete'


class VendorError(ColconWasmError):
    """A pinned library that could not be downloaded or does not match its pin."""


def pins():
    """Return the text that identifies the pinned set (written into COMPLETE)."""
    return ''.join(f"{name} {lib['version']} {lib['integrity']}\n"
                   for name, lib in sorted(LIBRARIES.items()))


def tarball_url(name):
    """Return the npm registry URL of a library's pinned tarball."""
    version = LIBRARIES[name]['version']
    return f'{REGISTRY}/{name}/-/{name.split("/")[-1]}-{version}.tgz'


def _download(name, cache):
    """Return a library's tarball bytes, from the cache or the registry, checked."""
    lib = LIBRARIES[name]
    algorithm, _, expected = lib['integrity'].partition('-')
    cached = cache / f"{name}-{lib['version']}.tgz" if cache else None
    if cached is not None and cached.is_file():
        data = cached.read_bytes()
    else:
        url = tarball_url(name)
        try:
            with urllib.request.urlopen(url, timeout=120) as response:
                data = response.read()
        except (urllib.error.URLError, OSError) as e:
            raise VendorError(
                f'the page library {name} {lib["version"]} could not be downloaded from {url}: '
                f'{e}. colcon-wasm ships it inside the wheel; building the wheel needs the npm '
                'registry once (or put the tarball into '
                f'{cache or "the cache folder"}).') from None
    digest = base64.b64encode(hashlib.new(algorithm, data).digest()).decode('ascii')
    if digest != expected:
        raise VendorError(
            f'the tarball of {name} {lib["version"]} does not match its pinned {algorithm} '
            f'(colcon_wasm/vendor.py): got {digest}. Delete {cached or "it"} and retry.')
    if cached is not None and not cached.is_file():
        cached.parent.mkdir(parents=True, exist_ok=True)
        cached.write_bytes(data)
    return data


def unpack(destination, cache=None):
    """
    Write every pinned library's files into ``destination/<library>/``.

    :param destination: the vendor folder (replaced if it exists)
    :param cache: a folder for the downloaded tarballs, or None
    :raises VendorError: naming the library and what to do
    """
    destination = Path(destination)
    scratch = Path(tempfile.mkdtemp(prefix='.vendor-', dir=destination.parent))
    try:
        for name, lib in LIBRARIES.items():
            data = _download(name, cache)
            with tarfile.open(fileobj=io.BytesIO(data), mode='r:gz') as archive:
                for relative in lib['files']:
                    try:
                        member = archive.getmember(f'package/{relative}')
                    except KeyError:
                        raise VendorError(
                            f'{name} {lib["version"]} has no file {relative} '
                            '(colcon_wasm/vendor.py lists it)') from None
                    target = scratch / name / relative
                    target.parent.mkdir(parents=True, exist_ok=True)
                    target.write_bytes(archive.extractfile(member).read())
        (scratch / COMPLETE).write_text(pins())
        if destination.exists():
            shutil.rmtree(destination)
        os.replace(scratch, destination)
    finally:
        if scratch.exists():
            shutil.rmtree(scratch, ignore_errors=True)


def _cache_root():
    return Path(os.environ.get('COLCON_WASM_CACHE', Path.home() / '.cache' / 'colcon-wasm'))


def vendor_dir():
    """
    Get the folder of the page's vendored libraries.

    An installed colcon-wasm has them in ``colcon_wasm/_data/vendor``. A
    source checkout unpacks them once into the cache folder, keyed by the
    pins.

    :raises VendorError: when a source checkout cannot get them
    """
    installed = Path(__file__).resolve().parent / '_data' / 'vendor'
    if (installed / COMPLETE).is_file():
        return installed
    key = hashlib.sha256(pins().encode()).hexdigest()[:16]
    folder = _cache_root() / f'vendor-{key}'
    if not (folder / COMPLETE).is_file():
        folder.parent.mkdir(parents=True, exist_ok=True)
        unpack(folder, cache=_cache_root() / 'npm-tarballs')
    return folder
