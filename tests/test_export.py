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
import gzip
import json
import re
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
def static_server(folder, log=None):
    """
    Serve a folder with Python's http.server on a free loopback port (no isolation headers).

    :param log: a file for the server's request log (one ``"GET /path HTTP/1.1" 200`` line
      per request), or None
    """
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        port = s.getsockname()[1]
    server = subprocess.Popen(
        [sys.executable, '-m', 'http.server', '--bind', '127.0.0.1', '--directory', str(folder),
         str(port)], stdout=subprocess.DEVNULL,
        stderr=log.open('w') if log else subprocess.DEVNULL)
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
    runtime = json.loads((target / 'colcon_wasm' / 'manifest.json').read_text())
    assert runtime == {'flags': {'pthread': True, 'pthread_pool_size': 4}}, runtime  # no paths
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
    done = _colcon_wasm('export', str(fresh), '--install-base', install,
                        '--packages-up-to', 'demo_nodes', 'nope_pkg')
    assert done.returncode == 1
    assert '--packages-up-to nope_pkg: no such package' in done.stderr, done.stderr
    assert 'demo_nodes' in done.stderr.split('there are:')[1]
    python_launch = tmp_path / 'talker.launch.py'
    python_launch.write_text('from launch import LaunchDescription\n')
    done = _colcon_wasm('export', str(fresh), '--install-base', install,
                        '--launch', str(python_launch))
    assert done.returncode == 1
    assert "a Python launch file runs Humble's launch on a host" in done.stderr, done.stderr
    done = _colcon_wasm('export', str(fresh), '--install-base', install,
                        '--launch', 'demo_nodes nope.launch.xml')
    assert done.returncode == 1
    assert "package 'demo_nodes' has no launch file 'nope.launch.xml'" in done.stderr
    done = _colcon_wasm('export', str(fresh), '--install-base', install,
                        '--base-url', 'demo/')
    assert done.returncode == 1
    assert '--base-url demo/: give the path the site lives under' in done.stderr, done.stderr
    assert not fresh.exists()


HEARD = ('[...colconWasm.session.processes.values()].some((p) => p.exe === "listener" '
         '&& p.log.some((e) => e.text.includes("I heard")))')
RUNNING = '[...colconWasm.session.processes.values()].map((p) => p.exe).sort().join(",")'
ISOLATED = 'window.crossOriginIsolated && !!navigator.serviceWorker.controller'


def _page(url, steps):
    """Drive the page at ``url`` through ``steps`` (tests/js/page_session.mjs); its result."""
    completed = subprocess.run(
        ['node', str(JS / 'page_session.mjs'), json.dumps({
            'url': url, 'chromium': CHROMIUM, 'timeoutMs': 60000, 'steps': steps})],
        capture_output=True, text=True, timeout=240)
    lines = completed.stdout.strip().splitlines()
    assert lines, completed.stderr[-3000:]
    result = json.loads(lines[-1])
    assert result['ok'], explain_page(result) + completed.stderr[-2000:]
    assert not result['pageErrors'], result['pageErrors']
    return result


def test_the_exported_demo_runs_from_a_static_host(exported):
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    target, _ = exported
    with static_server(target) as url:
        result = _page(url, [{'until': ISOLATED, 'save': 'isolated'},
                             {'until': HEARD, 'save': 'heard'},
                             {'until': RUNNING, 'save': 'running'}])
    assert result['saved']['isolated'] is True
    assert result['saved']['running'] == 'listener,talker', result['saved']


