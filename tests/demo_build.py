# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Build the bundled demo workspace once per test run, with the real colcon build --wasm."""

import atexit
import os
from pathlib import Path
import shutil
import subprocess
import sys
import tempfile
import threading

REPO = Path(__file__).resolve().parents[1]
_lock = threading.Lock()
_built = {}


def venv_tool(name):
    """Return a console script of the interpreter running the tests (its venv)."""
    path = Path(sys.executable).parent / name
    if not path.exists():
        raise RuntimeError(f'{name} is not installed next to {sys.executable}: pip install -e '
                           '.[test]')
    return path


def demo_install():
    """
    Build demo/src with ``colcon build --wasm`` in a scratch workspace.

    :returns: the install space (``install_wasm``)
    :raises RuntimeError: with the build's output when it fails
    """
    with _lock:
        if 'install' in _built:
            return _built['install']
        workspace = Path(tempfile.mkdtemp(prefix='colcon-wasm-demo-'))
        atexit.register(shutil.rmtree, workspace, ignore_errors=True)  # once the run is over
        shutil.copytree(REPO / 'demo' / 'src', workspace / 'src')
        command = ['nice', '-n', '10', str(venv_tool('colcon')), 'build', '--wasm',
                   '--event-handlers', 'console_cohesion+']
        result = subprocess.run(command, cwd=str(workspace), capture_output=True, text=True,
                                env=dict(os.environ), timeout=1800)
        if result.returncode != 0:
            raise RuntimeError('colcon build --wasm of the demo '
                               f'failed:\n{result.stdout[-8000:]}\n{result.stderr[-4000:]}')
        _built['install'] = workspace / 'install_wasm'
        return _built['install']
