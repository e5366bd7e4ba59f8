# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The rosbridge modules without a bus, under node --test (tests/js/test_rosbridge_units.mjs).

WebSocket frames and connections against the npm `ws` client, CBOR against
npm `cbor-x`, JSON with 64-bit integers, messages in rosbridge's JSON and
CBOR forms, capability lists. Needs no build, only `npm ci` in tests/js.
"""

from pathlib import Path
import shutil
import subprocess

import pytest

JS = Path(__file__).resolve().parent / 'js'


def test_rosbridge_modules():
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    if not (JS / 'node_modules' / 'ws').is_dir():
        pytest.skip(f'npm packages missing: run `npm ci` in {JS}')
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap', str(JS / 'test_rosbridge_units.mjs')],
        cwd=str(JS), capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout[-6000:] + result.stderr[-2000:]
    assert '# pass 7' in result.stdout and '# fail 0' in result.stdout, result.stdout[-3000:]
