# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The wheel's build step that pyproject.toml cannot say: the page's libraries.

``build_py`` also writes the pinned three.js and urdf-loader files
(``colcon_wasm/vendor.py``) into ``colcon_wasm/_data/vendor/``, so that the
wheel carries them and an installed colcon-wasm fetches nothing at run time.
Everything else is in pyproject.toml.
"""

import importlib.util
import os
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent


def _vendor_module():
    """Load colcon_wasm/vendor.py alone (colcon-wasm itself is not installed yet)."""
    spec = importlib.util.spec_from_file_location(
        'colcon_wasm_vendor', HERE / 'colcon_wasm' / 'vendor.py')
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


class BuildPyWithVendor(build_py):
    """build_py, then the page's pinned libraries into the build folder."""

    def run(self):
        """Build the Python files, then unpack the vendored libraries beside them."""
        super().run()
        if getattr(self, 'editable_mode', False):
            # a source checkout unpacks them into the cache on first use
            return
        vendor = _vendor_module()
        target = Path(self.build_lib) / 'colcon_wasm' / '_data' / 'vendor'
        target.parent.mkdir(parents=True, exist_ok=True)
        cache = Path(os.environ.get(
            'COLCON_WASM_CACHE', Path.home() / '.cache' / 'colcon-wasm')) / 'npm-tarballs'
        vendor.unpack(target, cache=cache)


setup(cmdclass={'build_py': BuildPyWithVendor})
