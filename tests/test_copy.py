# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The bus copies (client/copy.mjs, copier.memoryMover) under node --test (js/test_copy.mjs)."""

from pathlib import Path
import shutil
import subprocess

REPO = Path(__file__).resolve().parents[1]


def test_copies_are_byte_exact_at_every_alignment():
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap', str(REPO / 'tests' / 'js' / 'test_copy.mjs')],
        capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout[-6000:] + result.stderr[-2000:]
    assert '# fail 0' in result.stdout
    assert '# pass 7' in result.stdout, result.stdout[-2000:]
