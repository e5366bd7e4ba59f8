# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A clear error for an import of a Python module that is not in the browser.

Some Humble packages' Python modules are C extensions built against the
host's CPython (tf2_py, PyKDL), or need one (tf2_ros' Python part imports
tf2_py), or come from Pyodide's full distribution, which the npm package
does not carry (numpy): ``colcon build --wasm`` skips them
(recipes/humble.yaml says why). A finder last on ``sys.meta_path`` turns
Python's bare ``No module named 'tf2_py'`` into one that names the package
and the reason; a module that exists is always found first.
tests/test_pyodide_nodes.py checks :data:`MODULES` against the recipe.
"""

import importlib.abc
import sys

"""Top-level module: (the ROS package or distribution that has it, why it is not here)."""
MODULES = {
    'tf2_py': ('tf2_py', 'a C extension module of CPython; colcon-wasm skips the package'),
    'PyKDL': ('python_orocos_kdl', 'a C++ extension module (pybind11); colcon-wasm skips '
              'the package'),
    'tf2_ros': ('tf2_ros', 'its Python part imports tf2_py, a C extension; colcon-wasm '
                'builds only its C++ part'),
    'numpy': ('numpy', "a package of Pyodide's full distribution, not of the npm package "
              'pyodide that colcon-wasm runs (nothing is loaded from a CDN at run time)'),
}


"""Modules of Pyodide's distribution whose wheels the Pyodide folder lacks (set per node)."""
DISTRIBUTION = {}


def note_distribution_packages(absent):
    """
    Remember the imports of Pyodide packages that could not be loaded (python/distribution.mjs).

    :param absent: ``{module: [package, version, wheel file, Pyodide folder]}``
    """
    for module, (package, version, wheel, folder) in absent.items():
        DISTRIBUTION[module] = (
            package,
            f"a package of Pyodide's distribution ({package} {version} in the pyodide-lock.json "
            f'of {folder}), whose wheel {wheel} is not in that folder: give a Pyodide release '
            'folder that has it with --pyodide DIR (or COLCON_WASM_PYODIDE); nothing is loaded '
            'from a CDN at run time')


class NativeOnlyFinder(importlib.abc.MetaPathFinder):
    """Refuses the modules of :data:`MODULES` with a message that names their package."""

    def find_spec(self, fullname, path=None, target=None):
        """Raise ModuleNotFoundError for a known module that is not in the browser."""
        top = fullname.split('.')[0]
        if top not in MODULES and top not in DISTRIBUTION:
            return None
        package, why = DISTRIBUTION.get(top) or MODULES[top]
        raise ModuleNotFoundError(
            f"No module named '{fullname}' in colcon-wasm's Python: it comes from the "
            f"package '{package}', {why}. Run this node natively, or without this import.",
            name=fullname)


def install_finder():
    """Put the finder last on sys.meta_path (once)."""
    if not any(isinstance(f, NativeOnlyFinder) for f in sys.meta_path):
        sys.meta_path.append(NativeOnlyFinder())
