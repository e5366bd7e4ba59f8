# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The `.js` + `.wasm` pair loads in a browser worker (headless Chromium).

The fixture's `args_env` executable runs in a dedicated Web Worker of a page
served with COOP/COEP (SharedArrayBuffer for pthreads). The injected glue
hooks post its output and exit code to the page. Chromium is driven over the
DevTools protocol on a pipe (`--remote-debugging-pipe`); the test awaits the
page's promise, it does not poll.
"""

import fcntl
import functools
import http.server
import json
import os
from pathlib import Path
import select
import shutil
import subprocess
import tempfile
import threading
import time

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
import pytest

CHROMIUM = os.environ.get('COLCON_WASM_CHROMIUM', '/usr/bin/chromium')

PAGE = """<!doctype html><meta charset="utf-8"><title>colcon-wasm worker</title>
<script>
window.result = new Promise((resolve) => {
  const base = new URL('bin/', location.href).href;
  // a bootstrap worker sets Module, then loads the glue; pthread workers
  // must load the glue itself (mainScriptUrlOrBlob), not this bootstrap
  const boot = `var Module = {arguments: ['one', 'two words'],
                              env: {CALC_GREETING: 'from the page'},
                              locateFile: (p) => '${base}' + p,
                              mainScriptUrlOrBlob: '${base}args_env.js'};
                importScripts('${base}args_env.js');`;
  const worker = new Worker(URL.createObjectURL(
    new Blob([boot], {type: 'text/javascript'})));
  const lines = [];
  worker.onmessage = (event) => {
    const m = event.data;
    if (m.colconWasm === 'log') lines.push(m.stream + ':' + m.text);
    if (m.colconWasm === 'exit') resolve({lines, code: m.code,
                                          isolated: crossOriginIsolated});
  };
  worker.onerror = (e) => resolve({error: String(e.message)});
});
</script>"""


class _Handler(http.server.SimpleHTTPRequestHandler):
    def end_headers(self):
        self.send_header('Cross-Origin-Opener-Policy', 'same-origin')
        self.send_header('Cross-Origin-Embedder-Policy', 'require-corp')
        super().end_headers()

    def log_message(self, *args):
        pass


def _pipe_fds(read_fd, write_fd):
    """In the child: Chromium reads commands on fd 3, writes on fd 4."""
    high_read = fcntl.fcntl(read_fd, fcntl.F_DUPFD, 10)
    high_write = fcntl.fcntl(write_fd, fcntl.F_DUPFD, 10)
    os.dup2(high_read, 3)
    os.dup2(high_write, 4)


class DevToolsPipe:
    """The DevTools protocol over Chromium's `--remote-debugging-pipe`."""

    def __init__(self, profile):
        """Start headless Chromium on a blank page."""
        to_chrome_read, self._write_fd = os.pipe()
        self._read_fd, from_chrome_write = os.pipe()
        self.process = subprocess.Popen(
            [CHROMIUM, '--headless', '--no-sandbox', '--disable-gpu',
             '--disable-quic', '--no-first-run',
             '--disable-background-networking', '--disable-component-update',
             '--disable-sync', f'--user-data-dir={profile}',
             '--remote-debugging-pipe', 'about:blank'],
            close_fds=False, stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            preexec_fn=functools.partial(
                _pipe_fds, to_chrome_read, from_chrome_write))
        os.close(to_chrome_read)
        os.close(from_chrome_write)
        self._next_id = 0
        self._buffer = b''

    def call(self, method, session=None, timeout=120, **params):
        """Send a command and wait for its answer (events are skipped)."""
        self._next_id += 1
        message = {'id': self._next_id, 'method': method, 'params': params}
        if session:
            message['sessionId'] = session
        os.write(self._write_fd, json.dumps(message).encode() + b'\0')
        deadline = time.monotonic() + timeout
        while True:
            while b'\0' in self._buffer:
                raw, self._buffer = self._buffer.split(b'\0', 1)
                answer = json.loads(raw)
                if answer.get('id') == self._next_id:
                    assert 'error' not in answer, answer
                    return answer['result']
            left = deadline - time.monotonic()
            ready, _, _ = select.select([self._read_fd], [], [], max(left, 0))
            assert ready, f'no answer to {method} from Chromium in {timeout} s'
            chunk = os.read(self._read_fd, 65536)
            assert chunk, 'Chromium closed the DevTools pipe'
            self._buffer += chunk

    def close(self):
        """Stop Chromium (all its processes) and wait for it."""
        try:
            self.call('Browser.close', timeout=20)
            self.process.wait(timeout=30)
        except (AssertionError, OSError, subprocess.TimeoutExpired):
            self.process.kill()
            self.process.wait()
        os.close(self._write_fd)
        os.close(self._read_fd)


@pytest.fixture
def served_build(tmp_path):
    """Build ws_basic with --wasm and serve its calc_app prefix."""
    if not shutil.which(CHROMIUM) and not Path(CHROMIUM).is_file():
        pytest.skip(f'no Chromium at {CHROMIUM} (set COLCON_WASM_CHROMIUM)')
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'calc_app')
    prefix = ws / 'install_wasm' / 'calc_app'
    (prefix / 'index.html').write_text(PAGE)
    server = http.server.ThreadingHTTPServer(
        ('127.0.0.1', 0), functools.partial(_Handler, directory=str(prefix)))
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f'http://127.0.0.1:{server.server_address[1]}/index.html'
    server.shutdown()
    server.server_close()


def test_executable_runs_in_a_browser_worker(served_build):
    # Chromium's helper processes may still touch the profile while exiting
    with tempfile.TemporaryDirectory(ignore_cleanup_errors=True) as profile:
        chrome = DevToolsPipe(profile)
        try:
            targets = chrome.call('Target.getTargets')['targetInfos']
            page = next(t for t in targets if t['type'] == 'page')
            session = chrome.call('Target.attachToTarget',
                                  targetId=page['targetId'],
                                  flatten=True)['sessionId']
            # returns once the new document is committed
            chrome.call('Page.navigate', session=session, url=served_build)
            answer = chrome.call(
                'Runtime.evaluate', session=session,
                expression='new Promise((ok) => { const go = () => '
                           'window.result ? window.result.then(ok) : '
                           "addEventListener('load', () => "
                           'window.result.then(ok)); go(); })',
                awaitPromise=True, returnByValue=True, timeout=60000)
        finally:
            chrome.close()
    value = answer['result'].get('value')
    assert value and 'error' not in value, answer
    assert value['isolated'] is True
    assert value['code'] == 2
    assert value['lines'] == [
        'stdout:arg[1]=one', 'stdout:arg[2]=two words',
        'stdout:CALC_GREETING=from the page']
