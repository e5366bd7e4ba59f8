# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The HTTP server of colcon-wasm serve: headers, MIME, compression, refusals, load."""

from concurrent.futures import ThreadPoolExecutor
import gzip
import hashlib
import http.client
import json
import os
from pathlib import Path
import socket
import subprocess
import sys
import threading
import urllib.request

from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.server import find_runtime
from colcon_wasm.server import make_server
from colcon_wasm.server import ServeError
import pytest

REPO = Path(__file__).resolve().parents[1]
LAUNCHER = REPO / 'templates' / 'launcher'


def _file(path, data):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    return {'path': None, 'size': len(data), 'gzip_size': len(gzip.compress(data)),
            'sha256': hashlib.sha256(data).hexdigest()}


@pytest.fixture(scope='module')
def install(tmp_path_factory):
    """Write an isolated install space with one manifest, and a secret beside it."""
    root = tmp_path_factory.mktemp('ws')
    base = root / 'install_wasm'
    prefix = base / 'demo_nodes'
    lib = prefix / 'lib' / 'demo_nodes'
    wasm = b'\0asm\1\0\0\0' + bytes(range(256)) * 64
    files = []
    for name, data, role in (('talker.js', b'// glue\n' + b'var x = 1;\n' * 300, 'js'),
                             ('talker.wasm', wasm, 'wasm'),
                             ('talker.worker.js', b'// worker\n', 'worker')):
        entry = _file(lib / name, data)
        entry['path'] = 'lib/demo_nodes/' + name
        entry['role'] = role
        files.append(entry)
    (lib / 'secret.txt').write_text('not in the manifest')
    (root / 'outside.txt').write_text('outside the install space')
    os.symlink(root / 'outside.txt', lib / 'escape.js')
    files.append({'path': 'lib/demo_nodes/escape.js', 'role': 'js', 'size': 0})
    manifest = {
        'schema': 1, 'package': 'demo_nodes', 'package_version': '0.1.0',
        'executables': [
            {'name': 'talker', 'js': 'lib/demo_nodes/talker.js', 'files': files[:3],
             'uses_bus': True, 'pthread': True},
            {'name': 'escape', 'js': 'lib/demo_nodes/escape.js', 'files': files[3:],
             'uses_bus': True, 'pthread': False},
        ]}
    share = prefix / 'share' / 'demo_nodes' / 'colcon_wasm'
    share.mkdir(parents=True)
    (share / 'manifest.json').write_text(json.dumps(manifest))
    types = base / 'demo_interfaces' / 'share' / 'demo_interfaces' / 'colcon_wasm'
    types.mkdir(parents=True)
    (types / 'types.json').write_text(json.dumps({'schema': 1, 'package': 'demo_interfaces',
                                                  'messages': {}, 'services': {},
                                                  'actions': {}}))
    runtime = root / 'runtime'
    runtime.mkdir()
    (runtime / 'index.mjs').write_text("import { y } from './dep.mjs';\n"
                                       + 'export const x = 1;\n' * 100)
    (runtime / 'dep.mjs').write_text(
        "export { z } from './page/deep.mjs';\nexport const y = 2;\n")
    (runtime / 'page').mkdir()
    (runtime / 'page' / 'deep.mjs').write_text('export const z = 3;\n')
    (runtime / 'index.mjs.gz').write_bytes(gzip.compress(b'precompressed'))
    (runtime / 'sub').mkdir()
    os.symlink('/etc/hostname', runtime / 'link_out.mjs')
    (runtime / 'cdr.mjs').write_text('// stale: from an old build\n')
    page_modules = root / 'page_modules'
    (page_modules / 'page').mkdir(parents=True)
    (page_modules / 'cdr.mjs').write_text('// the page version\n')
    (page_modules / 'page' / 'deep.mjs').write_text('export const z = 4;\n')
    return base, runtime, page_modules


@pytest.fixture(scope='module')
def server(install):
    base, runtime, page_modules = install
    srv = make_server(InstallSpace(base), host='127.0.0.1', port=0, launcher_dir=LAUNCHER,
                      runtime_dir=runtime, runtime_origin='test', page_modules_dir=page_modules)
    thread = threading.Thread(target=srv.serve_forever, daemon=True)
    thread.start()
    yield srv
    srv.shutdown()
    srv.server_close()
    thread.join(10)


