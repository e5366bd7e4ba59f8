# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Pack an installed ``ament_python`` package for Pyodide: its manifest.

``colcon build --wasm`` installs an ``ament_python`` package with its stock
colcon task (``setup.py``, the host's setuptools): its modules go to
``lib/pythonX.Y/site-packages``, its ``console_scripts`` to ``lib/<pkg>/``,
its data files where ``data_files`` puts them. The modules are pure Python
and run in Pyodide as they are; this module then writes the package's
``share/<pkg>/colcon_wasm/manifest.json`` (docs/design.md section 5), so
that ``run``, ``launch`` and the page find its entry points beside the C++
executables:

* one executable per ``console_scripts`` entry point, with
  ``"python": {"module", "function"}`` and the installed script as ``js``;
* ``"python"`` at the top: the package's module folders (``path``) and
  files (``files``), relative to its prefix, and the compiled extension
  modules Pyodide cannot load (``native``), which make the build fail with
  their names.
"""

import configparser
from pathlib import Path

from colcon_wasm.error import ColconWasmError
from colcon_wasm.postprocess import MANIFEST_SCHEMA
from colcon_wasm.postprocess import write_json_if_changed

"""Where setuptools puts the modules under a prefix (Debian's Python: dist-packages)."""
MODULE_FOLDER_PATTERNS = (
    'lib/python*/site-packages', 'lib/python*/dist-packages',
    'local/lib/python*/site-packages', 'local/lib/python*/dist-packages')

"""Suffixes of compiled extension modules (CPython's, for the host: not Pyodide's)."""
NATIVE_SUFFIXES = ('.so', '.pyd', '.dylib')


class PythonPackageError(ColconWasmError):
    """An ``ament_python`` package that cannot run in Pyodide."""


def module_folders(prefix):
    """Return the folders of installed modules under a prefix (relative paths, sorted)."""
    prefix = Path(prefix)
    found = set()
    for pattern in MODULE_FOLDER_PATTERNS:
        found.update(p for p in prefix.glob(pattern) if p.is_dir())
    return sorted(p.relative_to(prefix).as_posix() for p in found)


def _normalized(name):
    return name.lower().replace('-', '_').replace('.', '_')


def distribution_metadata(folder, pkg_name):
    """
    Find the ``*.egg-info`` / ``*.dist-info`` of a package in a module folder.

    :returns: its path, or None when the folder has none for that name
    """
    wanted = _normalized(pkg_name)
    for info in sorted(Path(folder).iterdir()):
        if info.suffix not in ('.egg-info', '.dist-info'):
            continue
        project = info.name[:-len(info.suffix)].split('-')[0]
        if _normalized(project) == wanted:
            return info
    return None


def console_scripts(metadata):
    """
    Read the ``console_scripts`` of a distribution's ``entry_points.txt``.

    :returns: ``[(name, module, function)]`` in the file's order
    :raises PythonPackageError: for an entry point that is not ``module:function``
    """
    path = Path(metadata) / 'entry_points.txt'
    if not path.is_file():
        return []
    parser = configparser.ConfigParser(delimiters=('=',), interpolation=None)
    parser.optionxform = str
    parser.read(path, encoding='utf-8')
    if not parser.has_section('console_scripts'):
        return []
    scripts = []
    for name, target in parser.items('console_scripts'):
        target = target.split('[')[0].strip()  # extras: 'mod:fn [extra]'
        module, _, function = target.partition(':')
        if not module or not function:
            raise PythonPackageError(
                f"console_scripts entry '{name} = {target}' of '{path}' is not "
                "'module:function': fix the entry point in the package's setup.py or setup.cfg")
        scripts.append((name.strip(), module.strip(), function.strip()))
    return scripts


def _distribution_files(folder, metadata):
    """Yield the files of a distribution: its metadata and its top-level modules."""
    top_level = Path(metadata) / 'top_level.txt'
    names = top_level.read_text(encoding='utf-8').split() if top_level.is_file() else []
    roots = [Path(metadata)] + [Path(folder) / n for n in names]
    roots += [Path(folder) / f'{n}.py' for n in names]
    for root in roots:
        if root.is_file():
            yield root
        elif root.is_dir():
            yield from (p for p in root.rglob('*') if p.is_file())


def _installed_script(prefix, pkg_name, name):
    for candidate in (prefix / 'lib' / pkg_name / name, prefix / 'bin' / name):
        if candidate.is_file():
            return candidate
    return None


def _module_file(prefix, folders, module):
    parts = module.split('.')
    for folder in folders:
        base = prefix / folder / Path(*parts)
        for candidate in (base.with_suffix('.py'), base / '__init__.py'):
            if candidate.is_file():
                return candidate
    return None


def pack_python_package(*, pkg_name, pkg_version, install_prefix, recipe):
    """
    Write the manifest of an ``ament_python`` package installed under ``install_prefix``.

    :param dict recipe: ``{'name': ..., 'version': ...}`` of the recipe used
    :returns: the manifest data
    :raises PythonPackageError: when the package installed compiled
      extension modules (Pyodide cannot load the host's), or an entry point
      names a module that was not installed
    """
    prefix = Path(install_prefix)
    folders = module_folders(prefix)
    files = []
    native = []
    metadata = None
    for folder in folders:
        found = distribution_metadata(prefix / folder, pkg_name)
        if found is None:
            continue
        metadata = metadata or found
        # what the distribution installed: its top-level modules and its metadata
        # (a merged install space holds other packages' modules beside them)
        for path in sorted(_distribution_files(prefix / folder, found)):
            if '__pycache__' in path.parts:
                continue
            relative = path.relative_to(prefix).as_posix()
            files.append(relative)
            if path.name.endswith(NATIVE_SUFFIXES):
                native.append(relative)
    if native:
        raise PythonPackageError(
            f"'{pkg_name}' installs compiled extension modules ({', '.join(native)}): they "
            "are built for the host's CPython, and Pyodide cannot load them; skip the package "
            f"for --wasm (--packages-skip {pkg_name}, or 'skip: {{{pkg_name}: REASON}}' in a "
            'recipe overlay given with --wasm-recipe)')
    executables = []
    for name, module, function in (console_scripts(metadata) if metadata else []):
        module_file = _module_file(prefix, folders, module)
        if module_file is None:
            raise PythonPackageError(
                f"entry point '{name}' of '{pkg_name}' names the module '{module}', which the "
                f"package did not install under {', '.join(folders) or prefix}: add it to "
                "'packages' (or 'py_modules') in its setup.py")
        script = _installed_script(prefix, pkg_name, name) or module_file
        executables.append({
            'name': name,
            'js': script.relative_to(prefix).as_posix(),
            'python': {'module': module, 'function': function},
            'uses_bus': True,
            'pthread': False,
        })
    manifest = {
        'schema': MANIFEST_SCHEMA,
        'package': pkg_name,
        'package_version': pkg_version,
        'recipe': recipe,
        'emscripten': None,
        'flags': {},
        'python': {'path': folders, 'files': files},
        'executables': executables,
    }
    write_json_if_changed(prefix / 'share' / pkg_name / 'colcon_wasm' / 'manifest.json',
                          manifest)
    return manifest
