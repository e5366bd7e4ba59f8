# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Debian source packages, fetched once and unpacked with Debian's patches.

A system library with no WebAssembly build (TinyXML 1 behind the rosdep
key `tinyxml`) is built from the source Debian builds its own package
from: `apt-get source --download-only` fetches the `.dsc` and its tarballs
(apt needs `deb-src` lines in its sources), and this module unpacks the
upstream tarball, the `debian/` folder and applies `debian/patches/series`,
as `dpkg-source -x` does. The result is kept in
`$COLCON_WASM_CACHE/debian-source/<package>-<version>/` and reused.
"""

import os
from pathlib import Path
import re
import shutil
import subprocess
import tarfile
import tempfile

from colcon_wasm.error import ColconWasmError
from colcon_wasm.patch import apply_patches
from colcon_wasm.patch import PatchError

"""Marker of a complete unpacked source (holds its Debian version)."""
COMPLETE = '.colcon_wasm_complete'

DEB_SRC_HINT = (
    "apt's sources have no 'deb-src' lines: add them (Debian bookworm: "
    "`echo 'deb-src http://deb.debian.org/debian bookworm main' > "
    '/etc/apt/sources.list.d/deb-src.list && apt-get update`), or put the '
    "library's source in the workspace")


class DebianSourceError(ColconWasmError):
    """A Debian source package that cannot be fetched or unpacked."""


def cache_root():
    """Get colcon-wasm's cache folder ($COLCON_WASM_CACHE, ~/.cache/colcon-wasm)."""
    return Path(os.environ.get(
        'COLCON_WASM_CACHE', Path.home() / '.cache' / 'colcon-wasm'))


def cached_source(package, version_prefix=None):
    """Get the newest unpacked source of a package in the cache, or None."""
    folder = cache_root() / 'debian-source'
    found = []
    for path in folder.glob(f'{package}-*'):
        marker = path / COMPLETE
        if marker.is_file():
            version = marker.read_text().strip()
            if version_prefix is None or version.startswith(version_prefix):
                found.append((path.stat().st_mtime, path))
    return max(found)[1] if found else None


def parse_dsc(path):
    """
    Read a `.dsc` file: {'Format', 'Version', 'Source', 'files': [...]}.

    :raises DebianSourceError: when it has no file list
    """
    fields = {}
    files = []
    current = None
    for line in Path(path).read_text(errors='replace').splitlines():
        if line.startswith('-----BEGIN PGP SIGNATURE'):
            break
        if line.startswith(' ') and current in ('Files', 'Checksums-Sha256'):
            parts = line.split()
            if len(parts) >= 3 and parts[-1] not in files:
                files.append(parts[-1])
            continue
        match = re.match(r'^([A-Za-z0-9-]+):\s*(.*)$', line)
        if match:
            current = match.group(1)
            fields[current] = match.group(2).strip()
    if not files:
        raise DebianSourceError(f"the Debian source description '{path}' lists no files")
    fields['files'] = files
    return fields


def _extract(archive, destination, *, strip):
    """Unpack a tarball, dropping its top folder when `strip` is set."""
    with tarfile.open(archive) as tar:
        members = tar.getmembers()
        for member in members:
            name = member.name.lstrip('./')
            if strip:
                name = name.split('/', 1)[1] if '/' in name else ''
            if not name:
                continue
            target = (destination / name).resolve()
            if destination.resolve() not in target.parents and \
                    target != destination.resolve():
                raise DebianSourceError(f"'{archive}' has a member outside its folder: "
                                        f'{member.name}')
            member.name = name
            tar.extract(member, destination)


def _apply_series(tree, package):
    """Apply `debian/patches/series` (quilt) in order."""
    series = tree / 'debian' / 'patches' / 'series'
    if not series.is_file():
        return []
    patches = []
    for line in series.read_text().splitlines():
        line = line.split('#', 1)[0].strip()
        if line:
            patches.append(tree / 'debian' / 'patches' / line.split()[0])
    try:
        apply_patches(tree, patches, package=package, strip=1)  # quilt: -p1
    except PatchError as e:
        raise DebianSourceError(
            f"Debian's patches of '{package}' do not apply: {e}") from e
    return patches


def fetch(package, *, version_prefix=None, apt_get='apt-get'):
    """
    Get the unpacked, patched source of a Debian source package.

    :param str package: the source (or binary) package name
    :param str version_prefix: refuse another upstream version
    :returns: the source folder (in the cache)
    :raises DebianSourceError: saying what failed and how to fix it
    """
    found = cached_source(package, version_prefix)
    if found is not None:
        return found
    folder = cache_root() / 'debian-source'
    folder.mkdir(parents=True, exist_ok=True)
    download = Path(tempfile.mkdtemp(prefix=f'.{package}-', dir=folder))
    try:
        try:
            completed = subprocess.run(
                [apt_get, 'source', '--download-only', package], cwd=download,
                capture_output=True, text=True, timeout=600)
        except FileNotFoundError as e:
            raise DebianSourceError(
                f"cannot fetch Debian's source package '{package}': there is no "
                f"'{apt_get}' (a Debian or Ubuntu host is needed), or put the library's "
                'source in the workspace') from e
        if completed.returncode != 0:
            text = (completed.stderr or completed.stdout).strip()
            hint = DEB_SRC_HINT if 'deb-src' in text else \
                'check the package name and the network, then try again'
            raise DebianSourceError(
                f'`apt-get source --download-only {package}` failed: '
                f'{text.splitlines()[-1] if text else completed.returncode}; {hint}')
        dscs = sorted(download.glob('*.dsc'))
        if not dscs:
            raise DebianSourceError(
                f"`apt-get source {package}` downloaded no .dsc file in '{download}'")
        dsc = parse_dsc(dscs[0])
        version = dsc.get('Version', '0')
        upstream = version.split(':')[-1].rsplit('-', 1)[0]
        if version_prefix and not upstream.startswith(version_prefix):
            raise DebianSourceError(
                f"Debian's '{package}' is version {version}, the recipe expects "
                f'{version_prefix}: update the recipe, or put the source in the workspace')
        tree = download / 'source'
        tree.mkdir()
        origs = [download / f for f in dsc['files'] if '.orig.tar.' in f and
                 '.orig-' not in f]
        debian = [download / f for f in dsc['files'] if '.debian.tar.' in f]
        native = [download / f for f in dsc['files'] if '.tar.' in f and
                  not origs and not debian]
        for archive in origs + native:
            _extract(archive, tree, strip=True)
        for archive in debian:
            _extract(archive, tree, strip=False)
        patches = _apply_series(tree, package)
        (tree / COMPLETE).write_text(version + '\n')
        (tree / 'COLCON_IGNORE').write_text('')
        destination = folder / f"{dsc.get('Source', package)}-{upstream}"
        if destination.exists():
            shutil.rmtree(destination)
        tree.rename(destination)
        (destination / '.colcon_wasm_debian_patches').write_text(
            ''.join(f'{p.name}\n' for p in patches))
        return destination
    finally:
        shutil.rmtree(download, ignore_errors=True)
