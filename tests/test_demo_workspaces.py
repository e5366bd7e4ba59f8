# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""tests/demo_build.py: the demo workspaces of killed test runs are removed, live ones kept."""

import os
from pathlib import Path
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100


def test_orphaned_demo_workspaces_are_removed_and_live_ones_kept(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, 'tempdir', str(tmp_path))
    gone = subprocess.Popen([sys.executable, '-c', 'pass'])
    gone.wait()

    def workspace(name, owner=None, age_hours=0):
        folder = tmp_path / f'colcon-wasm-demo-{name}'
        (folder / 'src').mkdir(parents=True)
        if owner is not None:
            (folder / 'owner.pid').write_text(str(owner))
        then = time.time() - age_hours * 3600
        os.utime(folder, (then, then))
        return folder

    killed = workspace('killed', owner=gone.pid)
    live = workspace('live', owner=os.getpid())
    old = workspace('old', age_hours=30)
    new = workspace('new', age_hours=1)
    other = tmp_path / 'something-else'
    other.mkdir()
    demo_build.prune_orphaned_workspaces()
    assert not killed.exists() and not old.exists()
    assert live.is_dir() and new.is_dir() and other.is_dir()