def test_an_exported_launch_file_starts_with_the_page(tmp_path):
    """``--launch``: the demo's XML launch file, planned by the export with its argument."""
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    target = tmp_path / 'site'
    done = _colcon_wasm('export', str(target), '--install-base', str(demo_build.demo_install()),
                        '--launch', 'demo_nodes talker_listener.launch.xml topic:=news')
    assert done.returncode == 0, done.stderr
    planned = json.loads((target / 'workspace.json').read_text())['launch']['planned']
    assert [p['label'] for p in planned[0]['processes']] == ['talker-1', 'listener-2']
    launch = ('[...colconWasm.session.processes.values()].filter((p) => p.kind === "launch")'
              '.map((p) => `${p.label} ${p.state}`).join(",")')
    topics = ('colconWasm.session.graph.topics.filter((t) => t.name === "/news" '
              '&& t.publishers && t.subscribers).length')
    with static_server(target) as url:
        result = _page(url, [{'until': ISOLATED}, {'until': HEARD},
                             {'until': launch, 'save': 'launch'},
                             {'until': topics, 'save': 'news'}])
    assert result['saved']['launch'] == 'launch talker_listener.launch.xml running'
    assert result['saved']['news'] == 1  # the argument remapped chatter to /news


def test_python_nodes_run_in_an_export_with_pyodide(tmp_path):
    """``--python``: Pyodide is copied in; a Python talker talks to the exported listener."""
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    from humble_build import REPO
    pyodide = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'
    assert (pyodide / 'pyodide.asm.wasm').is_file(), f'run npm ci in {pyodide.parent.parent}'
    target = tmp_path / 'site'
    done = _colcon_wasm('export', str(target), '--install-base', str(demo_build.demo_install()),
                        '--run', 'demo_nodes/listener', '--python', str(pyodide))
    assert done.returncode == 0, done.stderr
    assert (target / 'pyodide' / 'pyodide.asm.wasm.gz').is_file()
    with static_server(target) as url:
        result = _page(url, [
            {'until': ISOLATED},
            {'python': 'py_talker', 'file': str(REPO / 'tests/data/pyodide/talker.py')},
            {'until': HEARD.replace('I heard', 'I heard: [Hello from Python: 3]'),
             'timeoutMs': 120000}])
    assert any('Publishing: "Hello from Python' in line
               for line in result['logs']['py_talker']), result['logs']['py_talker'][-5:]


def _requests(log):
    """Drive the page at ``url`` through ``steps`` (js/page_session.mjs); return its result."""
    return re.findall(r'"GET (\S+) HTTP/[\d.]+" \d+', log.read_text())


def test_a_site_under_a_sub_path_downloads_compressed_once(tmp_path):
    """
    ``--base-url /demo/``: the site in a sub-folder of what the host serves.

    A first visit fetches the executables' ``.gz`` forms (http.server
    compresses nothing), never the plain ``.wasm``; a second visit in the same
    browser fetches no executable at all: the service worker keeps each file
    under its hash (files.json).
    """
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    target = tmp_path / 'host' / 'demo'
    done = _colcon_wasm('export', str(target), '--install-base', str(demo_build.demo_install()),
                        '--run', 'demo_nodes/talker', '--run', 'demo_nodes/listener',
                        '--base-url', '/demo/')
    assert done.returncode == 0, done.stderr
    assert 'A first visit downloads' in done.stdout, done.stdout
    assert '<base href="/demo/">' in (target / 'index.html').read_text()
    manifest = json.loads((target / 'files.json').read_text())['files']
    talker = manifest['ws/demo_nodes/lib/demo_nodes/talker.wasm']
    assert gzip.decompress((target / 'ws/demo_nodes/lib/demo_nodes/talker.wasm.gz').read_bytes()) \
        == (target / 'ws/demo_nodes/lib/demo_nodes/talker.wasm').read_bytes()
    assert talker['gz'] < talker['size'] / 2, talker
    log = tmp_path / 'requests.log'
    with static_server(tmp_path / 'host', log) as url:
        result = _page(url + 'demo/', [
            {'until': ISOLATED, 'save': 'isolated'},
            {'until': HEARD, 'save': 'heard'},
            {'goto': url + 'demo/?second-visit'},
            {'until': ISOLATED, 'save': 'isolated_again'},
            {'until': HEARD, 'save': 'heard_again'},
            {'until': RUNNING, 'save': 'running'}])
    assert result['saved']['isolated_again'] is True
    assert result['saved']['running'] == 'listener,talker', result['saved']
    requests = _requests(log)
    second = requests.index('/demo/?second-visit')
    first, again = requests[:second], requests[second:]
    executables = [r for r in first if '/lib/demo_nodes/' in r]
    assert '/demo/ws/demo_nodes/lib/demo_nodes/talker.wasm.gz' in executables, first
    assert not [r for r in executables if r.endswith('.wasm')], executables
    # the worker reads the manifest anew at each visit (its fetch may come before the page's)
    assert requests.count('/demo/files.json') >= 2, requests
    assert not [r for r in again if '.wasm' in r or r.endswith('.js')], again
    assert ' 404 ' not in log.read_text(), log.read_text()  # the runtime's manifest too


