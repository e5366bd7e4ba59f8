# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
What programs see of their install spaces, without a build.

AMENT_PREFIX_PATH of isolated and merged install bases, the launch plan's
views and environment, the server's /fs/ endpoints (listings, files,
refusals) and the checks of Runtime.spawn({mounts}).
"""

import gzip
import http.client
import json
import os
from pathlib import Path
import subprocess
import threading

from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch import NodeProcess
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_view import ament_prefixes
from colcon_wasm.launch.install_view import program_environment
from colcon_wasm.launch.runner import host_plan
from colcon_wasm.server import make_server
import pytest

REPO = Path(__file__).resolve().parents[1]
LAUNCHER = REPO / 'templates' / 'launcher'
RUNTIME = REPO / 'packages' / 'wasm_js' / 'src'
ISOLATION = {'Cross-Origin-Opener-Policy': 'same-origin',
             'Cross-Origin-Embedder-Policy': 'require-corp',
             'Cross-Origin-Resource-Policy': 'same-origin'}


def _package(base, name, *, merged=False, executable=None):
    """Write an ament package marker (and optionally a manifest with one executable)."""
    prefix = base if merged else base / name
    marker = prefix / 'share' / 'ament_index' / 'resource_index' / 'packages' / name
    marker.parent.mkdir(parents=True, exist_ok=True)
    marker.write_text('')
    if executable:
        lib = prefix / 'lib' / name
        lib.mkdir(parents=True, exist_ok=True)
        (lib / (executable + '.js')).write_text('// glue\n')
        manifest = prefix / 'share' / name / 'colcon_wasm' / 'manifest.json'
        manifest.parent.mkdir(parents=True, exist_ok=True)
        manifest.write_text(json.dumps({'schema': 1, 'package': name, 'executables': [
            {'name': executable, 'js': f'lib/{name}/{executable}.js', 'files': [],
             'uses_bus': True, 'pthread': False}]}))
    return prefix


def test_ament_prefixes_of_isolated_and_merged_bases(tmp_path):
    overlay = tmp_path / 'overlay'
    _package(overlay, 'b_pkg')
    _package(overlay, 'a_pkg')
    (overlay / 'not_a_package' / 'share').mkdir(parents=True)
    (overlay / 'wrong_marker' / 'share' / 'ament_index' / 'resource_index' / 'packages').mkdir(
        parents=True)
    merged = tmp_path / 'merged'
    _package(merged, 'x_pkg', merged=True)
    _package(merged, 'y_pkg', merged=True)
    assert ament_prefixes([overlay, merged, tmp_path / 'missing', overlay]) == [
        str(overlay / 'a_pkg'), str(overlay / 'b_pkg'), str(merged)]
    assert ament_prefixes([merged, overlay])[0] == str(merged)
    assert ament_prefixes([tmp_path / 'empty_or_missing']) == []


def test_program_environment_keeps_what_the_user_set():
    assert program_environment({'A': '1'}, ['/p', '/q']) == {
        'A': '1', 'AMENT_PREFIX_PATH': '/p:/q'}
    assert program_environment({'AMENT_PREFIX_PATH': '/mine'}, ['/p']) == {
        'AMENT_PREFIX_PATH': '/mine'}
    assert program_environment({'AMENT_PREFIX_PATH': ''}, ['/p']) == {'AMENT_PREFIX_PATH': ''}
    assert program_environment(None, []) == {}


def test_launch_plan_gives_views_and_prefixes_overlay_first(tmp_path):
    install = tmp_path / 'install_wasm'
    _package(install, 'demo_nodes', executable='talker')
    underlay = tmp_path / 'underlay'
    _package(underlay, 'rclcpp')
    plan = LaunchPlan([NodeProcess('demo_nodes', 'talker'),
                       NodeProcess('demo_nodes', 'talker', env={'AMENT_PREFIX_PATH': '/x'})])
    description = host_plan(plan, InstallSpace(install, underlays=[]))
    assert description['mounts'] == [{'path': str(install)}]
    assert description['processes'][0]['env'] == {
        'AMENT_PREFIX_PATH': str(install / 'demo_nodes')}
    assert description['processes'][1]['env'] == {'AMENT_PREFIX_PATH': '/x'}
    both = f"{install / 'demo_nodes'}:{underlay / 'rclcpp'}"
    description = host_plan(plan, InstallSpace(install, underlays=[]), bases=[install, underlay])
    assert description['mounts'] == [{'path': str(install)}, {'path': str(underlay)}]
    assert description['processes'][0]['env']['AMENT_PREFIX_PATH'] == both
    # by default: the install space and the underlays it stands on
    description = host_plan(plan, InstallSpace(install, underlays=[underlay]))
    assert description['mounts'] == [{'path': str(install)}, {'path': str(underlay)}]
    assert description['processes'][0]['env']['AMENT_PREFIX_PATH'] == both


# ----------------------------------------------------------------- the server


@pytest.fixture(scope='module')
def tree(tmp_path_factory):
    """Write an isolated install space with files, links in and out, and a second base."""
    root = tmp_path_factory.mktemp('views')
    base = root / 'install_wasm'
    prefix = _package(base, 'demo_nodes', executable='talker')
    data = prefix / 'share' / 'demo_nodes' / 'data'
    data.mkdir(parents=True)
    (data / 'config.yaml').write_text('rate: 5\n' * 200)  # compressible, > 1 KiB
    (data / 'config.yaml.gz').write_bytes(gzip.compress(b'a different file'))
    (data / 'blob.bin').write_bytes(bytes(range(256)) * 8)
    os.chmod(data / 'blob.bin', 0o640)
    (data / 'sub dir').mkdir()
    (data / 'sub dir' / 'ü.txt').write_text('unicode name')
    os.symlink('config.yaml', data / 'link_in.yaml')
    os.symlink(str(prefix / 'share'), data / 'dir_link_in')
    (root / 'secret.txt').write_text('outside the install space')
    os.symlink(str(root / 'secret.txt'), data / 'link_out.txt')
    os.symlink(str(root), data / 'dir_link_out')
    os.symlink('missing', data / 'dangling')
    _package(base, 'other_pkg')
    (base / 'other_pkg' / 'share' / 'other_pkg').mkdir()
    underlay = root / 'underlay'
    _package(underlay, 'rclcpp')
    return root, base, underlay, data


@pytest.fixture(scope='module')
def server(tree):
    root, base, underlay, _ = tree
    # the page's programs see the install space and the underlays it stands on
    srv = make_server(InstallSpace(base, underlays=[underlay]), host='127.0.0.1', port=0,
                      launcher_dir=LAUNCHER, runtime_dir=RUNTIME, runtime_origin='test')
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


DATA = '/fs/0/demo_nodes/share/demo_nodes/data'


def test_workspace_describes_the_views_and_the_prefixes(tree, server):
    _, base, underlay, _ = tree
    status, _, body = _get(server, '/workspace.json')
    workspace = json.loads(body)
    assert workspace['mounts'] == [{'path': str(base), 'url': '/fs/0'},
                                   {'path': str(underlay), 'url': '/fs/1'}]
    assert workspace['environment'] == {'AMENT_PREFIX_PATH': ':'.join(map(str, [
        base / 'demo_nodes', base / 'other_pkg', underlay / 'rclcpp']))}


def test_listing_names_kinds_sizes_modes_and_times(tree, server):
    _, base, _, data = tree
    status, headers, body = _get(server, DATA + '/')
    assert status == 200, body
    assert headers['Content-Type'] == 'application/json'
    for name, value in ISOLATION.items():
        assert headers[name] == value
    listing = json.loads(body)
    assert listing['path'] == str(data)
    assert listing['mode'] == data.stat().st_mode & 0o7777
    entries = {e['name']: e for e in listing['entries']}
    # links out of the install space and dangling links are not in the view
    assert sorted(entries) == ['blob.bin', 'config.yaml', 'config.yaml.gz', 'dir_link_in',
                               'link_in.yaml', 'sub dir']
    assert [e['name'] for e in listing['entries']] == sorted(entries)
    blob = (data / 'blob.bin').stat()
    assert entries['blob.bin'] == {'name': 'blob.bin', 'kind': 'file', 'size': 2048,
                                   'mode': 0o640, 'mtime_ms': blob.st_mtime_ns // 1000000}
    assert entries['sub dir']['kind'] == 'dir'
    assert entries['dir_link_in']['kind'] == 'dir'  # links are followed
    assert entries['link_in.yaml']['kind'] == 'file'
    assert entries['link_in.yaml']['size'] == (data / 'config.yaml').stat().st_size
    status, _, body = _get(server, '/fs/0/')
    assert status == 200 and [e['name'] for e in json.loads(body)['entries']] == [
        'demo_nodes', 'other_pkg']
    status, _, body = _get(server, '/fs/1/rclcpp/share/ament_index/resource_index/packages/')
    assert status == 200 and [e['name'] for e in json.loads(body)['entries']] == ['rclcpp']
    status, _, body = _get(server, DATA + '/sub%20dir/')
    assert status == 200 and json.loads(body)['entries'][0]['name'] == 'ü.txt'


def test_files_are_served_exactly(tree, server):
    _, _, _, data = tree
    status, headers, body = _get(server, DATA + '/blob.bin')
    assert status == 200 and body == (data / 'blob.bin').read_bytes()
    assert headers['Content-Type'] == 'application/octet-stream'
    for name, value in ISOLATION.items():
        assert headers[name] == value
    # the config.yaml.gz beside it is another file, not a precompressed copy
    status, headers, body = _get(server, DATA + '/config.yaml', {'Accept-Encoding': 'gzip'})
    assert status == 200
    original = (data / 'config.yaml').read_bytes()
    if headers.get('Content-Encoding') == 'gzip':
        body = gzip.decompress(body)
    assert body == original
    status, _, body = _get(server, DATA + '/link_in.yaml')
    assert status == 200 and body == original
    status, _, body = _get(server, DATA + '/sub%20dir/%C3%BC.txt')
    assert status == 200 and body == b'unicode name'
    status, headers, body = _get(server, DATA + '/blob.bin', method='HEAD')
    assert status == 200 and body == b'' and headers['Content-Length'] == '2048'


def _walk(server, path, skip):
    status, headers, body = _get(server, f'{path}?walk={skip}')
    assert status == 200, body
    assert headers['Cross-Origin-Embedder-Policy'] == 'require-corp'
    return json.loads(body)['listings']


def test_a_walk_lists_the_directories_along_a_path(tree, server):
    _, base, _, data = tree
    listings = _walk(server, DATA + '/sub%20dir/%C3%BC.txt', 0)
    assert sorted(listings) == [
        '', 'demo_nodes', 'demo_nodes/share', 'demo_nodes/share/demo_nodes',
        'demo_nodes/share/demo_nodes/data', 'demo_nodes/share/demo_nodes/data/sub dir']
    assert listings['demo_nodes/share/demo_nodes/data'] == json.loads(_get(server, DATA + '/')[2])
    # from the 3rd directory on (0: the base); up to what exists; not through a link out
    assert sorted(_walk(server, DATA + '/missing/deeper', 3)) == [
        'demo_nodes/share/demo_nodes', 'demo_nodes/share/demo_nodes/data']
    assert sorted(_walk(server, DATA + '/dir_link_out/x', 4)) == [
        'demo_nodes/share/demo_nodes/data']
    assert _walk(server, '/fs/0/nothing/here', 1) == {}
    status, _, body = _get(server, DATA + '/?walk=two')
    assert status == 404 and b'walk=' in body


def test_a_walk_into_a_resource_index_brings_every_package_of_the_base(tree, server):
    _, base, _, _ = tree
    index = 'share/ament_index/resource_index'
    listings = _walk(server, f'/fs/0/demo_nodes/{index}/packages/demo_nodes', 0)
    for package in ('demo_nodes', 'other_pkg'):
        assert f'{package}/{index}/packages' in listings, sorted(listings)
        assert package in listings  # and the directories on the way to it
    assert [e['name'] for e in listings[f'other_pkg/{index}/packages']['entries']] == [
        'other_pkg']
    # elsewhere a walk stays on its path
    assert 'other_pkg' not in _walk(server, DATA, 0)


@pytest.mark.parametrize('path,status,says', [
    (DATA + '/../../../../../secret.txt', 403, 'path traversal refused'),
    (DATA + '/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/secret.txt', 403, 'path traversal refused'),
    ('/fs/0/..%2fsecret.txt', 403, 'path traversal refused'),
    ('/fs/0/%2e%2e/', 403, 'path traversal refused'),
    (DATA + '/link_out.txt', 404, 'leads out of the install space'),
    (DATA + '/dir_link_out/secret.txt', 404, 'leads out of the install space'),
    (DATA + '/dir_link_out/', 404, 'leads out of the install space'),
    (DATA + '/dangling', 404, 'is not in the install space'),
    (DATA + '/missing.txt', 404, 'is not in the install space'),
    (DATA + '/blob.bin/', 404, 'is not a directory'),
    (DATA, 404, 'is not a file (list a directory with a trailing slash)'),
    ('/fs/2/', 404, "no install base '2': this server has 2"),
    ('/fs/x/', 404, "no install base 'x'"),
])
def test_refusals_say_why(server, path, status, says):
    got, headers, body = _get(server, path)
    assert got == status, body
    assert says in body.decode(), body
    assert b'outside the install space' not in body
    assert headers['Cross-Origin-Embedder-Policy'] == 'require-corp'


# ------------------------------------------------------- Runtime.spawn checks


@pytest.mark.parametrize('options,message', [
    ({'mounts': 'x'}, "spawn 'p': mounts must be an array of {path, url?}"),
    ({'mounts': [{'path': 'relative/dir'}]}, 'mount path "relative/dir" must be an absolute'),
    ({'mounts': [{'path': '/'}]}, 'mount path "/" must be an absolute, normalized path other'),
    ({'mounts': [{'path': '/a/../b'}]}, 'mount path "/a/../b" must be'),
    ({'mounts': [{'path': '/a/'}]}, 'mount path "/a/" must be'),
    ({'mounts': [{'path': '/ws/install'}], 'files': {'/ws/install/p.yaml': 'x'}},
     "file '/ws/install/p.yaml' lies in the read-only view at '/ws/install': write it elsewhere"),
])
def test_spawn_checks_its_mounts(options, message):
    script = (
        'const { Runtime } = await import(process.argv[1]);'
        'const rt = await Runtime.create({ warmWorkers: 0 });'
        "try { await rt.spawn({ url: '/nowhere/p.js', ...JSON.parse(process.argv[2]) });"
        " console.log('spawned'); }"
        ' catch (e) { console.log(e.message); } finally { await rt.close(); }')
    done = subprocess.run(
        ['node', '--input-type=module', '-e', script, (RUNTIME / 'index.mjs').as_uri(),
         json.dumps(options)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert message in done.stdout, done.stdout
