# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Post-process a package after CMake installed it.

For every executable CMake installed as `<exe>.js`:

1. put `<exe>.wasm` (and `<exe>.worker.js`, `<exe>.wasm.map` when the build
   made them) beside the installed `.js` -- CMake installs only the `.js`;
2. inject the glue fragments of `templates/glue/` into the `.js` and
   `.worker.js` (see :mod:`colcon_wasm.glue`);
3. write `share/<pkg>/colcon_wasm/manifest.json` (docs/design.md section 5);
4. write the type descriptions (:mod:`colcon_wasm.typedesc`).
"""

import gzip
import hashlib
import json
import os
from pathlib import Path
import shutil

from colcon_core.logging import colcon_logger
from colcon_wasm import glue
from colcon_wasm import typedesc
from colcon_wasm.error import ColconWasmError

logger = colcon_logger.getChild(__name__)

MANIFEST_SCHEMA = 1

"""Files beside `<exe>.js` that belong to the executable, with roles."""
COMPANIONS = (('.wasm', 'wasm'), ('.worker.js', 'worker'),
              ('.wasm.map', 'map'))

"""Text in the glue the build made when an executable links the bus library."""
BUS_MARKER = 'wasmBus'

"""Suffix of the link launcher's report beside a linked `.js`."""
LINK_REPORT_SUFFIX = '.colcon_wasm_link.json'


def read_link_report(build_js):
    """
    Read what the link launcher linked into an executable.

    :returns: the report's plugins, components and registered classes, or
      None for an executable linked without the launcher
    """
    path = Path(str(build_js) + LINK_REPORT_SUFFIX)
    try:
        report = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return {key: report.get(key, []) for key in (
        'plugins', 'components', 'registrations', 'plugin_base_classes')}


def provided_package(installed_js, prefix, pkg_name):
    """
    Get the package an executable is installed for.

    `lib/<pkg>/<exe>.js` names its package; a package may install
    executables for another one (colcon-wasm's component containers install
    `lib/rclcpp_components/component_container.js`). None: its own.
    """
    parts = installed_js.relative_to(prefix).parts
    if len(parts) == 3 and parts[0] == 'lib' and parts[1] != pkg_name:
        return parts[1]
    return None


class Executable:
    """An installed executable: its `.js` and the build's companions."""

    def __init__(self, name, installed_js, build_js):
        """
        Pair an installed `.js` with the `.js` the build made.

        :param str name: the executable name (file name without `.js`)
        :param pathlib.Path installed_js: the `.js` in the install prefix
        :param pathlib.Path build_js: the `.js` in the build folder
        """
        self.name = name
        self.installed_js = installed_js
        self.build_js = build_js

    def companion(self, folder, suffix):
        """Get the path of a companion file in a folder."""
        return folder / (self.name + suffix)


def read_install_manifest(build_base):
    """
    List what CMake installed for a package.

    :param pathlib.Path build_base: the package's build folder
    :returns: absolute paths (empty when there is no install manifest)
    """
    manifest = Path(build_base) / 'install_manifest.txt'
    if not manifest.is_file():
        return []
    return [Path(line) for line in manifest.read_text().splitlines()
            if line.strip()]


def _build_glue_files(build_base):
    """Map executable name to the `.js` files in the build folder."""
    result = {}
    for root, dirs, files in os.walk(build_base):
        dirs[:] = [d for d in dirs
                   if d not in ('CMakeFiles', 'colcon_wasm_source')]
        for name in files:
            if name.endswith('.wasm'):
                stem = name[:-len('.wasm')]
                js = Path(root, stem + '.js')
                if js.is_file():
                    result.setdefault(stem, []).append(js)
    return result


def find_executables(build_base, installed_files):
    """
    Find the installed executables of a package.

    An installed `<exe>.js` is an executable when the build folder holds an
    `<exe>.js` with an `<exe>.wasm` beside it.

    :returns: list of :class:`Executable`
    """
    build_glue = _build_glue_files(build_base)
    executables = []
    for installed in installed_files:
        name = installed.name
        if not name.endswith('.js') or name.endswith('.worker.js'):
            continue
        stem = name[:-len('.js')]
        candidates = build_glue.get(stem)
        if not candidates:
            continue
        build_js = candidates[0]
        if len(candidates) > 1:
            wanted = glue.strip_injections(installed.read_text())
            build_js = next(
                (c for c in candidates if c.read_text() == wanted),
                candidates[0])
        executables.append(Executable(stem, installed, build_js))
    return executables


def _copy_if_changed(source, destination):
    if destination.is_file():
        s_stat, d_stat = source.stat(), destination.stat()
        if s_stat.st_size == d_stat.st_size and \
                s_stat.st_mtime_ns == d_stat.st_mtime_ns:
            return False
    shutil.copy2(source, destination)
    return True


