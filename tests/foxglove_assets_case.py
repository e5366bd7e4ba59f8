# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The fetchAsset case both Foxglove servers (launch --foxglove, serve --foxglove) must pass."""

import hashlib
import shutil

from rosbridge_launch import node_script


def check_fetch_asset(url, install, tmp_path):
    """
    Fetch package:// files of the demo's share folder; check the file and each refusal.

    npm `@foxglove/ws-protocol`'s FoxgloveClient (tests/js/foxglove_client.mjs,
    mode `assets`) asks for a mesh, a file kind outside the allowlist, a
    package not installed, a link out of the share folder, a missing file,
    a file:// URI, then a request without requestId.
    """
    share = install / 'demo_nodes' / 'share' / 'demo_nodes'
    if not share.is_dir():  # a merged install
        share = install / 'share' / 'demo_nodes'
    meshes = share / 'test_meshes'
    meshes.mkdir()
    try:
        mesh = bytes(range(256)) * 300  # 76.8 kB, every byte value
        (meshes / 'base link.stl').write_bytes(mesh)
        (meshes / 'notes.txt').write_text('not an asset', encoding='utf-8')
        outside = tmp_path / 'secret.stl'
        outside.write_bytes(b'outside the share folder')
        (meshes / 'escape.stl').symlink_to(outside)
        uris = ['package://demo_nodes/test_meshes/base%20link.stl',
                'package://demo_nodes/test_meshes/notes.txt',
                'package://no_such_package/meshes/a.stl',
                'package://demo_nodes/test_meshes/escape.stl',
                'package://demo_nodes/test_meshes/missing.stl',
                'file:///etc/passwd']
        r = node_script('foxglove_client.mjs', 'assets', url, *uris)
    finally:
        shutil.rmtree(meshes)
    assert 'assets' in r['capabilities']
    got = {x['uri']: x for x in r['responses']}
    assert [x['requestId'] for x in r['responses']] == list(range(1, len(uris) + 1))
    ok = got[uris[0]]
    assert ok['status'] == 0 and ok['bytes'] == len(mesh)
    assert ok['sha256'] == hashlib.sha256(mesh).hexdigest()
    errors = {uri: got[uri]['error'] for uri in uris[1:]}
    assert all(got[uri]['status'] == 1 for uri in uris[1:])
    assert "not an allowed asset (foxglove_bridge's asset_uri_allowlist" in errors[uris[1]]
    assert "package 'no_such_package' is not in the install space" in errors[uris[2]]
    assert "the path leaves the share folder of 'demo_nodes'" in errors[uris[3]]
    assert "no file test_meshes/missing.stl in the share folder of 'demo_nodes'" in errors[uris[4]]
    assert 'only package:// URIs are served' in errors[uris[5]]
    # no requestId: a status, and the connection went on
    assert any("fetchAsset needs an integer 'requestId'" in s.get('message', '')
               for s in r['status']), r['status']
