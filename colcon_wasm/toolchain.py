# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Find a usable Emscripten.

Lookup order (the first candidate that exists is used, then checked):

1. the `--wasm-emscripten PATH` option: an `emcc` executable, an emsdk
   folder or an Emscripten root folder;
2. the `EMSDK` environment variable (set by `emsdk_env.sh`);
3. `emcc` on `PATH`;
4. Debian's `/usr/share/emscripten`.
"""

import os
from pathlib import Path
import re
import shutil
import subprocess

from colcon_wasm.error import ColconWasmError

"""The oldest Emscripten this project is tested with (Debian bookworm)."""
MINIMUM_VERSION = (3, 1, 6)

DEBIAN_ROOT = Path('/usr/share/emscripten')

"""Where Debian installs the node modules emcc's JS optimizer needs."""
DEBIAN_NODE_PATH = Path('/usr/share/nodejs')

INSTALL_HINT = (
    'install it with `sudo apt-get install emscripten` (Debian/Ubuntu) or '
    'with emsdk (https://emscripten.org/docs/getting_started/downloads.html:'
    ' `./emsdk install latest && ./emsdk activate latest && '
    'source ./emsdk_env.sh`), or pass --wasm-emscripten PATH')


class Emscripten:
    """A located Emscripten installation."""

    def __init__(self, *, root, bin_dir, version, source):
        """
        Describe an Emscripten installation.

        :param pathlib.Path root: the folder holding `emcc.py` and `cmake/`
        :param pathlib.Path bin_dir: the folder holding the `emcc`, `em++`,
          `emar`, `emranlib` and `em-config` commands
        :param tuple version: (major, minor, patch)
        :param str source: how it was found, for messages
        """
        self.root = root
        self.bin_dir = bin_dir
        self.version = version
        self.source = source

    @property
    def version_string(self):
        """The version as `X.Y.Z`."""
        return '.'.join(str(v) for v in self.version)

    @property
    def emcc(self):
        """The `emcc` command."""
        return self.bin_dir / 'emcc'

    @property
    def platform_file(self):
        """Emscripten's own CMake toolchain file."""
        return self.root / 'cmake' / 'Modules' / 'Platform' / \
            'Emscripten.cmake'

    def environment(self, base_env=None):
        """
        Get the environment variables emcc needs.

        `PATH` gets the command folder first (Emscripten.cmake runs
        `em-config` from `PATH`). Debian's emcc needs `NODE_PATH` pointing at
        Debian's node modules (acorn) when the `node` on `PATH` is not
        Debian's own.

        :param dict base_env: the environment to extend (default: os.environ)
        :returns: the variables to set (only those that change)
        :rtype: dict
        """
        env = dict(os.environ if base_env is None else base_env)
        changes = {}
        path = env.get('PATH', '')
        entries = path.split(os.pathsep) if path else []
        if not entries or entries[0] != str(self.bin_dir):
            changes['PATH'] = os.pathsep.join(
                [str(self.bin_dir)] + [e for e in entries if e])
        if self.root == DEBIAN_ROOT and DEBIAN_NODE_PATH.is_dir():
            node_path = env.get('NODE_PATH', '')
            node_entries = node_path.split(os.pathsep) if node_path else []
            if str(DEBIAN_NODE_PATH) not in node_entries:
                changes['NODE_PATH'] = os.pathsep.join(
                    node_entries + [str(DEBIAN_NODE_PATH)])
        return changes

    def describe(self):
        """Get a short description for logs and the manifest."""
        return {'version': self.version_string, 'root': str(self.root)}

    def llvm_tool(self, name):
        """
        Get an LLVM tool of this Emscripten (e.g. `llvm-nm`).

        Emscripten's configuration names the LLVM folder (`LLVM_ROOT`) and
        Debian's adds a version suffix (`LLVM_ADD_VERSION`, e.g. 14:
        `llvm-nm-14`); both are asked from `em-config` once.

        :raises ColconWasmError: when the tool is not there
        """
        if not hasattr(self, '_llvm'):
            answers = []
            for key in ('LLVM_ROOT', 'LLVM_ADD_VERSION'):
                try:
                    completed = subprocess.run(
                        [str(self.bin_dir / 'em-config'), key],
                        capture_output=True, text=True, timeout=120,
                        env=dict(os.environ, **self.environment()))
                    answers.append(completed.stdout.strip()
                                   if completed.returncode == 0 else '')
                except (OSError, subprocess.SubprocessError):
                    answers.append('')
            self._llvm = tuple(answers)
        root, suffix = self._llvm
        names = [f'{name}-{suffix}', name] if suffix else [name]
        for folder in ([Path(root)] if root else []) + [self.bin_dir]:
            for candidate in names:
                if (folder / candidate).is_file():
                    return folder / candidate
        raise ColconWasmError(
            f"Emscripten at '{self.root}' has no {name} in its LLVM folder "
            f"('{root or 'LLVM_ROOT unknown'}'): its installation is "
            'incomplete; ' + INSTALL_HINT)


