# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Helpers for tests that run the real colcon and the real Emscripten."""

import hashlib
import os
from pathlib import Path
import shutil
import subprocess
import sys

REPO = Path(__file__).resolve().parents[1]
FIXTURES = Path(__file__).resolve().parent / 'fixtures'
BIN = Path(sys.executable).parent


def use_repo_venv():
    """
    Run the calling script again with the repository's .venv Python.

    For the bench/ scripts: their shebang is the system python3, which lacks
    colcon-wasm when it was installed into .venv (the README's set-up).
    Nothing happens when the running Python already imports colcon_wasm or
    when there is no .venv.
    """
    try:
        import colcon_wasm  # noqa: F401
        return
    except ImportError:
        pass
    venv_python = REPO / '.venv' / 'bin' / 'python'
    if venv_python.exists() and Path(sys.executable) != venv_python:
        os.execv(str(venv_python), [str(venv_python)] + sys.argv)
    sys.exit('colcon-wasm is not installed for ' + sys.executable
             + ': follow the README set-up (python3 -m venv .venv && '
             ".venv/bin/pip install -e '.[test]'), then run this again")


def tool(name):
    """Get a console script of the environment running the tests."""
    path = BIN / name
    if path.exists():
        return str(path)
    found = shutil.which(name)
    assert found, f'{name} is not installed in {BIN} nor on PATH'
    return found


def copy_fixture(name, destination):
    """Copy a fixture workspace to a temporary folder (never build in place)."""
    target = Path(destination) / name
    shutil.copytree(FIXTURES / name, target, symlinks=True)
    return target


def colcon(workspace, *args, env=None, check=True, timeout=900):
    """
    Run the real colcon in a workspace.

    Every build must leave `src/` byte-identical: checked on each call.

    :returns: the CompletedProcess (stdout and stderr merged into stdout)
    """
    src = Path(workspace) / 'src'
    before = tree_digest(src) if src.is_dir() else None
    full_env = dict(os.environ)
    full_env.pop('COLCON_DEFAULTS_FILE', None)
    full_env['COLCON_HOME'] = str(Path(workspace) / '.colcon_home')
    full_env.update(env or {})
    completed = subprocess.run(
        [tool('colcon'), '--log-base', 'log'] + list(args), cwd=workspace,
        env=full_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        text=True, timeout=timeout)
    if check and completed.returncode != 0:
        raise AssertionError(
            f'colcon {" ".join(args)} failed ({completed.returncode}):\n'
            + completed.stdout[-6000:])
    if before is not None:
        assert tree_digest(src) == before, \
            f'colcon {" ".join(args)} changed files under {src}'
    return completed


def node(script, *args, env=None, timeout=120):
    """Run a script with Node.js; returns the CompletedProcess."""
    full_env = dict(os.environ)
    full_env.update(env or {})
    return subprocess.run(
        ['node', str(script)] + [str(a) for a in args], env=full_env,
        capture_output=True, text=True, timeout=timeout)


def tree_digest(folder):
    """Hash every file (path, mode, bytes) below a folder."""
    digest = hashlib.sha256()
    folder = Path(folder)
    for path in sorted(folder.rglob('*')):
        relative = path.relative_to(folder).as_posix()
        if path.is_symlink():
            digest.update(f'L {relative} {os.readlink(path)}\n'.encode())
        elif path.is_file():
            digest.update(f'F {relative} {path.stat().st_mode:o}\n'.encode())
            digest.update(path.read_bytes())
        elif path.is_dir():
            digest.update(f'D {relative}\n'.encode())
    return digest.hexdigest()


def is_elf(path):
    """Check if a file is a native ELF executable."""
    with open(path, 'rb') as handle:
        return handle.read(4) == b'\x7fELF'
