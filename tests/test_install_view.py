# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Programs read their install spaces, read-only, at their real paths.

A C++ probe (tests/fixtures/fs_probe, built by the real `colcon build
--wasm`) finds its prefix through AMENT_PREFIX_PATH as ament_index_cpp does,
lists, stats and reads its share folder (text, binary, from a thread too),
and checks that a missing file is ENOENT and that writes fail with EROFS. It
runs through `colcon-wasm run` and `launch` (Node.js) and the page of
`colcon-wasm serve` (Chromium); what it prints is compared with the files.
"""

import json
import os
from pathlib import Path
import shutil
import subprocess
import sys
import threading
from urllib.parse import quote

from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch import NodeProcess
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.server import make_server
from core import harness
import pytest

REPO = Path(__file__).resolve().parents[1]
FIXTURE = REPO / 'tests' / 'fixtures' / 'fs_probe'
JS = REPO / 'tests' / 'js'
LAUNCHER = REPO / 'templates' / 'launcher'
RUNTIME = REPO / 'packages' / 'wasm_js' / 'src'
COLCON_WASM = Path(sys.executable).parent / 'colcon-wasm'
DATA = 'share/fs_probe/data'


@pytest.fixture(scope='module')
def install():
    """Build the probe (once, cached like the core tests' build); return its install space."""
    build = harness.build(source=FIXTURE, package='fs_probe')
    base = build.workspace / 'install_wasm'
    markers = sorted(p.name for p in base.glob('*/share/ament_index/resource_index/packages/*'))
    assert markers == ['fs_probe'], markers  # the expected AMENT_PREFIX_PATH below relies on it
    return base


@pytest.fixture(scope='module')
def overlay(install, tmp_path_factory):
    """Write an install base over the probe's: its own fs_probe share, and one more package."""
    base = tmp_path_factory.mktemp('overlay') / 'install_wasm'
    shutil.copytree(install / 'fs_probe' / 'share', base / 'fs_probe' / 'share')
    (base / 'fs_probe' / 'share' / 'fs_probe' / 'data' / 'hello.txt').write_text(
        'Hello from the overlay.\n')
    marker = base / 'other_pkg' / 'share' / 'ament_index' / 'resource_index' / 'packages'
    marker.mkdir(parents=True)
    (marker / 'other_pkg').write_text('')
    return base


def _fnv1a64(data):
    value = 14695981039346656037
    for byte in data:
        value = ((value ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return f'{value:016x}'


def expected_output(prefix, *, ament_prefix_path, resources):
    """Compute from the real files what fs_probe prints for a prefix."""
    prefix = Path(prefix)

    def listing(relative):
        names = sorted(f"{p.name}:{'d' if p.is_dir() else 'f'}"
                       for p in (prefix / relative).iterdir())
        return f"LIST {relative} {','.join(names)} errno=OK"

    def stat(relative):
        info = (prefix / relative).stat()
        kind = 'd' if (prefix / relative).is_dir() else 'f'
        return (f'STAT {relative} size={info.st_size} mode={info.st_mode & 0o7777:o} '
                f'mtime={int(info.st_mtime)} type={kind}')

    def lines(relative):
        text = (prefix / relative).read_text(encoding='utf-8')
        return [f'LINE {relative} {line}' for line in text.split('\n')[:-1]]

    blob = (prefix / DATA / 'blob.bin').read_bytes()
    first_yaml_line = (prefix / DATA / 'sub' / 'nested.yaml').read_text().split('\n')[0]
    return [
        f'AMENT_PREFIX_PATH {ament_prefix_path}',
        f"RESOURCES packages {','.join(resources)}",
        f'PREFIX {prefix}',
        listing(DATA),
        listing('share/fs_probe'),
        stat(DATA + '/hello.txt'),
        stat(DATA + '/blob.bin'),
        stat(DATA),
        *lines(DATA + '/hello.txt'),
        f'BINARY {DATA}/blob.bin size={len(blob)} fnv1a64={_fnv1a64(blob)}',
        f'BINARY_AT {DATA}/blob.bin offset=3000 {blob[3000:3016].hex()}',
        f'IFSTREAM {DATA}/sub/nested.yaml {first_yaml_line} good=1',
        'MISSING fopen errno=ENOENT',
        'MISSING stat errno=ENOENT',
        'MISSING opendir errno=ENOENT',
        *[f'WRITE {what} errno=EROFS' for what in (
            'fopen_w_existing', 'fopen_a_existing', 'fopen_w_new', 'open_rdwr', 'mkdir',
            'unlink', 'rename', 'chmod', 'truncate')],
        stat(DATA + '/hello.txt'),
        *lines(DATA + '/hello.txt'),
        f'THREAD {DATA}/blob.bin bytes={len(blob)} errno=OK',
        'DONE',
    ]


def _of(output, label):
    """Return the lines a process printed, from launch-style output (``[label] ...``)."""
    tag = f'[{label}] '
    return [line[len(tag):] for line in output.splitlines() if line.startswith(tag)]


def _colcon_wasm(*args, env=None, timeout=120):
    environ = {k: v for k, v in os.environ.items() if k != 'COLCON_WASM_PREFIX_PATH'}
    return subprocess.run([str(COLCON_WASM)] + [str(a) for a in args], capture_output=True,
                          text=True, timeout=timeout, env=dict(environ, **(env or {})))


def test_run_sees_its_install_space_in_node(install):
    done = _colcon_wasm('run', '--install-base', install, 'fs_probe', 'fs_probe')
    assert done.returncode == 0, done.stdout + done.stderr
    prefix = install / 'fs_probe'
    assert _of(done.stdout, 'fs_probe-1') == expected_output(
        prefix, ament_prefix_path=prefix, resources=['fs_probe']), done.stdout + done.stderr


def test_launch_keeps_an_ament_prefix_path_the_user_set(install, tmp_path):
    prefix = install / 'fs_probe'
    launch = tmp_path / 'probe.launch.xml'
    launch.write_text(
        '<launch>\n'
        f'  <node pkg="fs_probe" exec="fs_probe" args="{prefix}">\n'
        '    <env name="AMENT_PREFIX_PATH" value="/custom/prefix"/>\n'
        '  </node>\n'
        '  <node pkg="fs_probe" exec="fs_probe"/>\n'
        '</launch>\n')
    done = _colcon_wasm('launch', '--install-base', install, launch)
    assert done.returncode == 0, done.stdout + done.stderr
    # the user's value is kept; the view is there all the same (the prefix is in argv)
    assert _of(done.stdout, 'fs_probe-1') == expected_output(
        prefix, ament_prefix_path='/custom/prefix', resources=['fs_probe'])
    assert _of(done.stdout, 'fs_probe-2') == expected_output(
        prefix, ament_prefix_path=prefix, resources=['fs_probe'])


def test_run_sees_the_underlays_too(install, tmp_path):
    overlay = tmp_path / 'install_wasm'
    marker = overlay / 'other_pkg' / 'share' / 'ament_index' / 'resource_index' / 'packages'
    marker.mkdir(parents=True)
    (marker / 'other_pkg').write_text('')
    # fs_probe is the underlay's (COLCON_WASM_PREFIX_PATH, as a sourced setup.sh sets it)
    done = _colcon_wasm('run', '--install-base', overlay, 'fs_probe', 'fs_probe',
                        env={'COLCON_WASM_PREFIX_PATH': str(install)})
    assert done.returncode == 0, done.stdout + done.stderr
    prefixes = [overlay / 'other_pkg', install / 'fs_probe']
    assert _of(done.stdout, 'fs_probe-1') == expected_output(
        install / 'fs_probe', ament_prefix_path=':'.join(map(str, prefixes)),
        resources=['fs_probe', 'other_pkg']), done.stdout + done.stderr


def test_several_bases_overlay_first_in_node(install, overlay, capfd):
    plan = LaunchPlan([NodeProcess('fs_probe', 'fs_probe')])
    # bases given explicitly (the install space alone has no underlays)
    status = execute(plan, install_base=str(install), bases=[overlay, install],
                     command='test')
    out, err = capfd.readouterr()
    assert status == 0, out + err
    prefixes = [overlay / 'fs_probe', overlay / 'other_pkg', install / 'fs_probe']
    assert _of(out, 'fs_probe-1') == expected_output(
        overlay / 'fs_probe', ament_prefix_path=':'.join(map(str, prefixes)),
        resources=['fs_probe', 'other_pkg']), out + err


def test_a_runtime_without_views_is_reported(install, tmp_path):
    # an install space whose wasm_js was built before views existed
    base = tmp_path / 'install_wasm'
    base.mkdir()
    os.symlink(install / 'fs_probe', base / 'fs_probe')
    src = base / 'wasm_js' / 'share' / 'wasm_js' / 'src'
    shutil.copytree(RUNTIME, src)
    for name, what, instead in (('runtime.mjs', 'static get features()', 'static get no()'),
                                ('program_worker.mjs', 'mountReadOnlyViews(msg.mounts,', '(')):
        text = (src / name).read_text()
        assert what in text
        (src / name).write_text(text.replace(what, instead))
    done = _colcon_wasm('run', '--install-base', base, 'fs_probe', 'fs_probe')
    assert 'predates read-only views: the processes do not see their install space' in \
        done.stderr, done.stderr
    assert "rebuild it with 'colcon build --wasm --packages-select wasm_js'" in done.stderr
    assert _of(done.stdout, 'fs_probe-1')[-1] == 'PREFIX none', done.stdout
    assert done.returncode == 1


# ------------------------------------------------------------------ Chromium


def _browser_or_skip():
    reason = harness.browser_skip_reason()
    if reason:
        pytest.skip(reason)


def _run_page(url):
    done = subprocess.run(
        ['node', str(JS / 'page_run.mjs'), json.dumps({'url': url, 'chromium': harness.CHROMIUM})],
        cwd=str(JS), capture_output=True, text=True, timeout=180)
    lines = [line for line in done.stdout.splitlines() if line.startswith('{')]
    assert lines, 'page_run.mjs printed nothing: ' + done.stderr[-3000:]
    result = json.loads(lines[-1])
    assert done.returncode == 0 and not result['pageErrors'], result
    return result['processes']


def _stdout_of(process):
    return [e['text'] for e in process['log'] if e['stream'] == 'stdout']


def test_page_program_sees_its_install_space_in_chromium(install):
    _browser_or_skip()
    serve = subprocess.Popen([str(COLCON_WASM), 'serve', '--install-base', str(install),
                              '--port', '0'], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True)
    try:
        url = next((line.split()[1] for line in serve.stdout if line.startswith('Open ')), None)
        assert url, 'colcon-wasm serve did not start: ' + serve.stderr.read()
        assert url.startswith('http://127.0.0.1:')
        [process] = _run_page(url + '?run=fs_probe/fs_probe')
    finally:
        serve.terminate()
        serve.wait(10)
    assert process['state'] == 'exited', process
    prefix = install / 'fs_probe'
    assert _stdout_of(process) == expected_output(
        prefix, ament_prefix_path=prefix, resources=['fs_probe'])


@pytest.fixture
def counted_server(install, overlay):
    """Serve two bases with the server of colcon-wasm serve, recording each /fs/ request."""
    server = make_server(InstallSpace(install), host='127.0.0.1', port=0,
                         launcher_dir=LAUNCHER, runtime_dir=RUNTIME, runtime_origin='test',
                         page_modules_dir=RUNTIME, bases=[overlay, install])
    requests = []
    route = server.site.route

    def recording_route(segments, query=None, directory=False):
        if segments and segments[0] == 'fs':
            kind = 'walk' if (query or {}).get('walk') else 'list' if directory else 'read'
            requests.append((kind, '/'.join(segments[1:])))
        return route(segments, query, directory)

    server.site.route = recording_route
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield server, requests
    server.shutdown()
    server.server_close()
    thread.join(10)


def test_page_views_are_lazy_cached_and_layered_in_chromium(install, overlay, counted_server):
    _browser_or_skip()
    server, requests = counted_server
    url = server.url
    # Given its prefix in argv, a program that reads nothing of the views asks nothing.
    [process] = _run_page(url + '?run=' + quote('fs_probe/fs_probe /nowhere'))
    assert 'PREFIX none' in _stdout_of(process), process
    assert requests == []
    [process] = _run_page(url + '?run=fs_probe/fs_probe')
    assert process['state'] == 'exited', process
    prefixes = [overlay / 'fs_probe', overlay / 'other_pkg', install / 'fs_probe']
    assert _stdout_of(process) == expected_output(
        overlay / 'fs_probe', ament_prefix_path=':'.join(map(str, prefixes)),
        resources=['fs_probe', 'other_pkg'])
    # each file fetched once (hello.txt is read three times, from two streams)
    assert sorted(r for r in requests if r[0] == 'read') == [
        ('read', f'0/fs_probe/{DATA}/{name}')
        for name in ('blob.bin', 'hello.txt', 'sub/nested.yaml')], requests
    # directories come in walks along the paths looked up, not one request each (those
    # would be 23 here): one into each base's package index (base 0's brings other_pkg's
    # too), one to data/, one to data/sub/
    listings = [r for r in requests if r[0] != 'read']
    assert len(listings) <= 4 and len(set(listings)) == len(listings), requests
    # the underlay's fs_probe is shadowed: only its package index is looked at
    assert not [r for r in requests if r[1].startswith('1/fs_probe/share/fs_probe')], requests
