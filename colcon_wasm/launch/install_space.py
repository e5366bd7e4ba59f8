# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""What an install space of ``colcon build --wasm`` holds, read from manifests.

An install space is an install base and the ``--wasm`` underlays it was
built on (highest priority first); a package is taken from the first base
that has it.

``serve``, ``run`` and ``launch`` find executables only through the
per-package ``share/<pkg>/colcon_wasm/manifest.json`` (docs/design.md §5) and
type descriptions through ``share/<pkg>/colcon_wasm/types.json``.  Isolated
(``<base>/<pkg>/...``) and merged (``<base>/share/<pkg>``) layouts both work.
"""

import json
import os
from pathlib import Path

from colcon_wasm.error import ColconWasmError

MANIFEST_SCHEMA = 1

"""The marker of an install base built with ``colcon build --wasm``."""
INSTALL_MARKER = '.colcon_wasm_install.json'

"""The variable that sourced ``setup.sh`` files of ``--wasm`` install bases set."""
PREFIX_PATH_VARIABLE = 'COLCON_WASM_PREFIX_PATH'


def _marker_underlays(base):
    """Get the underlays a base's marker names (none without a readable marker)."""
    marker = Path(base) / INSTALL_MARKER
    try:
        return json.loads(marker.read_text(encoding='utf-8')).get('underlays', [])
    except (OSError, ValueError):
        return []


def _default_underlays(base, environ):
    """
    Get the underlays of a base: its marker's, then COLCON_WASM_PREFIX_PATH.

    The underlays of those follow them (their markers, recursively), as a
    sourced setup.sh chains what its workspace was built on; bases built
    before markers listed the whole chain keep working.
    """
    underlays = list(_marker_underlays(base))
    underlays += [p for p in environ.get(PREFIX_PATH_VARIABLE, '').split(os.pathsep) if p]
    at = 0
    while at < len(underlays):
        for deeper in _marker_underlays(underlays[at]):
            if deeper not in underlays and Path(deeper) != Path(base):
                underlays.append(deeper)
        at += 1
    return underlays


def _scan_base(base):
    """Find the packages of one install base (merged or isolated layout)."""
    found = {}
    merged_index = base / 'share' / 'colcon-core' / 'packages'
    if merged_index.is_dir():
        for marker in merged_index.iterdir():
            found[marker.name] = Package(marker.name, base)
    merged_share = base / 'share'
    if merged_share.is_dir():
        for manifest in merged_share.glob('*/colcon_wasm/manifest.json'):
            name = manifest.parent.parent.name
            found.setdefault(name, Package(name, base))
    for child in sorted(base.iterdir()):
        if child.name in found or not child.is_dir() or child.name == 'share':
            continue
        if (child / 'share' / child.name).is_dir():
            found[child.name] = Package(child.name, child)
    return found


class InstallSpaceError(ColconWasmError):
    """An install space, package or executable that is not there or is broken."""


class Executable:
    """One executable of a manifest, with absolute paths."""

    def __init__(self, package, entry):
        """Wrap one ``executables[]`` entry of a package's manifest."""
        self.package = package
        self.name = entry['name']
        self.entry = entry
        self.js = package.prefix / entry['js']
        self.files = [dict(f, absolute=package.prefix / f['path'])
                      for f in entry.get('files', [])]
        self.uses_bus = bool(entry.get('uses_bus', True))
        self.pthread = bool(entry.get('pthread', False))
        # an entry point of a Python package: {'module', 'function'} (Pyodide runs it)
        self.python = entry.get('python')
        # a package may install executables for another one (colcon-wasm's
        # component containers are rclcpp_components' executables)
        self.package_name = entry.get('package') or package.name

    @property
    def label(self):
        """Return ``pkg/exe``."""
        return f'{self.package_name}/{self.name}'


class Package:
    """A package in the install space."""

    def __init__(self, name, prefix):
        """Remember the package's name and install prefix."""
        self.name = name
        self.prefix = Path(prefix)
        self.share = self.prefix / 'share' / name
        self.manifest_path = self.share / 'colcon_wasm' / 'manifest.json'
        self.types_path = self.share / 'colcon_wasm' / 'types.json'
        self._manifest = None

    @property
    def manifest(self):
        """Return the parsed manifest, or None when the package has none."""
        if self._manifest is None and self.manifest_path.is_file():
            try:
                data = json.loads(self.manifest_path.read_text(encoding='utf-8'))
            except (OSError, ValueError) as e:
                raise InstallSpaceError(
                    f"cannot read the manifest '{self.manifest_path}': {e}; rebuild '{self.name}' "
                    'with '
                    'colcon build --wasm') from e
            if data.get('schema') != MANIFEST_SCHEMA:
                raise InstallSpaceError(
                    f"manifest '{self.manifest_path}' has schema {data.get('schema')!r}, this "
                    f'colcon-wasm reads schema {MANIFEST_SCHEMA}; '
                    f"rebuild '{self.name}' with this colcon-wasm")
            self._manifest = data
        return self._manifest

    def python_path(self):
        """Return the folders of the package's Python modules (absolute; none for C++ packages)."""
        manifest = self.manifest
        if manifest is None or not isinstance(manifest.get('python'), dict):
            return []
        return [self.prefix / p for p in manifest['python'].get('path', [])]

    def executables(self):
        """Return the package's Executables (none without a manifest)."""
        manifest = self.manifest
        if manifest is None:
            return []
        return [Executable(self, entry) for entry in manifest.get('executables', [])]


