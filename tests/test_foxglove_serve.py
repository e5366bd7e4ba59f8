# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon-wasm serve --foxglove`: a Foxglove client on the graph of the served pages.

The demo talker, listener and add_two_ints_server run in a page (headless
Chromium); the page joins serve's relay; npm `@foxglove/ws-protocol`'s
FoxgloveClient (tests/js/foxglove_client.mjs, mode `relay`) connects to
serve's Foxglove port, decodes the page's CDR with `@foxglove/rosmsg2-
serialization` from the advertised schema, publishes JSON to the page's
listener, calls its service and follows the connection graph by node as
the page stops its listener. All on 127.0.0.1, every wait bounded.
"""

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from foxglove_assets_case import check_fetch_asset  # noqa: E402
from rosbridge_launch import node_script  # noqa: E402


def test_a_foxglove_client_sees_hears_and_drives_the_pages(tmp_path):
    from served_page import explain_page
    from served_page import ServedPage
    install = demo_build.demo_install()
    tab = [
        {'pkg': 'demo_nodes', 'exe': 'talker', 'start': 'talker'},
        {'pkg': 'demo_nodes', 'exe': 'listener', 'start': 'listener'},
        {'pkg': 'demo_nodes', 'exe': 'add_two_ints_server', 'start': 'server'},
        {'until': 'colconWasm.session.bridge && colconWasm.session.bridge.state === '
                  "'connected' && colconWasm.session.bridge.relay"},
        {'wait': 'listener', 'text': 'I heard: [from foxglove json 4]', 'timeoutMs': 60000},
        # the Foxglove client sees the listener leave the connection graph
        {'stop': 'listener'},
        # its last call
        {'wait': 'server', 'text': 'Incoming request: a: 4242 b: 1', 'timeoutMs': 60000},
    ]
    with ServedPage(install, args=['--foxglove', '127.0.0.1:0']) as served:
        assert served.foxglove_url and served.foxglove_url.startswith('ws://127.0.0.1:'), \
            served.foxglove_url
        with ThreadPoolExecutor(1) as pool:
            page = pool.submit(served.run, tab, 90000)
            r = node_script('foxglove_client.mjs', 'relay', served.foxglove_url, timeout=90)
            result = page.result(timeout=200)
    assert result['ok'], explain_page(result)
    assert r['protocol'] == 'foxglove.websocket.v1' and r['sdkProtocol'] == 'foxglove.sdk.v1'
    # the demo's install has no rcl_interfaces: no parameters (test_foxglove_rclcpp.py has them)
    assert set(r['info']['capabilities']) == {'clientPublish', 'services', 'connectionGraph',
                                              'assets'}, r['info']
    assert r['info']['supportedEncodings'] == ['json'], r['info']
    channel = r['channel']
    assert (channel['encoding'], channel['schemaEncoding'], channel['schemaName']) == \
        ('cdr', 'ros2msg', 'demo_interfaces/msg/Chatter'), channel
    from colcon_wasm.launch.install_space import InstallSpace
    assert channel['schema'] == InstallSpace(install).ros2msg_schemas().full_text(
        'demo_interfaces/msg/Chatter')
    # the page talker's CDR, decoded by a third-party reader
    talked = [h for h in r['heard'] if h['data'].startswith('Hello World')]
    assert talked and all(h['data'] == f"Hello World: {h['count']}" for h in talked), r['heard']
    # JSON published by Foxglove reached the page's C++ listener, in order
    heard = [line.rsplit('[', 1)[1].rstrip(']') for line in result['logs']['listener']
             if 'from foxglove json' in line]
    assert heard == [f'from foxglove json {i}' for i in range(5)], result['logs']['listener']
    assert r['sumJson'] == {'sum': 11}, r
    assert 'takes json' in r['cdrRefused']['message'], r['cdrRefused']
    assert 'no service with id 9999' in r['missing']['message'], r['missing']
    statuses = [s.get('message', '') for s in r['status']]
    assert any('malformed JSON' in s for s in statuses), statuses
    assert any("unknown or unsupported op 'noSuchOp'" in s for s in statuses), statuses
    assert any('unknown binary opcode 0x7f' in s for s in statuses), statuses
    assert any("takes json, not 'cdr'" in s for s in statuses), statuses
    assert r['last'] == {'sum': 4243}, r
    # the connection graph by node (which node of the tab holds which endpoint), as the
    # page's nodes come and go: the first update is complete, then what changed
    before, after = r['graphBefore'], r['graphAfter']
    assert before['published']['/chatter'] == ['/talker'], before
    assert before['subscribed']['/chatter'] == ['/listener'], before
    assert before['services']['/add_two_ints'] == ['/add_two_ints_server'], before
    assert r['firstGraph']['removedTopics'] == [] and r['firstGraph']['publishedTopics'], r
    # then this server subscribed to /chatter and published on it for the client (its
    # node is foxglove_bridge's), and the listener left
    assert after['subscribed']['/chatter'] == ['/foxglove_bridge'], after
    assert after['published']['/chatter'] == ['/foxglove_bridge', '/talker'], after
    assert after['services'] == before['services'], after


def test_serve_foxglove_fetch_asset_serves_package_files_and_refuses_the_rest(tmp_path):
    """Serve --foxglove answers fetchAsset with the install's package:// files, as launch does."""
    from served_page import ServedPage
    install = demo_build.demo_install()
    with ServedPage(install, args=['--foxglove', '127.0.0.1:0']) as served:
        check_fetch_asset(served.foxglove_url, install, tmp_path)
