# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
``colcon-wasm export`` (issue 41): the page and its nodes as a static site.

The demo workspace is exported with ``--run`` of its talker and listener,
and the folder is served by Python's ``http.server``, which sends no
cross-origin isolation headers. In Chromium, the site's service worker
isolates the page (one reload), the talker and listener start by
themselves, and the listener hears the talker. Bad input is refused
before anything is written.
"""

import contextlib
import json
import socket
import subprocess
import sys
import time
import urllib.request

import pytest
from served_page import browser_skip_reason
from served_page import CHROMIUM
from served_page import explain_page
from served_page import JS


def _colcon_wasm(*args):
    from pathlib import Path
    return subprocess.run([str(Path(sys.executable).parent / 'colcon-wasm'), *args],
                          capture_output=True, text=True, timeout=600)


@contextlib.contextmanager
def static_server(folder):
    """Serve a folder with Python's http.server on a free loopback port (no isolation headers)."""
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        port = s.getsockname()[1]
    server = subprocess.Popen(
        [sys.executable, '-m', 'http.server', '--bind', '127.0.0.1', '--directory', str(folder),
         str(port)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f'http://127.0.0.1:{port}/'
    try:
        for _ in range(100):
            try:
                with urllib.request.urlopen(url, timeout=1) as response:
                    headers = dict(response.headers)
                break
            except OSError:
                time.sleep(0.1)
        assert 'Cross-Origin-Embedder-Policy' not in headers, headers
        yield url
    finally:
        server.terminate()
        server.wait(10)


@pytest.fixture(scope='module')
def exported(tmp_path_factory):
    import demo_build
    target = tmp_path_factory.mktemp('export') / 'site'
    done = _colcon_wasm('export', str(target), '--install-base', str(demo_build.demo_install()),
                        '--run', 'demo_nodes/talker', '--run', 'demo_nodes/listener')
    assert done.returncode == 0, done.stderr
    return target, done


def test_export_writes_the_page_runtime_executables_and_views(exported):
    target, done = exported
    assert 'Exported 7 executable(s)' in done.stdout, done.stdout
    for name in ('index.html', 'coi_sw.js', 'launcher/app.mjs', 'wasm_js/runtime.mjs',
                 'ws/demo_nodes/lib/demo_nodes/talker.js', 'fs/0/index.html'):
        assert (target / name).is_file(), name
    listing = json.loads((target / 'fs' / '0' / 'index.html').read_text())
    assert 'demo_nodes' in {e['name'] for e in listing['entries']}, listing
    workspace = json.loads((target / 'workspace.json').read_text())
    assert workspace['static'] is True
    assert workspace['autorun'] == ['demo_nodes/talker', 'demo_nodes/listener']
    assert 'launch files are evaluated by serve' in workspace['launch']['problem']


def test_bad_input_is_refused_before_anything_is_written(tmp_path):
    import demo_build
    install = str(demo_build.demo_install())
    busy = tmp_path / 'busy'
    busy.mkdir()
    (busy / 'notes.txt').write_text('mine')
    done = _colcon_wasm('export', str(busy), '--install-base', install)
    assert done.returncode == 1
    assert f"'{busy}' is not empty and holds no earlier export" in done.stderr, done.stderr
    assert sorted(p.name for p in busy.iterdir()) == ['notes.txt']
    fresh = tmp_path / 'fresh'
    done = _colcon_wasm('export', str(fresh), '--install-base', install,
                        '--run', 'demo_nodes/nope')
    assert done.returncode == 1
    assert "there is no executable 'demo_nodes/nope'" in done.stderr, done.stderr
    assert 'demo_nodes/talker' in done.stderr  # the list of what there is
    assert not fresh.exists()


def test_the_exported_demo_runs_from_a_static_host(exported):
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    target, _ = exported
    heard = ('[...colconWasm.session.processes.values()].some((p) => p.exe === "listener" '
             '&& p.log.some((e) => e.text.includes("I heard")))')
    with static_server(target) as url:
        completed = subprocess.run(
            ['node', str(JS / 'page_session.mjs'), json.dumps({
                'url': url, 'chromium': CHROMIUM, 'timeoutMs': 60000, 'steps': [
                    {'until': 'window.crossOriginIsolated && !!navigator.serviceWorker.controller',
                     'save': 'isolated'},
                    {'until': heard, 'save': 'heard'},
                    {'until': '[...colconWasm.session.processes.values()].map((p) => p.exe)'
                              '.sort().join(",")', 'save': 'running'},
                ]})],
            capture_output=True, text=True, timeout=180)
    lines = completed.stdout.strip().splitlines()
    assert lines, completed.stderr[-3000:]
    result = json.loads(lines[-1])
    assert result['ok'], explain_page(result) + completed.stderr[-2000:]
    assert result['saved']['isolated'] is True
    assert result['saved']['running'] == 'listener,talker', result['saved']
    assert not result['pageErrors'], result['pageErrors']
