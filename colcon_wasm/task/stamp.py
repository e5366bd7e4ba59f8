# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Skip a package whose last build is still up to date.

A no-op `colcon build` runs, for every package, a shell that sources all its
dependencies, `cmake --build`, `cmake --install` and the post-processing:
about a second per package, over a minute for the Humble core. After a
successful build the wasm task writes a *stamp* into the package's build
folder: a digest of everything the build read that colcon-wasm can see.

* the package's source files (path, size and modification time; a patched
  package: its original source and the patches);
* the CMake arguments (colcon-wasm's and the user's), the `--wasm*`
  settings, the Emscripten installation and the `EMCC_*`/`EM_*` variables;
* colcon-wasm's own build inputs (toolchain files, glue templates);
* the stamp digest of every dependency (so a rebuilt dependency rebuilds
  its dependents, transitively).

The next build skips the package when the digest is the same and what the
build installed is still there. Anything else (a changed file, a new
argument, `--cmake-force-configure`, a missing installed file) runs the
stock build as before. The stamp is removed before a build starts, so a
failed or interrupted build is never taken for an up-to-date one.
"""

import hashlib
import json
import os
from pathlib import Path
import sys

from colcon_core.logging import colcon_logger
from colcon_wasm import resources
from colcon_wasm.patch import source_fingerprint

logger = colcon_logger.getChild(__name__)

"""The stamp file in a package's build folder."""
STAMP_FILE = 'colcon_wasm_stamp.json'

STAMP_SCHEMA = 1

"""Options that ask for work even when nothing changed."""
FORCING_OPTIONS = ('cmake_force_configure', 'cmake_clean_cache',
                   'cmake_clean_first', 'cmake_target')

"""Options whose values are build inputs (all task kinds)."""
INPUT_OPTIONS = ('cmake_args', 'ament_cmake_args', 'catkin_cmake_args',
                 'symlink_install', 'merge_install', 'install_base',
                 'build_base', 'path')

"""Environment variables read by emcc (prefixes)."""
EMSCRIPTEN_ENVIRONMENT = ('EMCC_', 'EM_', 'EMMAKEN_')

"""colcon-wasm data that changes what a build produces."""
DATA_INPUTS = (('toolchains',), ('templates', 'glue'))

_data_digest = None


def data_digest():
    """Hash colcon-wasm's own build inputs (once per process)."""
    global _data_digest
    if _data_digest is None:
        digest = hashlib.sha256()
        folders = [resources.path(parts[0]).joinpath(*parts[1:])
                   for parts in DATA_INPUTS]
        package = Path(__file__).resolve().parents[1]
        files = [package / name for name in (
            'compile_launcher.py', 'postprocess.py', 'glue.py',
            'typedesc.py')]
        files += sorted((package / 'link').glob('*.py'))
        for folder in folders:
            files += sorted(p for p in folder.rglob('*') if p.is_file())
        for path in files:
            if path.is_file():
                digest.update(path.name.encode() + b'\0')
                digest.update(path.read_bytes())
        _data_digest = digest.hexdigest()
    return _data_digest


def stamp_path(build_base):
    """Get the stamp file of a package build folder."""
    return Path(build_base) / STAMP_FILE


def read_stamp(build_base):
    """Read a package's stamp (None when absent or unreadable)."""
    try:
        data = json.loads(stamp_path(build_base).read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get('schema') != STAMP_SCHEMA:
        return None
    return data


def dependency_digests(build_base, dependencies):
    """
    Get the stamp digest of each dependency (None: not stamped).

    :param build_base: this package's build folder (its siblings are the
      dependencies' build folders)
    :param dependencies: the dependency names
    """
    parent = Path(build_base).parent
    result = {}
    for name in sorted(dependencies):
        stamp = read_stamp(parent / name)
        result[name] = stamp.get('digest') if stamp else None
    return result


def build_inputs(*, args, source, patches, settings, dependencies):
    """
    Describe what a package build depends on.

    :param args: the package's colcon arguments
    :param pathlib.Path source: the package's own source folder
    :param patches: the patch files applied to it
    :param dict settings: the `--wasm*` settings and Emscripten
    :param dependencies: the dependency names
    :returns: a JSON-compatible dict
    """
    options = {}
    for name in INPUT_OPTIONS:
        value = getattr(args, name, None)
        options[name] = list(value) if isinstance(value, (list, tuple)) \
            else value
    return {
        'source': source_fingerprint(source, patches),
        'options': options,
        'settings': settings,
        'environment': sorted(
            (name, value) for name, value in os.environ.items()
            if name.startswith(EMSCRIPTEN_ENVIRONMENT)),
        'python': list(sys.version_info[:3]),
        'colcon_wasm': data_digest(),
        'dependencies': dependency_digests(args.build_base, dependencies),
    }


def digest_of(inputs):
    """Hash a build inputs description."""
    return hashlib.sha256(
        json.dumps(inputs, sort_keys=True).encode()).hexdigest()


def installed_files_present(build_base, install_prefix, pkg_name):
    """
    Check that what the last build installed is still there.

    :returns: the path of the first missing file, or None
    """
    required = [Path(install_prefix) / 'share' / 'colcon-core' / 'packages'
                / pkg_name]
    manifest = Path(build_base) / 'install_manifest.txt'
    if manifest.is_file():
        required += [Path(line) for line in manifest.read_text().splitlines()
                     if line.strip()]
    for path in required:
        if not os.path.lexists(path):
            return path
    return None


def is_up_to_date(args, pkg_name, inputs):
    """
    Check if a package's last build is up to date.

    :returns: (True, None) or (False, reason)
    """
    for name in FORCING_OPTIONS:
        if getattr(args, name, None):
            return False, f'--{name.replace("_", "-")} given'
    stamp = read_stamp(args.build_base)
    if stamp is None:
        return False, 'no stamp of an earlier build'
    if stamp.get('digest') != digest_of(inputs):
        changed = sorted(
            key for key in inputs
            if stamp.get('inputs', {}).get(key) != inputs[key])
        return False, 'changed: ' + ', '.join(changed or ['inputs'])
    missing = installed_files_present(
        args.build_base, args.install_base, pkg_name)
    if missing is not None:
        return False, f"'{missing}' is missing"
    return True, None


def remove_stamp(build_base):
    """Forget the last build (before building again)."""
    try:
        stamp_path(build_base).unlink()
    except FileNotFoundError:
        pass


def write_stamp(build_base, inputs):
    """Record a successful build."""
    path = stamp_path(build_base)
    path.parent.mkdir(parents=True, exist_ok=True)
    staging = path.with_name(path.name + '.tmp')
    staging.write_text(json.dumps({
        'schema': STAMP_SCHEMA, 'digest': digest_of(inputs),
        'inputs': inputs}, indent=1, sort_keys=True) + '\n')
    os.replace(staging, path)