def _get(server, path, headers=None, method='GET'):
    connection = http.client.HTTPConnection(*server.server_address[:2], timeout=30)
    try:
        connection.putrequest(method, path, skip_accept_encoding=True)
        for name, value in (headers or {}).items():
            connection.putheader(name, value)
        connection.endheaders()
        response = connection.getresponse()
        return response.status, dict(response.getheaders()), response.read()
    finally:
        connection.close()


@pytest.mark.parametrize('path', [
    '/', '/workspace.json', '/launcher/launcher.css', '/wasm_js/index.mjs',
    '/ws/demo_nodes/lib/demo_nodes/talker.wasm', '/nope', '/wasm_js/../x'])
def test_isolation_headers_on_every_response(server, path):
    status, headers, _ = _get(server, path)
    assert status in (200, 403, 404)
    assert headers['Cross-Origin-Opener-Policy'] == 'same-origin'
    assert headers['Cross-Origin-Embedder-Policy'] == 'require-corp'
    assert headers['Cross-Origin-Resource-Policy'] == 'same-origin'
    assert headers['X-Content-Type-Options'] == 'nosniff'


@pytest.mark.parametrize('path,mime', [
    ('/', 'text/html; charset=utf-8'),
    ('/workspace.json', 'application/json'),
    ('/launcher/launcher.css', 'text/css; charset=utf-8'),
    ('/launcher/app.mjs', 'text/javascript; charset=utf-8'),
    ('/launcher/favicon.svg', 'image/svg+xml'),
    ('/wasm_js/index.mjs', 'text/javascript; charset=utf-8'),
    ('/ws/demo_nodes/lib/demo_nodes/talker.js', 'text/javascript; charset=utf-8'),
    ('/ws/demo_nodes/lib/demo_nodes/talker.worker.js', 'text/javascript; charset=utf-8'),
    ('/ws/demo_nodes/lib/demo_nodes/talker.wasm', 'application/wasm'),
    ('/ws/demo_interfaces/share/demo_interfaces/colcon_wasm/types.json', 'application/json'),
])
def test_mime_types(server, path, mime):
    status, headers, _ = _get(server, path)
    assert status == 200, path
    assert headers['Content-Type'] == mime


def test_gzip_only_when_accepted(install, server):
    path = '/ws/demo_nodes/lib/demo_nodes/talker.wasm'
    original = (install[0] / 'demo_nodes' / 'lib' / 'demo_nodes' / 'talker.wasm').read_bytes()
    status, headers, body = _get(server, path, {'Accept-Encoding': 'gzip, deflate, br'})
    assert status == 200
    assert headers['Content-Encoding'] == 'gzip'
    assert headers['Vary'] == 'Accept-Encoding'
    assert int(headers['Content-Length']) == len(body) < len(original)
    assert gzip.decompress(body) == original
    status, headers, body = _get(server, path, {'Accept-Encoding': 'gzip;q=0, identity'})
    assert 'Content-Encoding' not in headers
    assert body == original
    status, headers, body = _get(server, path)
    assert 'Content-Encoding' not in headers and body == original


def test_precompressed_sibling_wins(server):
    status, headers, body = _get(server, '/wasm_js/index.mjs', {'Accept-Encoding': 'gzip'})
    assert headers['Content-Encoding'] == 'gzip'
    assert gzip.decompress(body) == b'precompressed'


def test_small_files_are_not_compressed(server):
    _, headers, body = _get(server, '/ws/demo_nodes/lib/demo_nodes/talker.worker.js',
                            {'Accept-Encoding': 'gzip'})
    assert 'Content-Encoding' not in headers and body == b'// worker\n'


def test_etag_gives_304(server):
    path = '/ws/demo_nodes/lib/demo_nodes/talker.js'
    _, headers, _ = _get(server, path)
    status, again, body = _get(server, path, {'If-None-Match': headers['ETag']})
    assert status == 304 and body == b''
    assert again['Cross-Origin-Embedder-Policy'] == 'require-corp'


def test_head_and_other_methods(server):
    status, headers, body = _get(server, '/ws/demo_nodes/lib/demo_nodes/talker.wasm',
                                 method='HEAD')
    assert status == 200 and body == b'' and int(headers['Content-Length']) > 0
    status, headers, _ = _get(server, '/', method='POST')
    assert status == 405 and headers['Allow'] == 'GET, HEAD'


@pytest.mark.parametrize('path', [
    '/wasm_js/', '/wasm_js/sub', '/wasm_js/sub/', '/launcher/', '/ws/demo_nodes/lib/',
    '/ws/demo_nodes/lib/demo_nodes'])
