# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Check what `colcon build --wasm` and the tests need on this machine."""

import importlib.metadata
import os
import re
import shutil
import subprocess

from colcon_wasm.error import ColconWasmError
from colcon_wasm.toolchain import find_emscripten

"""Node.js major version the runtime needs (growable SharedArrayBuffer)."""
MINIMUM_NODE = 20

"""Python distributions colcon-wasm needs at build time: (name, why)."""
PYTHON_REQUIREMENTS = (
    ('colcon-core', 'colcon itself'),
    ('colcon-cmake', 'the stock CMake build task'),
    ('colcon-ros', 'ament_cmake / ros.cmake packages'),
    ('colcon-package-selection', '--packages-up-to and friends'),
    ('jinja2', 'glue templates'),
    ('PyYAML', 'recipes'),
    ('empy', "Humble's code generators (need empy 3.x)"),
    ('lark', "Humble's rosidl_parser"),
)


class Check:
    """The result of one check."""

    def __init__(self, name, ok, detail, fix=None, required=True):
        """Record a check result."""
        self.name = name
        self.ok = ok
        self.detail = detail
        self.fix = fix
        self.required = required

    def line(self):
        """Format the result as one line."""
        status = 'ok' if self.ok else ('MISSING' if self.required
                                       else 'missing (optional)')
        text = f'{status:>19}  {self.name}: {self.detail}'
        if not self.ok and self.fix:
            text += f' -> {self.fix}'
        return text


def check_emscripten(option=None):
    """Check for a usable Emscripten (same lookup as the build)."""
    try:
        emscripten = find_emscripten(option)
    except ColconWasmError as e:
        return Check('Emscripten', False, str(e))
    return Check('Emscripten', True,
                 f'{emscripten.version_string} in {emscripten.root} '
                 f'({emscripten.source})')


def _run_version(command):
    try:
        completed = subprocess.run(
            command, capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    return (completed.stdout or completed.stderr).strip()


def check_node():
    """Check for Node.js >= 20."""
    node = shutil.which('node')
    fix = ('install Node.js 20 or newer: `sudo apt-get install nodejs` '
           '(Debian bookworm has 18: use the NodeSource or nvm packages)')
    if not node:
        return Check('Node.js', False, 'no `node` on PATH', fix)
    text = _run_version([node, '--version']) or ''
    match = re.match(r'v(\d+)\.', text)
    if not match:
        return Check('Node.js', False, f"'{node} --version' failed", fix)
    if int(match.group(1)) < MINIMUM_NODE:
        return Check('Node.js', False,
                     f'{text} at {node}, need v{MINIMUM_NODE} or newer', fix)
    return Check('Node.js', True, f'{text} at {node}')


def check_chromium():
    """Check for a Chromium for the browser tests (optional)."""
    candidates = [os.environ.get('COLCON_WASM_CHROMIUM'), '/usr/bin/chromium',
                  shutil.which('chromium'), shutil.which('chromium-browser')]
    fix = ('`sudo apt-get install chromium` (only the browser tests and '
           '`colcon-wasm serve` checks need it), or set COLCON_WASM_CHROMIUM')
    for candidate in candidates:
        if candidate and os.path.isfile(candidate) and \
                os.access(candidate, os.X_OK):
            text = _run_version([candidate, '--version']) or 'unknown version'
            return Check('Chromium', True, f'{text} at {candidate}',
                         required=False)
    return Check('Chromium', False, 'not found', fix, required=False)


def check_python_requirements():
    """Check the Python distributions colcon-wasm needs."""
    checks = []
    for name, why in PYTHON_REQUIREMENTS:
        try:
            version = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            checks.append(Check(f'Python: {name}', False, f'needed for {why}',
                                f'pip install {name}'))
            continue
        if name == 'empy' and not version.startswith('3.'):
            checks.append(Check(
                f'Python: {name}', False,
                f'{version} installed, Humble needs 3.x',
                "pip install 'empy==3.3.4'"))
            continue
        checks.append(Check(f'Python: {name}', True, version))
    return checks


def check_pyodide():
    """Check for the Pyodide npm package of Python nodes (optional)."""
    from colcon_wasm.launch.errors import LaunchError
    from colcon_wasm.launch.python_nodes import find_pyodide
    from colcon_wasm.launch.python_nodes import install_hint
    from colcon_wasm.launch.python_nodes import PYODIDE_VERSION
    try:
        folder = find_pyodide()
    except LaunchError as e:
        detail = str(e).split(': npm install')[0]
        return Check('Pyodide', False, detail, install_hint(), required=False)
    return Check('Pyodide', True, f'{PYODIDE_VERSION} in {folder} (Python nodes, '
                 'docs/python.md)', required=False)


def run_checks(emscripten_option=None):
    """Run every check, in the order printed."""
    return [check_emscripten(emscripten_option), check_node(),
            check_chromium(), check_pyodide()] + check_python_requirements()