def parse_version(text):
    """
    Parse the first `X.Y.Z` in a text.

    :param str text: e.g. the content of `emscripten-version.txt` or the
      first line of `emcc --version`
    :returns: the version tuple, or None
    """
    match = re.search(r'(\d+)\.(\d+)\.(\d+)', text or '')
    if not match:
        return None
    return tuple(int(g) for g in match.groups())


def _root_from_bin_dir(bin_dir):
    """Get the Emscripten root belonging to a folder holding `emcc`."""
    emcc = bin_dir / 'emcc'
    if (bin_dir / 'emcc.py').is_file():
        return bin_dir  # emsdk / git checkout: commands live in the root
    # Debian: /usr/bin/emcc is a wrapper (or symlink to one) calling
    # /usr/share/emscripten/emcc.py
    try:
        text = emcc.resolve().read_text(errors='replace')[:4096]
    except OSError:
        text = ''
    match = re.search(r'(/\S+?)/\$BASENAME\.py', text)
    if match and (Path(match.group(1)) / 'emcc.py').is_file():
        return Path(match.group(1))
    if (DEBIAN_ROOT / 'emcc.py').is_file():
        return DEBIAN_ROOT
    return None


def _candidate_from_path(path, source):
    """
    Interpret a user-given path as an Emscripten installation.

    :returns: (root, bin_dir) or None
    """
    path = Path(path).expanduser()
    if path.is_file() and path.name in ('emcc', 'emcc.py'):
        bin_dir = path.parent
        root = _root_from_bin_dir(bin_dir)
        return (root, bin_dir) if root else None
    if path.is_dir():
        # emsdk folder
        for sub in ('upstream/emscripten', 'emscripten'):
            if (path / sub / 'emcc.py').is_file():
                return path / sub, path / sub
        # Emscripten root (git checkout or emsdk's upstream/emscripten)
        if (path / 'emcc.py').is_file():
            if (path / 'emcc').is_file():
                return path, path
            if path == DEBIAN_ROOT and Path('/usr/bin/emcc').is_file():
                return path, Path('/usr/bin')
            return None
        # a bin folder with emcc
        if (path / 'emcc').is_file():
            root = _root_from_bin_dir(path)
            return (root, path) if root else None
    return None


def candidates(option=None, env=None):
    """
    List where Emscripten is looked for, in lookup order.

    :param str option: the value of `--wasm-emscripten`, if any
    :param dict env: the environment (default: os.environ)
    :returns: list of (description, path or None)
    """
    env = os.environ if env is None else env
    result = []
    if option:
        result.append(('--wasm-emscripten', option))
    result.append(('EMSDK', env.get('EMSDK') or None))
    emcc = shutil.which('emcc', path=env.get('PATH'))
    result.append(('emcc on PATH', emcc))
    result.append(('Debian', str(DEBIAN_ROOT)))
    return result


def read_version(root, bin_dir):
    """
    Read the Emscripten version.

    :returns: the version tuple or None
    """
    version_file = root / 'emscripten-version.txt'
    if version_file.is_file():
        version = parse_version(version_file.read_text())
        if version:
            return version
    try:
        completed = subprocess.run(
            [str(bin_dir / 'emcc'), '--version'], capture_output=True,
            text=True, timeout=120)
    except (OSError, subprocess.SubprocessError):
        return None
    return parse_version(completed.stdout.splitlines()[0]
                         if completed.stdout else '')


def find_emscripten(option=None, env=None):
    """
    Find a usable Emscripten, in the documented lookup order.

    An explicit `--wasm-emscripten` that is not usable is an error (it is
    never silently replaced by another installation).

    :param str option: the value of `--wasm-emscripten`, if any
    :param dict env: the environment (default: os.environ)
    :returns: the :class:`Emscripten`
    :raises ColconWasmError: with one line naming what was looked for and
      how to install Emscripten
    """
    looked = []
    for source, value in candidates(option, env):
        if not value:
            looked.append(f'{source} (not set)' if source != 'emcc on PATH'
                          else 'emcc on PATH (not found)')
            continue
        found = _candidate_from_path(value, source)
        if not found:
            looked.append(f"{source} '{value}' (no emcc there)")
            if source == '--wasm-emscripten':
                raise ColconWasmError(
                    f"--wasm-emscripten '{value}' is not an emcc executable,"
                    ' an emsdk folder or an Emscripten root; '
                    + INSTALL_HINT)
            continue
        root, bin_dir = found
        version = read_version(root, bin_dir)
        if version is None:
            looked.append(f"{source} '{value}' (version unreadable)")
            continue
        if version < MINIMUM_VERSION:
            needed = '.'.join(str(v) for v in MINIMUM_VERSION)
            found_v = '.'.join(str(v) for v in version)
            raise ColconWasmError(
                f"Emscripten {found_v} at '{root}' ({source}) is too old, "
                f'need {needed} or newer; ' + INSTALL_HINT)
        return Emscripten(
            root=root, bin_dir=bin_dir, version=version, source=source)
    raise ColconWasmError(
        'no Emscripten found (looked for: ' + '; '.join(looked) + '); '
        + INSTALL_HINT)
