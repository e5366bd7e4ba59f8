# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The page's pure JS helpers (YAML, stats, field paths, images) under node --test."""

import json
from pathlib import Path
import shutil
import subprocess
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import cdr_fastcdr  # noqa: E402, I100

REPO = Path(__file__).resolve().parents[1]


def test_tools_helpers(tmp_path):
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    types = tmp_path / 'types.json'
    types.write_text(json.dumps(cdr_fastcdr.load_types()), encoding='utf-8')
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap',
         str(REPO / 'tests' / 'js' / 'test_page_tools.mjs')],
        env={'CDR_TYPES': str(types), 'PATH': '/usr/bin:/bin'},
        capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout[-6000:] + result.stderr[-2000:]
    assert '# fail 0' in result.stdout
