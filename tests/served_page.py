# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The launcher page of a real `colcon-wasm serve`, driven in headless Chromium.

    with ServedPage(install) as page:
        result = page.run([
            {'start': 'talker', 'pkg': 'demo_nodes', 'exe': 'talker', 'args': []},
            {'wait': 'talker', 'text': 'Publishing'}])
    assert result['ok'], explain_page(result)

Steps are those of tests/js/page_session.mjs: the page's own session starts
the executables, as a user pressing Run does.
"""

import json
import os
from pathlib import Path
import subprocess
import sys

from humble_build import REPO
import pytest

JS = REPO / 'tests' / 'js'
CHROMIUM = os.environ.get('COLCON_WASM_CHROMIUM', '/usr/bin/chromium')


def browser_skip_reason():
    """Why a page cannot be driven here, or None."""
    if not Path(CHROMIUM).exists():
        return f'Chromium not found at {CHROMIUM} (set COLCON_WASM_CHROMIUM)'
    if not (JS / 'node_modules' / 'playwright-core').is_dir():
        return f'playwright-core missing: run `npm ci` in {JS}'
    return None


class ServedPage:
    """`colcon-wasm serve` of an install space, for the length of a with block."""

    def __init__(self, install, *, env=None, args=()):
        """Serve `install` (its underlays come from its marker) on a free port; `args` to serve."""
        reason = browser_skip_reason()
        if reason:
            pytest.skip(reason)
        self.install = Path(install)
        self.env = dict(os.environ, **(env or {}))
        self.process = None
        self.url = None
        self.args = [str(a) for a in args]
        self.rosbridge_url = None
        self.foxglove_url = None

    def __enter__(self):  # noqa: D105
        self.process = subprocess.Popen(
            [str(Path(sys.executable).parent / 'colcon-wasm'), 'serve', '--install-base',
             str(self.install), '--port', '0', *self.args],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=self.env)
        for line in self.process.stdout:
            if line.startswith('rosbridge relay: '):
                self.rosbridge_url = line.split()[2]
            if line.startswith('foxglove server: '):
                self.foxglove_url = line.split()[2]
            if line.startswith('Open '):
                self.url = line.split()[1]
                break
        if self.url is None:
            raise AssertionError('colcon-wasm serve did not start: ' + self.process.stderr.read())
        return self

    def __exit__(self, *exc):  # noqa: D105
        self.process.terminate()
        self.process.wait(10)

    def run(self, steps, timeout_ms=90000, query=''):
        """Run page_session.mjs steps in a new page (its URL + ``query``); returns its result."""
        completed = subprocess.run(
            ['node', str(JS / 'page_session.mjs'), json.dumps(
                {'url': self.url + query, 'chromium': CHROMIUM, 'steps': steps,
                 'timeoutMs': timeout_ms})],
            capture_output=True, text=True, timeout=timeout_ms / 1000 + 120)
        lines = completed.stdout.strip().splitlines()
        assert lines, f'page_session.mjs printed nothing: {completed.stderr[-3000:]}'
        return json.loads(lines[-1])


def explain_page(result):
    """Describe a page result for an assertion message."""
    text = [f"error: {result.get('error')}", f"states: {result.get('states')}"]
    for name, lines in (result.get('logs') or {}).items():
        text += [f'[{name}] {line}' for line in lines[-25:]]
    text += result.get('pageErrors') or []
    return '\n'.join(text)


def param_talker_tab(done_text):
    """
    Return the steps of a page of rclcpp nodes on serve's relay: param_talker, listener.

    The page joins the relay, then runs until its listener hears ``done_text``
    on /chatter (what a test's clients publish once they are done).
    """
    probe = {'pkg': 'rmw_wasm_cpp_node_tests', 'exe': 'probe'}
    return [
        dict(probe, start='talker', args=['param_talker']),
        dict(probe, start='listener', args=['listener']),
        {'until': "colconWasm.session.bridge && colconWasm.session.bridge.state === 'connected' "
                  '&& colconWasm.session.bridge.relay'},
        {'wait': 'listener', 'text': f'HEARD {done_text}', 'timeoutMs': 150000},
    ]
