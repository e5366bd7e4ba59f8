# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
Run scenarios of ROS executables in Node.js and in headless Chromium.

A scenario (tests/rmw/web/scenario.mjs) starts executables on one wasm_js
Runtime, waits for log lines, exits and graph changes, stops workers, and
reports every log line with its severity. The same scenario runs in Node.js
worker_threads (tests/rmw/run_scenario.mjs) and in a page of headless
Chromium served with COOP/COEP (tests/rmw/browser_scenario.mjs, one browser
per test session).

    platform = Platform('node', build)       # or 'chromium'
    report = platform.run([
        {'spawn': 'talker', 'exe': platform.exe('examples_rclcpp_minimal_publisher',
                                                'publisher_member_function')},
        {'wait': 'talker', 'text': 'Publishing', 'count': 3}])
    assert report['ok'], explain(report)
"""

import atexit
import json
import os
from pathlib import Path
import shutil
import subprocess
import tempfile

from humble_build import REPO
import pytest

HERE = REPO / 'tests' / 'rmw'
CHROMIUM = os.environ.get('COLCON_WASM_CHROMIUM', '/usr/bin/chromium')
PLAYWRIGHT = REPO / 'tests' / 'js' / 'node_modules' / 'playwright-core'

_browsers = {}


def browser_skip_reason():
    """Why the browser scenarios cannot run here, or None."""
    if not Path(CHROMIUM).exists():
        return f'Chromium not found at {CHROMIUM} (set COLCON_WASM_CHROMIUM)'
    if not PLAYWRIGHT.is_dir():
        return f'playwright-core missing: run `npm ci` in {PLAYWRIGHT.parents[1]}'
    return None


class Browser:
    """One headless Chromium serving an install space (and extra folders)."""

    def __init__(self, install, routes=()):
        """Start the browser; `routes` are extra ('/prefix/', folder) pairs to serve."""
        self.process = subprocess.Popen(
            ['node', str(HERE / 'browser_scenario.mjs'), str(install)] +
            [f'{prefix}={folder}' for prefix, folder in routes],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        hello = self.process.stdout.readline()
        assert hello, 'browser_scenario.mjs exited at start-up'
        self.base = json.loads(hello)['base']
        self.next_id = 0

    def run(self, scenario):
        """Run a scenario in a new page; returns its report."""
        return self._send({'scenario': scenario})

    def call(self, page, function, arg):
        """Open a page and return `await window[function](arg)`."""
        return self._send({'page': page, 'call': function, 'arg': arg})

    def _send(self, message):
        self.next_id += 1
        self.process.stdin.write(json.dumps({'id': self.next_id, **message}) + '\n')
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        assert line, 'browser_scenario.mjs exited'
        reply = json.loads(line)
        assert 'error' not in reply, reply['error']
        return reply['result']

    def close(self):
        """Stop the browser and the server."""
        if self.process.poll() is None:
            self.process.stdin.close()
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()


@atexit.register
def close_browsers():
    """Stop the session's browsers (at exit)."""
    for browser in _browsers.values():
        browser.close()
    _browsers.clear()


class Platform:
    """Where scenarios run: 'node' or 'chromium', on the executables of one build."""

    def __init__(self, name, build):
        """Prepare a platform; skips the test when Chromium cannot run here."""
        self.name = name
        self.install = build.install
        if name == 'chromium':
            reason = browser_skip_reason()
            if reason:
                pytest.skip(reason)
            key = str(self.install)
            if key not in _browsers:
                _browsers[key] = Browser(self.install)
            self._browser = _browsers[key]

    def exe(self, package, name):
        """Get how this platform names an installed executable (a path or a URL)."""
        from colcon_wasm.launch.install_space import InstallSpace
        from colcon_wasm.launch.install_space import InstallSpaceError
        try:
            path = InstallSpace(self.install, underlays=[]).executable(package, name).js
        except InstallSpaceError as e:
            raise AssertionError(f'{package}/{name} was not built: {e}') from e
        if self.name == 'node':
            return str(path)
        return f'{self._browser.base}/install/{path.relative_to(self.install).as_posix()}'

    def view(self):
        """
        Get what `colcon-wasm run` gives a program in Node.js, for a spawn step.

        That is read-only views of the install bases, and AMENT_PREFIX_PATH.
        """
        from colcon_wasm.launch.install_space import InstallSpace
        from colcon_wasm.launch.install_view import ament_prefixes
        from colcon_wasm.launch.install_view import view_bases
        from colcon_wasm.launch.install_view import view_mounts
        assert self.name == 'node', 'the scenario page serves no views: use tests/served_page.py'
        bases = view_bases(InstallSpace(self.install))
        return {'mounts': view_mounts(bases),
                'env': {'AMENT_PREFIX_PATH': ':'.join(ament_prefixes(bases))}}

    def run(self, steps, runtime=None, timeout=180):
        """Run the steps (see tests/rmw/web/scenario.mjs) and return the report."""
        scenario = {'runtime': runtime or {}, 'steps': steps}
        if self.name == 'chromium':
            return self._browser.run(scenario)
        with tempfile.TemporaryDirectory() as folder:
            path = Path(folder) / 'scenario.json'
            path.write_text(json.dumps(scenario))
            runtime_module = self.install / 'wasm_js' / 'share' / 'wasm_js' / 'src' / 'runtime.mjs'
            completed = subprocess.run(
                ['node', str(HERE / 'run_scenario.mjs'), str(runtime_module), str(path)],
                capture_output=True, text=True, timeout=timeout)
        assert completed.returncode == 0 and completed.stdout.strip(), \
            f'run_scenario.mjs failed ({completed.returncode}):\n{completed.stderr[-4000:]}'
        return json.loads(completed.stdout.splitlines()[-1])


def lines(report, name, severity=None):
    """Get the log texts of one process (optionally of one severity)."""
    return [entry['text'] for entry in report['logs']
            if entry['name'] == name and (severity is None or entry['severity'] == severity)]


def explain(report):
    """Describe a report for an assertion message: the error and the last log lines."""
    tail = '\n'.join(f"  [{e['name']}] {e['severity']}: {e['text']}" for e in report['logs'][-40:])
    console = '\n'.join(report.get('console', [])[-20:])
    return f"{report.get('error')}\nexits: {report.get('exits')}\nlogs:\n{tail}\n{console}"


def have_node():
    """Check that Node.js is on PATH."""
    return shutil.which('node') is not None
