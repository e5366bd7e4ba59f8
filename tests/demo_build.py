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
import time

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


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def prune_orphaned_workspaces(max_age_hours=24):
    """
    Remove the demo workspaces of test runs that were killed (atexit never ran).

    Each workspace names its test run's process in ``owner.pid``; one whose
    process is gone is removed, and one without that file (being made, or
    of an older checkout) once it is a day old.
    """
    limit = time.time() - max_age_hours * 3600
    for folder in Path(tempfile.gettempdir()).glob('colcon-wasm-demo-*'):
        try:
            orphaned = not _alive(int((folder / 'owner.pid').read_text()))
        except (OSError, ValueError):
            try:
                orphaned = folder.stat().st_mtime < limit
            except OSError:
                continue
        if orphaned:
            shutil.rmtree(folder, ignore_errors=True)


def demo_install():
    """
    Build demo/src with ``colcon build --wasm`` in a scratch workspace.

    :returns: the install space (``install_wasm``)
    :raises RuntimeError: with the build's output when it fails
    """
    with _lock:
        if 'install' in _built:
            return _built['install']
        prune_orphaned_workspaces()
        workspace = Path(tempfile.mkdtemp(prefix='colcon-wasm-demo-'))
        atexit.register(shutil.rmtree, workspace, ignore_errors=True)  # once the run is over
        (workspace / 'owner.pid').write_text(str(os.getpid()))
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
