# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The data folders shipped with colcon-wasm.

`recipes/`, `toolchains/`, `patches/`, `templates/` and `packages/` are
top-level folders of the repository. The wheel maps them into
`colcon_wasm/_data/<name>` (see `[tool.setuptools] package-dir` in
`pyproject.toml`). This module is the only place that knows both layouts.
"""

from pathlib import Path

DATA_NAMES = ('recipes', 'toolchains', 'patches', 'templates', 'packages')

_PACKAGE_DIR = Path(__file__).resolve().parent


def path(name):
    """
    Get the folder of one kind of shipped data.

    :param str name: one of :data:`DATA_NAMES`
    :returns: the absolute folder path (it may not exist for `packages`
      when no bundled package is part of this installation)
    :rtype: pathlib.Path
    :raises ValueError: for an unknown name
    """
    if name not in DATA_NAMES:
        raise ValueError(
            f"Unknown data folder '{name}', expected one of: "
            + ', '.join(DATA_NAMES))
    installed = _PACKAGE_DIR / '_data' / name
    if installed.is_dir():
        return installed
    # running from a source checkout (editable install or PYTHONPATH)
    return _PACKAGE_DIR.parent / name


def file(name, *parts):
    """
    Get one file inside a shipped data folder.

    :param str name: one of :data:`DATA_NAMES`
    :param parts: path components inside that folder
    :rtype: pathlib.Path
    """
    return path(name).joinpath(*parts)
