# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A bus process killed at the worst moment of each bus operation (issue 42).

tests/js/bus_faults.mjs runs the scenarios of
tests/js/bus_faults_scenarios.mjs on the repository's runtime (no build),
once in Node.js and once in Chromium: a JS-only bus process is stopped at
a fault point (packages/wasm_js/src/bus/faults.mjs), its worker is
terminated there and the runtime cleans up; the scenario then checks that
the locks are free, the victim's endpoints are gone and the arena whole,
its peers' events fired, and the live processes' traffic went on
(docs/faults.md). The demo_ scenarios kill the demo's C++ programs
(demo/src, built by tests/demo_build.py) through the same fault points
(Runtime.spawn's faultPoint). Each scenario is bounded (40 s, fixed counts).
"""

import json
import os
from pathlib import Path
import shutil
import subprocess

from core import harness
import demo_build
import pytest

HERE = Path(__file__).resolve().parent
RUNNER = HERE / 'js' / 'bus_faults.mjs'


def _node():
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    return node


def _scenarios():
    listed = subprocess.run([_node(), str(RUNNER), '--list'], capture_output=True,
                            text=True, timeout=60, check=True).stdout
    return [json.loads(line) for line in listed.splitlines() if line]


SCENARIOS = _scenarios()


def _run(*args, timeout):
    done = subprocess.run([_node(), str(RUNNER), *args], capture_output=True, text=True,
                          timeout=timeout, cwd=str(HERE / 'js'))
    assert done.returncode == 0, done.stdout[-4000:] + done.stderr[-4000:]
    results = {}
    for line in done.stdout.splitlines():
        if line.startswith('{'):
            r = json.loads(line)
            results[r['scenario']] = r
    return results


@pytest.fixture(scope='module')
def demo():
    return demo_build.demo_install()


@pytest.fixture(scope='module')
def node_results(demo):
    return _run('node', '--demo', str(demo), timeout=600)


@pytest.fixture(scope='module')
def chromium_results(demo):
    reason = harness.browser_skip_reason()
    if reason:
        pytest.skip(reason)
    return _run('chromium', harness.CHROMIUM, '--demo', str(demo), timeout=900)


def _check(results, name):
    assert name in results, f'scenario {name!r} did not run: {sorted(results)}'
    r = results[name]
    why = json.dumps(r, indent=1)
    assert r['ok'], why
    # what every scenario saw: the victim stopped where asked, then was gone
    assert r['facts'].get('gone'), why
    return r


@pytest.mark.parametrize('name', [s['scenario'] for s in SCENARIOS])
def test_node(node_results, name):
    r = _check(node_results, name)
    assert r['facts']['bus'] == 'SharedArrayBuffer'  # Node.js 20: no multi-memory


@pytest.mark.parametrize('name', [s['scenario'] for s in SCENARIOS if not s['nodeOnly']])
def test_chromium(chromium_results, name):
    r = _check(chromium_results, name)
    if not os.environ.get('COLCON_WASM_CHROMIUM'):
        # Debian's Chromium has multi-memory: the bus is a shared WebAssembly.Memory
        assert r['facts']['bus'] == 'WebAssembly.Memory'
