# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Python part of a CMake package, for Pyodide (``ament_cmake_python``).

An ``ament_cmake`` package may install Python modules
(``ament_python_install_package``: ``lib/pythonX.Y/site-packages/<pkg>``
and its egg-info) and Python scripts (``install(PROGRAMS ... DESTINATION
lib/<pkg>)``) beside its C++ executables. They are pure Python and run in
Pyodide as they are; this module finds them in what CMake installed (its
``install_manifest.txt``), for the package's manifest
(:func:`colcon_wasm.postprocess.postprocess_package`):

* ``"python"``: the module folders and the files the package installed
  into them, as an ``ament_python`` package's (colcon_wasm.python_package);
* one executable per Python script in ``lib/<pkg>/``, with
  ``"python": {"script": true}``: Pyodide runs it as ``__main__``.
"""

from pathlib import Path

from colcon_core.logging import colcon_logger
from colcon_wasm.python_package import module_folders
from colcon_wasm.python_package import NATIVE_SUFFIXES

logger = colcon_logger.getChild(__name__)


def is_python_script(path):
    """Check if an installed file is a Python script (``.py``, or a python shebang)."""
    path = Path(path)
    if path.suffix == '.py':
        return True
    try:
        with open(path, 'rb') as handle:
            first = handle.readline(200)
    except OSError:
        return False
    return first.startswith(b'#!') and b'python' in first


def python_part(prefix, pkg_name, installed):
    """
    Find the Python modules and scripts a CMake package installed.

    :param prefix: the package's install prefix
    :param str pkg_name: the package name
    :param installed: the absolute paths CMake installed
    :returns: ``(python, executables)``: the manifest's ``"python"`` entry
      (None when the package installed no module) and the executable
      entries of its Python scripts
    """
    prefix = Path(prefix)
    installed = [Path(p) for p in installed]
    folders = module_folders(prefix)
    files, native, scripts = [], [], []
    script_folder = f'lib/{pkg_name}/'
    for path in sorted(installed):
        relative = _relative(path, prefix)
        if relative is None or '__pycache__' in path.parts or not path.is_file():
            continue
        if any(relative.startswith(folder + '/') for folder in folders):
            (native if path.name.endswith(NATIVE_SUFFIXES) else files).append(relative)
            continue
        name = relative[len(script_folder):]
        if relative.startswith(script_folder) and '/' not in name and \
                path.suffix not in ('.js', '.wasm') and is_python_script(path):
            scripts.append({
                'name': name,
                'js': relative,
                'python': {'script': True},
                'uses_bus': True,
                'pthread': False,
            })
    if native:
        logger.warning(
            f"'{pkg_name}' installs compiled Python extension modules ({', '.join(native)}): "
            'Pyodide cannot load them, and an import of them fails in a Python node')
    python = {'path': folders, 'files': files} if files else None
    return python, scripts


def _relative(path, prefix):
    try:
        return path.relative_to(prefix).as_posix()
    except ValueError:
        return None
