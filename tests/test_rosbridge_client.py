# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rosbridge client of the runtime against the rosbridge server.

`colcon-wasm launch --rosbridge-connect` (Node.js) and the launcher page's
`?rosbridge=` (headless Chromium) bridged to a `colcon-wasm launch
--rosbridge` of real C++ nodes (rmw_wasm_cpp_node_tests' probe, the Humble
build of tests/rclcpp_build.py), both ways; the server killed and
restarted mid-stream. All on 127.0.0.1, every wait bounded.
"""

import json
from pathlib import Path
import re
import socket
import subprocess
import sys
import textwrap
import time

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rclcpp_build import rclcpp_build  # noqa: E402, I100, I202
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from rosbridge_launch import JS  # noqa: E402

SERVER = """
    launch:
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: listener}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: add_server,
             remap: [{from: hold, to: add}]}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: param_talker, name: news_talker,
             param: [{name: greeting, value: from_server}], remap: [{from: chatter, to: news}]}
"""

CLIENT = """
    launch:
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: param_talker, name: talker,
             param: [{name: greeting, value: from_client}]}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: listener, name: news_listener,
             remap: [{from: chatter, to: news}]}
    - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: caller,
             remap: [{from: hold, to: add}]}
"""


def _free_port():
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def _write(folder, name, text):
    path = folder / name
    path.write_text(textwrap.dedent(text).lstrip(), encoding='utf-8')
    return path


@pytest.fixture(scope='module')
def install():
    """Get the Humble build with the probe."""
    return rclcpp_build().install


def test_node_launch_bridged_both_ways_before_and_after_the_server_starts(install, tmp_path):
    """The client starts first (queues, KEEP_LAST keeps the last 10), then both ways and a call."""
    port = _free_port()
    server_file = _write(tmp_path, 'server.launch.yaml', SERVER)
    client_file = _write(tmp_path, 'client.launch.yaml', CLIENT)
    url = f'ws://127.0.0.1:{port}'
    with BackgroundLaunch(install, '--rosbridge-connect', url, client_file,
                          wait_url=False) as client:
        client.wait_for(f'cannot connect to {url} yet; retrying', timeout=60)
        client.wait_for('NAME /talker TOPIC /chatter', timeout=60)
        client.wait_for('[talker]: info line', timeout=30)
        time.sleep(3)  # 30 messages at 10 Hz: more than the talker's KEEP_LAST 10
        with BackgroundLaunch(install, '--rosbridge', f'127.0.0.1:{port}',
                              server_file) as server:
            client.wait_for(f'connected to {url}', timeout=30)
            # client -> server: the talker's messages reach the C++ listener of the server
            server.wait_for(re.compile(r'\[probe_listener\]: HEARD from_client \d+'), timeout=30)
            # server -> client: the server's talker reaches the client's listener
            client.wait_for(re.compile(r'\[news_listener\]: HEARD from_server \d+'), timeout=30)
            # the client's C++ caller is answered by the server's C++ service
            client.wait_for('[caller]: RESULT 5', timeout=30)
            server.wait_for('[add_server]: ANSWERED 5', timeout=10)
            report = client.wait_for(re.compile(
                r'/chatter: (\d+) older messages were replaced \(KEEP_LAST\) and 0 '
                r'lost'), timeout=10)
            assert int(report.group(1)) > 0
            heard = [int(n) for n in re.findall(r'HEARD from_client (\d+)', server.output())]
            # the last 10 queued while the server was away, then the live ones, in order
            assert heard == sorted(heard) and len(set(heard)) == len(heard), heard[:30]
            assert heard[0] > 1, heard[:12]
            assert heard[:10] == list(range(heard[0], heard[0] + 10)), heard[:12]


def test_server_restarted_mid_stream_reliable_messages_arrive_in_order(install, tmp_path):
    """Kill the server mid-stream and start it again: nothing within the bound is lost."""
    port = _free_port()
    server_file = _write(tmp_path, 'server.launch.yaml', """
        launch:
        - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: keep_all_listener}
    """)
    address = ['--rosbridge', f'127.0.0.1:{port}']
    first = BackgroundLaunch(install, *address, server_file)
    first.wait_for('process started', timeout=30)
    wasm_js = _runtime_dir(install)
    types = _types(install, 'std_msgs')
    client = subprocess.Popen(
        ['node', str(JS / 'rosbridge_client_side.mjs'), first.url, str(wasm_js), '12', str(types)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=str(JS))
    try:
        first.wait_for(re.compile(r'HEARD seq 1\d\d'), timeout=30)
        first.stop()  # mid-stream
        second = BackgroundLaunch(install, *address, server_file)
        try:
            out, _ = client.communicate(timeout=60)
            seq = re.search(r'PUBLISHED (\d+) LAST', out).group(1)
            second.wait_for(re.compile(rf'HEARD seq {seq}$'), timeout=20)
        finally:
            second.stop()
    finally:
        if client.poll() is None:
            client.kill()
            client.wait(10)
    assert 'lost the connection to' in out and 'reconnected to' in out, out[-3000:]
    stats = json.loads(out.strip().splitlines()[-1])['stats']
    assert stats['connects'] == 2 and stats['lost'] == 0 and stats['queued'] > 0, stats
    one = [int(n) for n in re.findall(r'HEARD seq (\d+)', first.output())]
    two = [int(n) for n in re.findall(r'HEARD seq (\d+)', second.output())]
    assert one == list(range(one[0], one[-1] + 1)), one
    # everything sent while the server was down, and after, in order, once
    assert two == list(range(one[-1] + 1, two[-1] + 1)), (one[-3:], two[:5])


def _runtime_dir(install):
    """Get the install space's wasm_js runtime (the one the executables were built with)."""
    from colcon_wasm.launch.install_space import InstallSpace
    return InstallSpace(install).package('wasm_js').share / 'src'


