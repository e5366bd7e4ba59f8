# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes of ``run --python`` and ``launch --python``: scripts that Pyodide runs.

Each becomes a process of the plan with ``python`` (the script) instead of
an executable; the Node host starts it with the runtime's
``python/spawn.mjs``. A ``--python`` value is the script, or the script
and its arguments as one shell-quoted word (``--python 'talker.py
--ros-args -p rate:=2'``, :func:`split_python_value`); they become the
script's ``sys.argv[1:]``. Pyodide is not part of the wheel: it is the npm
package ``pyodide`` at :data:`PYODIDE_VERSION`, found by
:func:`find_pyodide` (``colcon-wasm doctor`` says how to install it).
See docs/python.md.
"""

import json
import os
from pathlib import Path
import shlex

from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.install_view import program_environment

#: The npm release of ``pyodide`` the runtime is tested with (python/spawn.mjs pins it too).
PYODIDE_VERSION = '314.0.8'
#: Names the folder of the npm package (the one holding ``pyodide.mjs``).
PYODIDE_ENVIRONMENT_VARIABLE = 'COLCON_WASM_PYODIDE'
#: The files a Python node loads from that folder.
PYODIDE_FILES = ('pyodide.mjs', 'pyodide.asm.mjs', 'pyodide.asm.wasm', 'python_stdlib.zip',
                 'pyodide-lock.json')


def default_pyodide_prefix():
    """Return where ``doctor`` tells users to install Pyodide (under the cache folder)."""
    cache = Path(os.environ.get('COLCON_WASM_CACHE', Path.home() / '.cache' / 'colcon-wasm'))
    return cache / 'pyodide'


def install_hint():
    """Return the commands that install Pyodide where it is looked for."""
    prefix = default_pyodide_prefix()
    text = ("npm install --prefix '{}' pyodide@{} (or install it elsewhere and set {} to "
            'its node_modules/pyodide folder)')
    return text.format(prefix, PYODIDE_VERSION, PYODIDE_ENVIRONMENT_VARIABLE)


def find_pyodide(option=None):
    """
    Find the Pyodide npm package: ``option``, then $COLCON_WASM_PYODIDE, then the cache.

    :returns: the folder holding ``pyodide.mjs``
    :raises LaunchError: naming what is missing or the wrong version, and the fix
    """
    if option:
        candidates = [(Path(option), '--pyodide')]
    elif os.environ.get(PYODIDE_ENVIRONMENT_VARIABLE):
        candidates = [(Path(os.environ[PYODIDE_ENVIRONMENT_VARIABLE]),
                       f'${PYODIDE_ENVIRONMENT_VARIABLE}')]
    else:
        candidates = [(default_pyodide_prefix() / 'node_modules' / 'pyodide', 'default')]
    folder, source = candidates[0]
    folder = folder.expanduser().resolve()
    missing = [f for f in PYODIDE_FILES if not (folder / f).is_file()]
    if missing:
        raise LaunchError(f"Python nodes need Pyodide {PYODIDE_VERSION}, and '{folder}' "
                          f"({source}) lacks {', '.join(missing)}: {install_hint()}")
    try:
        version = json.loads((folder / 'package.json').read_text(encoding='utf-8'))['version']
    except (OSError, ValueError, KeyError):
        version = 'unknown'
    if version != PYODIDE_VERSION:
        raise LaunchError(f'Incorrect Pyodide version {version} in {folder}. Need Pyodide '
                          f'version {PYODIDE_VERSION}: {install_hint()}')
    return folder


def split_python_value(value):
    """
    Split a ``--python`` value into the script and its arguments.

    A value that names a file as a whole is the script alone (a path with
    spaces); else it is split as a shell splits words, and the first word
    is the script.

    :returns: ``(script, [arguments])``
    :raises LaunchError: for quotes that do not close, or an empty value
    """
    if Path(value).is_file():
        return value, []
    try:
        words = shlex.split(value)
    except ValueError as e:
        raise LaunchError(f'--python {value!r}: {e} (the value is the script, then its '
                          "arguments, quoted as in a shell: --python 'talker.py --ros-args "
                          "-p rate:=2')") from e
    if not words:
        raise LaunchError('--python needs a script (--python FILE, or '
                          "--python 'FILE ARGS...')")
    return words[0], words[1:]


def python_processes(scripts, prefixes, *, first_index):
    """
    Describe the Python nodes for the Node host, labelled ``<stem>-N`` after the others.

    :param scripts: the ``--python`` values (:func:`split_python_value`), or
      ``(script, [arguments])`` pairs
    :param prefixes: the ``AMENT_PREFIX_PATH`` entries the processes see
    :raises LaunchError: for a script that is not a file
    """
    entries = []
    for index, script in enumerate(scripts, start=first_index):
        value = isinstance(script, (str, os.PathLike))
        file, arguments = split_python_value(str(script)) if value else script
        path = Path(file).resolve()
        if not path.is_file():
            given = f' (from --python {str(script)!r}: the script, then its arguments)' \
                if value and arguments else ''
            raise LaunchError(f"Python node '{file}' does not exist{given}")
        entries.append({
            'label': f'{path.stem}-{index}',
            'python': str(path),
            'js': str(path),
            'args': [str(a) for a in arguments],
            'env': program_environment({}, prefixes),
        })
    return entries