def test_no_directory_listing(server, path):
    status, _, body = _get(server, path)
    assert status == 404
    assert b'index.mjs' not in body and b'talker' not in body


@pytest.mark.parametrize('path', [
    '/wasm_js/../../../../etc/passwd',
    '/wasm_js/%2e%2e/%2e%2e/%2e%2e/etc/passwd',
    '/wasm_js/%2E%2E/%2E%2E/etc/passwd',
    '/wasm_js/..%2f..%2f..%2fetc%2fpasswd',
    '/wasm_js/%2e%2e%2f%2e%2e%2fetc/passwd',
    '/wasm_js/..%5c..%5cetc%5cpasswd',
    '/wasm_js/..\\..\\etc\\passwd',
    '/launcher/./launcher.css',
    '/wasm_js/index.mjs%00.png',
    '/ws/demo_nodes/lib/demo_nodes/../../../../../etc/passwd',
    '/ws/demo_nodes/%2e%2e/demo_nodes/lib/demo_nodes/talker.js',
    '/wasm_js//etc/passwd',
])
def test_traversal_is_refused(server, path):
    status, _, body = _get(server, path)
    assert status == 403, (path, status, body)
    assert b'root:' not in body


@pytest.mark.parametrize('path', [
    '/wasm_js/%252e%252e/%252e%252e/etc/passwd',  # double encoding: a literal name
    '/wasm_js/%c0%ae%c0%ae/etc/passwd',  # overlong UTF-8 for '.'
    '/ws/demo_nodes/lib/demo_nodes/secret.txt',  # beside listed files, but not listed
    '/ws/demo_nodes/share/demo_nodes/colcon_wasm/manifest.json',
    '/ws/other/lib/demo_nodes/talker.js',
    '/launcher/index.html',  # the template itself
    '//etc/passwd',  # a network-path reference: host 'etc', path /passwd
])
def test_unlisted_and_odd_paths_are_not_found(server, path):
    status, _, body = _get(server, path)
    assert status in (400, 404), (path, status)
    assert b'root:' not in body and b'not in the manifest' not in body


def test_symlinks_that_leave_the_root_are_refused(server):
    status, _, body = _get(server, '/ws/demo_nodes/lib/demo_nodes/escape.js')
    assert status == 403 and b'outside the install space' not in body
    assert b'leads out of the served directory' in body
    status, _, body = _get(server, '/wasm_js/link_out.mjs')
    assert status == 403


def test_workspace_json_lists_the_manifests(server):
    status, _, body = _get(server, '/workspace.json')
    workspace = json.loads(body)
    assert [p['name'] for p in workspace['packages']] == ['demo_nodes']
    talker = workspace['packages'][0]['executables'][0]
    assert talker['name'] == 'talker'
    assert talker['url'] == '/ws/demo_nodes/lib/demo_nodes/talker.js'
    assert talker['pthread'] is True
    assert workspace['types'] == [
        '/ws/demo_interfaces/share/demo_interfaces/colcon_wasm/types.json']
    assert workspace['runtime'] == '/wasm_js/index.mjs'


def test_page_embeds_the_workspace(server):
    status, _, body = _get(server, '/')
    assert status == 200
    html = body.decode()
    assert '<script type="module" src="/launcher/app.mjs">' in html
    start = html.index('id="workspace">') + len('id="workspace">')
    embedded = json.loads(html[start:html.index('</script>', start)])
    assert embedded['packages'][0]['executables'][0]['name'] == 'talker'


def test_page_modules_come_with_colcon_wasm_not_the_install_space(server):
    # cdr.mjs and page/ belong to the page: an old build's copy must not be served
    assert _get(server, '/wasm_js/cdr.mjs')[2] == b'// the page version\n'
    assert _get(server, '/wasm_js/page/deep.mjs')[2] == b'export const z = 4;\n'
    assert _get(server, '/wasm_js/dep.mjs')[0] == 200  # the runtime: the install space's


def test_page_preloads_its_module_graph_and_the_run_executables(server):
    _, _, body = _get(server, '/?run=demo_nodes/talker&run=demo_nodes/nope')
    html = body.decode()
    for module in ('/launcher/app.mjs', '/launcher/session.mjs', '/launcher/views/topics.mjs',
                   '/wasm_js/index.mjs', '/wasm_js/dep.mjs', '/wasm_js/page/deep.mjs'):
        assert f'<link rel="modulepreload" href="{module}">' in html, module
    assert '<link rel="preload" href="/ws/demo_nodes/lib/demo_nodes/talker.wasm" as="fetch" ' \
        'crossorigin>' in html
    assert html.count('rel="preload"') == 1


