# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The tools process gives a late TRANSIENT_LOCAL subscription the history (node --test)."""

from pathlib import Path
import shutil
import subprocess

REPO = Path(__file__).resolve().parents[1]


def test_late_transient_local_subscriptions_get_the_history():
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap',
         str(REPO / 'tests' / 'js' / 'test_tools_history.mjs')],
        capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout[-6000:] + result.stderr[-2000:]
    assert '# pass 1' in result.stdout and '# fail 0' in result.stdout