class InstallSpace:
    """The packages of an install base and of the underlays it was built on."""

    def __init__(self, base, underlays=None, environ=None):
        """
        Open an install base and its underlays.

        The underlays are, highest priority first, the ones given, else the
        ones the base was built on (its ``--wasm`` marker) followed by the
        entries of ``COLCON_WASM_PREFIX_PATH``; those that do not exist (a
        moved underlay) are left out. A package in several bases is taken
        from the first, as ``AMENT_PREFIX_PATH`` orders prefixes.

        :raises InstallSpaceError: when the directory does not exist
        """
        self.base = Path(base).absolute()
        if not self.base.is_dir():
            raise InstallSpaceError(
                f"no install space at '{base}': run 'colcon build --wasm' in the workspace "
                'first, or pass --install-base DIR')
        if underlays is None:
            underlays = _default_underlays(self.base, os.environ if environ is None else environ)
        self.bases = [self.base]
        for underlay in underlays:
            underlay = Path(underlay).absolute()
            if underlay.is_dir() and underlay not in self.bases:
                self.bases.append(underlay)

    @property
    def underlays(self):
        """Return the underlays' install bases, highest priority first."""
        return self.bases[1:]

    def packages(self):
        """Return ``{name: Package}``, scanned anew on each call (rebuilds show)."""
        found = {}
        for base in reversed(self.bases):
            found.update(_scan_base(base))
        return dict(sorted(found.items()))

    def share_folders(self):
        """
        Return each package's share folder, as the ament index resolves ``package://``.

        :returns: ``{name: Path}``, packages without a share folder left out
        """
        return {name: package.share for name, package in self.packages().items()
                if package.share.is_dir()}

    def package(self, name):
        """Return a Package by name or raise an error listing what is there."""
        packages = self.packages()
        if name in packages:
            return packages[name]
        where = f"the install space '{self.base}'"
        if self.underlays:
            where += ' nor its underlays ' + ', '.join(
                f"'{u}'" for u in self.underlays)
        raise InstallSpaceError(
            f"package '{name}' is not in {where} ({'they have' if self.underlays else 'it has'}: "
            f"{', '.join(packages) or 'no packages'}); build it with "
            f"'colcon build --wasm --packages-up-to {name}'")

    def executable(self, package_name, name):
        """Return the Executable ``package_name/name`` or raise a clear error."""
        found = self._effective_executables()
        executable = found.get((package_name, name))
        if executable is not None:
            if not executable.js.is_file():
                raise InstallSpaceError(
                    f"the manifest of '{executable.package.name}' lists '{name}', but "
                    f"'{executable.js}' is missing; rebuild "
                    'the package')
            return executable
        package = self.package(package_name)
        if package.manifest is None and not any(p == package_name for p, _ in found):
            raise InstallSpaceError(
                f"package '{package_name}' in '{package.prefix}' has no colcon-wasm manifest "
                f"('{package.manifest_path}'): it was not built "
                "with 'colcon build --wasm', or it installs no executables")
        names = [n for p, n in found if p == package_name]
        raise InstallSpaceError(
            f"package '{package_name}' has no executable '{name}' (it has: "
            f"{', '.join(names) or 'none'})")

    def executables(self, skip=None):
        """
        Return every Executable, by package (what ``ros2 run`` would find).

        :param skip: a predicate on package names: packages for which it is
          false are left out (e.g. those whose manifest cannot be read)
        """
        found = self._effective_executables(skip)
        # by package; in a package, in the order of its manifest
        return sorted(found.values(), key=lambda e: e.package_name)

    def _effective_executables(self, keep=None):
        """
        Map ``(package, executable)`` to the Executable that runs.

        Bases are read lowest priority first, so an overlay's executable
        replaces an underlay's; in one base an executable a package installs
        for another one (``"package"`` in its manifest entry) replaces that
        package's own.
        """
        found = {}
        for base in reversed(self.bases):
            packages = _scan_base(base)
            own, provided = [], []
            for package in packages.values():
                if keep is not None and not keep(package.name):
                    continue
                for executable in package.executables():
                    (own if executable.package_name == package.name else provided).append(
                        executable)
            for executable in own + provided:
                found[(executable.package_name, executable.name)] = executable
        return found

    def python_path(self):
        """
        Return the module folders of every Python package, highest priority first.

        What ``PYTHONPATH`` holds after sourcing the install space natively: a
        Python node imports the modules of the other packages too.
        """
        folders = []
        for package in self.packages().values():
            try:
                folders += [f for f in package.python_path() if f not in folders]
            except InstallSpaceError:
                continue  # a broken manifest: its executables are refused when run
        return folders

    def type_description_files(self):
        """Return the types.json files of all packages."""
        return [p.types_path for p in self.packages().values() if p.types_path.is_file()]

    def ros2msg_schemas(self):
        """
        Get the complete definitions (rosbag2's ros2msg) of the install's types.

        :rtype: colcon_wasm.ros2msg.Ros2MsgSchemas
        """
        from colcon_wasm.ros2msg import Ros2MsgSchemas
        return Ros2MsgSchemas.from_files(self.type_description_files())

    def find_package_prefix(self, name):
        """Return the install prefix of a package (for find-pkg-share)."""
        return self.package(name).prefix