def _types(install, package):
    from colcon_wasm.launch.install_space import InstallSpace
    return InstallSpace(install).package(package).types_path


def test_page_bridged_to_a_node_launch_both_ways(install, tmp_path):
    """A Chromium page with ?rosbridge= and a Node.js launch: talker and listener each way."""
    from served_page import explain_page
    from served_page import ServedPage
    server_file = _write(tmp_path, 'server.launch.yaml', SERVER)
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0', server_file) as server:
        with ServedPage(install) as page:
            result = page.run([
                {'start': 'talker', 'pkg': 'rmw_wasm_cpp_node_tests', 'exe': 'probe',
                 'args': ['param_talker', '--ros-args', '-p', 'greeting:=from_page',
                          '-r', '__node:=page_talker']},
                {'start': 'listener', 'pkg': 'rmw_wasm_cpp_node_tests', 'exe': 'probe',
                 'args': ['listener', '--ros-args', '-r', 'chatter:=news']},
                {'until': 'colconWasm.session.bridge && colconWasm.session.bridge.state === '
                          "'connected'"},
                {'wait': 'listener', 'regex': r'HEARD from_server \d+', 'count': 3},
                {'until': 'colconWasm.session.graph.nodes.filter((n) => n.remote).map((n) => '
                          "n.fqn + ' ' + n.process).join('\\n') || null",
                 'save': 'remote'},
                {'until': "document.querySelector('#rosbridge-state').textContent",
                 'save': 'chip'},
            ], query=f'?rosbridge={server.url}')
            assert result['ok'], explain_page(result)
            server.wait_for(re.compile(r'\[probe_listener\]: HEARD from_page \d+'), timeout=30)
    remote = result['saved']['remote']
    assert f'/add_server remote {server.url}' in remote, remote
    assert '/news_talker remote' in remote, remote
    assert result['saved']['chip'] == 'rosbridge: connected', result['saved']


@pytest.mark.parametrize('server_side, client_side', [
    ('action_server_not_composable', 'action_client_not_composable_with_feedback'),
    ('action_client_not_composable_with_feedback', 'action_server_not_composable'),
], ids=['remote_server', 'remote_client'])
def test_actions_cross_the_bridge(install, tmp_path, server_side, client_side):
    """A C++ action client and server on either side: goal, feedback and result cross."""
    def launch_file(name, exe):
        package = f"examples_rclcpp_minimal_action_{'server' if 'server' in exe else 'client'}"
        return _write(tmp_path, name, f"""
            launch:
            - node: {{pkg: {package}, exec: {exe}}}
        """)
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0',
                          launch_file('a.launch.yaml', server_side)) as server:
        with BackgroundLaunch(install, '--rosbridge-connect', server.url,
                              launch_file('b.launch.yaml', client_side), wait_url=False) as client:
            client.wait_for(f'connected to {server.url}', timeout=30)
            where = client if 'client' in client_side else server
            where.wait_for('result received', timeout=60)
            where.wait_for('process has finished cleanly', timeout=10)
            output = where.output()
    numbers = [int(n) for n in re.findall(r'\[minimal_action_client\]: (\d+)$', output, re.M)]
    assert numbers == [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55], output[-3000:]
    feedback = re.findall(r'Next number in sequence received: (\d+)', output)
    assert len(feedback) >= 5, output[-3000:]
