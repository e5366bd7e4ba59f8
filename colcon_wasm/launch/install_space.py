# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""What an install space of ``colcon build --wasm`` holds, read from manifests.

``serve``, ``run`` and ``launch`` find executables only through the
per-package ``share/<pkg>/colcon_wasm/manifest.json`` (docs/design.md §5) and
type descriptions through ``share/<pkg>/colcon_wasm/types.json``.  Isolated
(``<base>/<pkg>/...``) and merged (``<base>/share/<pkg>``) layouts both work.
"""

import json
from pathlib import Path

MANIFEST_SCHEMA = 1


class InstallSpaceError(Exception):
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

    @property
    def label(self):
        """Return ``pkg/exe``."""
        return '{}/{}'.format(self.package.name, self.name)


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
                    "cannot read the manifest '{}': {}; rebuild '{}' with "
                    'colcon build --wasm'.format(self.manifest_path, e, self.name)) from e
            if data.get('schema') != MANIFEST_SCHEMA:
                raise InstallSpaceError(
                    "manifest '{}' has schema {!r}, this colcon-wasm reads schema {}; "
                    "rebuild '{}' with this colcon-wasm".format(
                        self.manifest_path, data.get('schema'), MANIFEST_SCHEMA, self.name))
            self._manifest = data
        return self._manifest

    def executables(self):
        """Return the package's Executables (none without a manifest)."""
        manifest = self.manifest
        if manifest is None:
            return []
        return [Executable(self, entry) for entry in manifest.get('executables', [])]


class InstallSpace:
    """The packages of one install base."""

    def __init__(self, base):
        """
        Open an install base.

        :raises InstallSpaceError: when the directory does not exist
        """
        self.base = Path(base).absolute()
        if not self.base.is_dir():
            raise InstallSpaceError(
                "no install space at '{}': run 'colcon build --wasm' in the workspace "
                'first, or pass --install-base DIR'.format(base))

    def packages(self):
        """Return ``{name: Package}``, scanned anew on each call (rebuilds show)."""
        found = {}
        merged_index = self.base / 'share' / 'colcon-core' / 'packages'
        if merged_index.is_dir():
            for marker in merged_index.iterdir():
                found[marker.name] = Package(marker.name, self.base)
        merged_share = self.base / 'share'
        if merged_share.is_dir():
            for manifest in merged_share.glob('*/colcon_wasm/manifest.json'):
                name = manifest.parent.parent.name
                found.setdefault(name, Package(name, self.base))
        for child in sorted(self.base.iterdir()):
            if child.name in found or not child.is_dir() or child.name == 'share':
                continue
            if (child / 'share' / child.name).is_dir():
                found[child.name] = Package(child.name, child)
        return dict(sorted(found.items()))

    def package(self, name):
        """Return a Package by name or raise an error listing what is there."""
        packages = self.packages()
        if name in packages:
            return packages[name]
        raise InstallSpaceError(
            "package '{}' is not in the install space '{}' (it has: {}); build it with "
            "'colcon build --wasm --packages-up-to {}'".format(
                name, self.base, ', '.join(packages) or 'no packages', name))

    def executable(self, package_name, name):
        """Return the Executable ``package_name/name`` or raise a clear error."""
        package = self.package(package_name)
        if package.manifest is None:
            raise InstallSpaceError(
                "package '{}' in '{}' has no colcon-wasm manifest ('{}'): it was not built "
                "with 'colcon build --wasm', or it installs no executables".format(
                    package_name, self.base, package.manifest_path))
        executables = package.executables()
        for executable in executables:
            if executable.name == name:
                if not executable.js.is_file():
                    raise InstallSpaceError(
                        "the manifest of '{}' lists '{}', but '{}' is missing; rebuild "
                        'the package'.format(package_name, name, executable.js))
                return executable
        raise InstallSpaceError(
            "package '{}' has no executable '{}' (it has: {})".format(
                package_name, name, ', '.join(e.name for e in executables) or 'none'))

    def executables(self):
        """Return every Executable of every manifest, by package."""
        return [e for p in self.packages().values() for e in p.executables()]

    def type_description_files(self):
        """Return the types.json files of all packages."""
        return [p.types_path for p in self.packages().values() if p.types_path.is_file()]

    def find_package_prefix(self, name):
        """Return the install prefix of a package (for find-pkg-share)."""
        return self.package(name).prefix
