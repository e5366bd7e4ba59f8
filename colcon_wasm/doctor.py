# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Check what `colcon build --wasm` and the tests need on this machine."""

import importlib.metadata
import os
import re
import shlex
import shutil
import subprocess
import tempfile

from colcon_wasm.error import ColconWasmError
from colcon_wasm.toolchain import find_emscripten

"""Node.js major version the runtime needs (growable SharedArrayBuffer)."""
MINIMUM_NODE = 20

"""
CMake version the build needs: the cmake_minimum_required of the packages
colcon-wasm builds first (packages/wasm_cpp, packages/wasm_js) and README.md's
(ament_cmake itself asks for 3.5; the toolchain files need nothing newer).
"""
MINIMUM_CMAKE = (3, 16)

"""Native C++ compilers looked for on PATH when CXX is unset, in CMake's order."""
CXX_NAMES = ('c++', 'g++', 'clang++')

"""What the C++ compiler check builds and runs (C++17 and its library) and prints."""
CXX17_PROGRAM = """\
#include <cstdio>
#include <optional>
#include <string_view>
#include <utility>

int main() {
  auto [name, value] = std::pair<std::string_view, std::optional<int>>{"c++", 17};
  std::printf("%.*s%d\\n", static_cast<int>(name.size()), name.data(), value.value_or(0));
  return 0;
}
"""
CXX17_OUTPUT = 'c++17'

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


def check_cmake():
    """
    Check for CMake >= MINIMUM_CMAKE, found as colcon-cmake finds it.

    colcon-cmake runs ``$CMAKE_COMMAND`` when it is set, else ``cmake`` on PATH.
    """
    need = '.'.join(str(n) for n in MINIMUM_CMAKE)
    fix = (f'install CMake {need} or newer: `sudo apt-get install -y cmake` '
           '(or `pip install cmake`), or set CMAKE_COMMAND to its path')
    configured = os.environ.get('CMAKE_COMMAND')
    if configured:
        cmake = shutil.which(configured)
        if not cmake:
            return Check('CMake', False,
                         f'CMAKE_COMMAND={configured} is no program', fix)
    else:
        cmake = shutil.which('cmake')
        if not cmake:
            return Check('CMake', False,
                         'no `cmake` on PATH (and CMAKE_COMMAND is unset)', fix)
    text = _run_version([cmake, '--version']) or ''
    match = re.search(r'version ((\d+)\.(\d+)\S*)', text)
    if not match:
        return Check('CMake', False,
                     f"'{cmake} --version' printed no version", fix)
    if (int(match.group(2)), int(match.group(3))) < MINIMUM_CMAKE:
        return Check('CMake', False,
                     f'{match.group(1)} at {cmake}, need {need} or newer', fix)
    return Check('CMake', True, f'{match.group(1)} at {cmake}')


def find_cxx():
    """
    Return the native C++ compiler as ``(command, None)``, or ``(None, why)``.

    As CMake looks for a native build's compiler: ``$CXX`` when it is set (a
    program, maybe followed by flags: ``command`` is its words, the program
    resolved on PATH), else the first of :data:`CXX_NAMES` on PATH.
    """
    configured = os.environ.get('CXX', '').strip()
    if configured:
        try:
            words = shlex.split(configured)
        except ValueError as e:
            return None, f'CXX={configured} cannot be split into words ({e})'
        program = shutil.which(words[0]) if words else None
        if not program:
            return None, f'CXX={configured} names no program'
        return [program] + words[1:], None
    for name in CXX_NAMES:
        program = shutil.which(name)
        if program:
            return [program], None
    return None, f'CXX is unset and no {", ".join(CXX_NAMES)} on PATH'


def _first_lines(text, count=5):
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    more = ' | ...' if len(lines) > count else ''
    return ' | '.join(lines[:count]) + more


def check_cxx():
    """
    Check for a native C++ compiler that builds and runs a C++17 program (optional).

    ``colcon build --wasm`` compiles with Emscripten alone; the native
    ``colcon build`` beside it, scripts/demo.sh and the tests need this one.
    The program (:data:`CXX17_PROGRAM`) is compiled, linked and run in a
    temporary folder; a failure reports the compiler's own message.
    """
    fix = ('`sudo apt-get install -y g++` (the native `colcon build` and the tests '
           'need it), or set CXX to a C++17 compiler')
    command, why = find_cxx()
    if command is None:
        return Check('C++ compiler', False, why, fix, required=False)
    name = ' '.join(command)
    try:
        version = subprocess.run(command + ['--version'], capture_output=True,
                                 text=True, timeout=60)
        lines = version.stdout.strip().splitlines()
        label = lines[0] if version.returncode == 0 and lines else 'unknown version'
        with tempfile.TemporaryDirectory(prefix='colcon-wasm-doctor-') as folder:
            source = os.path.join(folder, 'cxx17.cpp')
            program = os.path.join(folder, 'cxx17')
            with open(source, 'w', encoding='utf-8') as f:
                f.write(CXX17_PROGRAM)
            built = subprocess.run(command + ['-std=c++17', source, '-o', program],
                                   capture_output=True, text=True, timeout=60)
            if built.returncode != 0:
                message = _first_lines(built.stderr or built.stdout) or 'no message'
                return Check('C++ compiler', False,
                             f'{name} failed to build a C++17 program '
                             f'(exit {built.returncode}): {message}', fix, required=False)
            ran = subprocess.run([program], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError) as e:
        return Check('C++ compiler', False, f'{name}: {e}', fix, required=False)
    if ran.returncode != 0 or ran.stdout.strip() != CXX17_OUTPUT:
        message = _first_lines(ran.stderr) or 'no message'
        return Check('C++ compiler', False,
                     f'the C++17 program {name} built does not run here (exit '
                     f'{ran.returncode}, printed {ran.stdout.strip()!r}, not '
                     f'{CXX17_OUTPUT!r}): {message}', fix, required=False)
    return Check('C++ compiler', True, f'{label} at {name} (C++17 builds and runs)',
                 required=False)


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
    return [check_emscripten(emscripten_option), check_cmake(), check_cxx(),
            check_node(), check_chromium(), check_pyodide()] + \
        check_python_requirements()