def test_port_already_taken_is_a_clear_error(install, server):
    base, runtime, _ = install
    port = server.server_address[1]
    with pytest.raises(ServeError) as info:
        make_server(InstallSpace(base), host='127.0.0.1', port=port, launcher_dir=LAUNCHER,
                    runtime_dir=runtime, runtime_origin='test')
    assert str(info.value) == (
        f'port {port} on 127.0.0.1 is already in use (another colcon-wasm serve, or another '
        'server?): stop it, or pass --port N (--port 0 picks a free port)')


def test_port_taken_by_another_program(install):
    base, runtime, _ = install
    blocker = socket.socket()
    blocker.bind(('127.0.0.1', 0))
    blocker.listen(1)
    try:
        with pytest.raises(ServeError, match='is already in use'):
            make_server(InstallSpace(base), host='127.0.0.1', port=blocker.getsockname()[1],
                        launcher_dir=LAUNCHER, runtime_dir=runtime, runtime_origin='test')
    finally:
        blocker.close()


def test_200_concurrent_requests(install, server):
    wasm = (install[0] / 'demo_nodes' / 'lib' / 'demo_nodes' / 'talker.wasm').read_bytes()
    barrier = threading.Barrier(200, timeout=60)

    def fetch(i):
        connection = http.client.HTTPConnection(*server.server_address[:2], timeout=60)
        connection.connect()
        barrier.wait()  # all 200 connections are open before any request is sent
        path = ['/ws/demo_nodes/lib/demo_nodes/talker.wasm', '/workspace.json', '/'][i % 3]
        connection.request('GET', path, headers={'Accept-Encoding': 'gzip'})
        response = connection.getresponse()
        body = response.read()
        connection.close()
        if i % 3 == 0:
            assert gzip.decompress(body) == wasm
        return response.status

    with ThreadPoolExecutor(max_workers=200) as pool:
        statuses = list(pool.map(fetch, range(200)))
    assert statuses == [200] * 200


def test_runtime_lookup_prefers_the_install_space(tmp_path):
    bundled = tmp_path / 'bundled'
    bundled.mkdir()
    (bundled / 'index.mjs').write_text('')
    base = tmp_path / 'install'
    base.mkdir()
    directory, origin = find_runtime(InstallSpace(base), bundled)
    assert directory == bundled and origin.startswith('colcon-wasm')
    share = base / 'wasm_js' / 'share' / 'wasm_js'
    share.mkdir(parents=True)
    (share / 'index.mjs').write_text('')
    directory, origin = find_runtime(InstallSpace(base), bundled)
    assert directory == share and origin.startswith('install space')
    with pytest.raises(ServeError, match='the wasm_js runtime was not found'):
        find_runtime(InstallSpace(tmp_path / 'bundled'), tmp_path / 'none')


def _colcon_wasm():
    return str(Path(sys.executable).parent / 'colcon-wasm')


def test_cli_without_an_install_space(tmp_path):
    result = subprocess.run([_colcon_wasm(), 'serve', '--install-base', str(tmp_path / 'nope')],
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert result.stderr == (
        f"colcon-wasm serve: no install space at '{tmp_path / 'nope'}': run 'colcon build --wasm' "
        'in the workspace '
        'first, or pass --install-base DIR\n')


def test_cli_port_taken_and_serving(install, server):
    base, _, _ = install
    port = server.server_address[1]
    result = subprocess.run([_colcon_wasm(), 'serve', '--install-base', str(base),
                             '--port', str(port)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 1
    assert f'colcon-wasm serve: port {port} on 127.0.0.1 is already in use' \
        in result.stderr
    process = subprocess.Popen([_colcon_wasm(), 'serve', '--install-base', str(base),
                                '--port', '0'], stdout=subprocess.PIPE, text=True)
    try:
        lines = [process.stdout.readline() for _ in range(3)]
        assert lines[0] == f'Serving 2 executable(s) of {base}\n'
        url = lines[2].split()[1]
        with urllib.request.urlopen(url + 'workspace.json', timeout=30) as response:
            assert response.headers['Cross-Origin-Embedder-Policy'] == 'require-corp'
            assert json.load(response)['packages'][0]['name'] == 'demo_nodes'
    finally:
        process.terminate()
        process.wait(10)
