# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The wheel's build step that pyproject.toml cannot say: the page's libraries.

``build_py`` also writes the pinned three.js and urdf-loader files
(``colcon_wasm/vendor.py``) into ``colcon_wasm/_data/vendor/``, so that the
wheel carries them and an installed colcon-wasm fetches nothing at run time.
Everything else is in pyproject.toml.
"""

import os
from pathlib import Path
import sys

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent


def _vendor_module():
    """Import colcon_wasm/vendor.py from the source tree (colcon-wasm is not installed yet)."""
    sys.path.insert(0, str(HERE))
    from colcon_wasm import vendor
    return vendor


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