def install_companions(executable):
    """
    Copy `.wasm`, `.worker.js` and `.wasm.map` beside the installed `.js`.

    :returns: list of (role, installed path)
    :raises ColconWasmError: when the build made no `.wasm`
    """
    build_dir = executable.build_js.parent
    install_dir = executable.installed_js.parent
    files = [('js', executable.installed_js)]
    glue_text = executable.build_js.read_text()
    wasm_bytes = executable.companion(build_dir, '.wasm').read_bytes() \
        if executable.companion(build_dir, '.wasm').is_file() else b''
    for suffix, role in COMPANIONS:
        source = executable.companion(build_dir, suffix)
        # a companion belongs to this link only when the output names it
        # (a worker.js of an earlier pthread build may still be there)
        referenced = {
            'wasm': True,
            'worker': (executable.name + suffix) in glue_text,
            'map': (executable.name + suffix).encode() in wasm_bytes,
        }[role]
        if not source.is_file() or not referenced:
            if role == 'wasm':
                raise ColconWasmError(
                    f"executable '{executable.name}': '{source}' is missing")
            stale = executable.companion(install_dir, suffix)
            if stale.is_file():
                stale.unlink()  # e.g. a worker.js of an earlier pthread build
            continue
        destination = executable.companion(install_dir, suffix)
        _copy_if_changed(source, destination)
        files.append((role, destination))
    return files


def file_entry(path, prefix, role):
    """Describe one installed file for the manifest."""
    data = Path(path).read_bytes()
    return {
        'path': Path(path).relative_to(prefix).as_posix(),
        'role': role,
        'size': len(data),
        'gzip_size': len(gzip.compress(data, compresslevel=9, mtime=0)),
        'sha256': hashlib.sha256(data).hexdigest(),
    }


def write_json_if_changed(path, data):
    """Write JSON (sorted keys, stable) only when the content changes."""
    text = json.dumps(data, indent=2, sort_keys=False) + '\n'
    path = Path(path)
    if path.is_file() and path.read_text() == text:
        return False
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return True


def call_type_description_generator(prefix, pkg_name):
    """
    Write the package's type descriptions (:mod:`colcon_wasm.typedesc`).

    :returns: True (the generator ran)
    """
    typedesc.write_type_descriptions(prefix, pkg_name)
    return True


def postprocess_package(*, pkg_name, pkg_version, build_base, install_prefix,
                        emscripten, recipe, flags, fragments=None):
    """
    Post-process one installed package.

    :param str pkg_name: the package name
    :param str pkg_version: its version (or None)
    :param build_base: its build folder
    :param install_prefix: its install prefix
    :param dict emscripten: `{'version': ..., 'root': ...}`
    :param dict recipe: `{'name': ..., 'version': ...}`
    :param dict flags: the manifest's flags entry
    :param fragments: glue fragments (default: the shipped ones)
    :returns: the manifest data
    """
    build_base = Path(build_base)
    prefix = Path(install_prefix)
    if fragments is None:
        fragments = glue.load_fragments()
    installed = read_install_manifest(build_base)
    executables = find_executables(build_base, installed)
    entries = []
    for executable in sorted(executables, key=lambda e: e.name):
        files = install_companions(executable)
        context = {
            'package': pkg_name, 'executable': executable.name,
            # what the build used (the manifest's flags), not guessed from its files
            'pthread': bool(flags.get('pthread')),
            'pthread_pool_size': int(flags.get('pthread_pool_size') or 0),
            'debug': bool(flags.get('debug')),
            'emscripten_version': emscripten.get('version'),
        }
        for role, path in files:
            if role in ('js', 'worker'):
                glue.inject_file(path, fragments, target=role,
                                 context=context)
        text = executable.build_js.read_text()
        entry = {
            'name': executable.name,
            'js': executable.installed_js.relative_to(prefix).as_posix(),
            'files': [file_entry(path, prefix, role) for role, path in files],
            'uses_bus': BUS_MARKER in text,
            'pthread': context['pthread'],
            'pthread_pool_size': context['pthread_pool_size'],
        }
        provides = provided_package(executable.installed_js, prefix, pkg_name)
        if provides:
            entry['package'] = provides
        linked = read_link_report(executable.build_js)
        if linked is not None:
            entry['linked'] = linked
        entries.append(entry)
    # its Python modules and scripts (ament_cmake_python): Pyodide runs them
    from colcon_wasm.cmake_python import python_part
    python, scripts = python_part(prefix, pkg_name, installed)
    names = {e['name'] for e in entries}
    entries += [s for s in scripts if s['name'] not in names]
    manifest = {
        'schema': MANIFEST_SCHEMA,
        'package': pkg_name,
        'package_version': pkg_version,
        'recipe': recipe,
        'emscripten': emscripten,
        'flags': flags,
        'executables': entries,
    }
    if python is not None:
        manifest['python'] = python
    write_json_if_changed(
        prefix / 'share' / pkg_name / 'colcon_wasm' / 'manifest.json',
        manifest)
    if call_type_description_generator(prefix, pkg_name):
        logger.debug(f"Wrote type descriptions of '{pkg_name}'")
    return manifest