PUBLISHER = 'examples_rclcpp_minimal_publisher/publisher_member_function'
SUBSCRIBER = 'examples_rclcpp_minimal_subscriber/subscriber_member_function'
SUBSCRIBER_HEARD = (
    '[...colconWasm.session.processes.values()].some((p) => p.exe === '
    '"subscriber_member_function" && p.log.some((e) => e.text.includes("I heard")))')


def test_a_humble_rclcpp_export_is_served_whole_by_the_static_folder(tmp_path):
    """
    Humble's minimal publisher and subscriber (rclcpp), exported up to them.

    Every file the page asks for is in the folder (no 404), the subscriber
    hears the publisher, and a second visit fetches no program again. A
    package the selection leaves out is neither listed nor in the views.
    """
    from rclcpp_build import rclcpp_build
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    build = rclcpp_build()
    target = tmp_path / 'site'
    done = _colcon_wasm(
        'export', str(target), '--install-base', str(build.install),
        '--packages-up-to', PUBLISHER.split('/')[0], SUBSCRIBER.split('/')[0],
        '--run', PUBLISHER, '--run', SUBSCRIBER)
    assert done.returncode == 0, done.stderr
    workspace = json.loads((target / 'workspace.json').read_text())
    listed = {p['name'] for p in workspace['packages']}
    assert {'examples_rclcpp_minimal_publisher', 'examples_rclcpp_minimal_subscriber',
            'rclcpp_components'} <= listed, listed
    assert 'examples_rclcpp_minimal_timer' not in listed
    assert not (target / 'fs' / '0' / 'examples_rclcpp_minimal_timer').exists()
    root = json.loads((target / 'fs' / '0' / 'index.html').read_text())
    assert 'examples_rclcpp_minimal_timer' not in {e['name'] for e in root['entries']}
    assert not list((target / 'fs').rglob('*.a')), 'static libraries in the views'
    left_out_file = (build.install / 'examples_rclcpp_minimal_timer' / 'share'
                     / 'examples_rclcpp_minimal_timer' / 'package.xml')
    assert left_out_file.is_file()
    log = tmp_path / 'requests.log'
    with static_server(target, log) as url:
        _page(url, [
            {'until': ISOLATED}, {'until': SUBSCRIBER_HEARD},
            {'goto': url + '?second-visit'}, {'until': ISOLATED},
            {'until': SUBSCRIBER_HEARD},
            # a file of a package left out: ENOENT, and the log says which option includes it
            {'start': 'reader', 'pkg': PUBLISHER.split('/')[0], 'exe': PUBLISHER.split('/')[1],
             'args': ['--ros-args', '--params-file', str(left_out_file)]},
            {'wait': 'reader', 'text': '--packages-select examples_rclcpp_minimal_timer'}])
    missing = [line for line in log.read_text().splitlines()
               if ' 404 ' in line and 'examples_rclcpp_minimal_timer' not in line]
    assert not missing, missing
    requests = _requests(log)
    again = requests[requests.index('/?second-visit'):]
    assert not [r for r in again if '.wasm' in r or r.endswith('.js')], again
