# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon-wasm record FILE.mcap`: record a rosbridge server's topics.

Against the rosbridge server of a `colcon-wasm launch` of the demo (talker
and camera), and against `colcon-wasm serve --rosbridge`'s relay with the
demo talker in a page (headless Chromium). The files are read by the
third-party `mcap` + `mcap-ros2-support` and `rosbags`; every message must
be what the nodes published, in order, without a gap. All on 127.0.0.1,
every wait bounded.
"""

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
import re
import socket
import sys
import time

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from test_record import colcon_wasm  # noqa: E402
from test_record import frame_pixels  # noqa: E402
from test_record import mcap_messages  # noqa: E402
from test_relay_units import Client  # noqa: E402


@pytest.fixture(scope='module')
def install():
    """Build the demo workspace (once per test run)."""
    return demo_build.demo_install()


@pytest.fixture(scope='module')
def launched(install):
    """Launch the demo talker and camera with `--rosbridge 127.0.0.1:0`, for the module."""
    with BackgroundLaunch(install, '--rosbridge', '127.0.0.1:0', 'demo_nodes/talker',
                          'demo_nodes/camera') as run:
        run.wait_for("Publishing: 'Hello World: 3'", timeout=60)
        yield run


def _chatter_counts(messages):
    counts = [d.count for topic, _, _, d, _ in messages if topic == '/chatter']
    for topic, _, _, d, _ in messages:
        if topic == '/chatter':
            assert d.data == f'Hello World: {d.count}'
    return counts


def test_record_the_topics_of_a_launch_rosbridge_server(install, launched, tmp_path):
    path = tmp_path / 'remote.mcap'
    code, out, err = colcon_wasm('record', path, '--url', launched.url, '--install-base',
                                 install, '--duration', '5', '--record-compression', 'zstd')
    assert code == 0, out + err
    assert re.search(r'\d+ messages on \d+ topics into .*remote\.mcap', err), err
    messages = mcap_messages(path)
    counts = _chatter_counts(messages)
    assert len(counts) >= 3, counts  # 5 s at 1 Hz, less the first discovery
    assert counts == list(range(counts[0], counts[-1] + 1)), counts
    frames = [m for m in messages if m[0] == '/camera/image']
    assert len(frames) >= 20, len(frames)
    first = next(k for k in range(10000) if bytes(frames[0][3].data) == frame_pixels(k))
    for i, (_, _, _, d, _) in enumerate(frames):
        assert bytes(d.data) == frame_pixels(first + i), f'frame {first + i}'
    for topic in ('/chatter', '/camera/image'):
        times = [m[1] for m in messages if m[0] == topic]
        assert times == sorted(times), topic
    # publish_time: the server's stamp, at most a second before the arrival here
    assert all(0 <= m[1] - m[2] < 1e9 for m in messages), \
        [(m[1], m[2]) for m in messages if not 0 <= m[1] - m[2] < 1e9][:3]

    from rosbags import highlevel
    with highlevel.AnyReader([path]) as reader:
        types = {c.topic: c.msgtype for c in reader.connections}
        assert types['/chatter'] == 'demo_interfaces/msg/Chatter', types
        seen = sum(1 for _ in reader.messages())
    assert seen == len(messages)


def test_record_only_the_record_topics(install, launched, tmp_path):
    path = tmp_path / 'chatter.mcap'
    code, out, err = colcon_wasm('record', path, '--url', launched.url, '--install-base',
                                 install, '--duration', '3', '--record-topic', '/chatter')
    assert code == 0, out + err
    messages = mcap_messages(path)
    assert {m[0] for m in messages} == {'/chatter'}, {m[0] for m in messages}
    assert len(_chatter_counts(messages)) >= 2


def test_errors_name_what_failed_and_leave_no_file(install, tmp_path):
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        port = s.getsockname()[1]
    path = tmp_path / 'none.mcap'
    code, out, err = colcon_wasm('record', path, '--url', f'ws://127.0.0.1:{port}',
                                 '--install-base', install, '--duration', '2')
    assert code == 1, out + err
    assert f'cannot connect to ws://127.0.0.1:{port}' in err, err
    assert 'start the rosbridge server first' in err, err
    assert not path.exists()
    code, out, err = colcon_wasm('record', tmp_path / 'no' / 'such' / 'x.mcap',
                                 '--install-base', install)
    assert code == 1 and 'does not exist' in err, out + err
    code, out, err = colcon_wasm('record', path, '--url', 'http://127.0.0.1:1',
                                 '--install-base', install)
    assert code == 1 and 'is not a ws://HOST:PORT URL' in err, out + err


def _wait_for_a_chatter_message(url, page, timeout=150):
    """Return once the page's talker is heard through the relay at ``url``.

    The recording starts then, so that its duration is all talking (the
    page's start-up on a loaded machine took most of it otherwise).
    """
    client = Client.connect(url)
    client.send({'op': 'subscribe', 'id': 'wait', 'topic': '/chatter',
                 'type': 'demo_interfaces/msg/Chatter'})
    deadline = time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            assert not page.done(), page.result()
            if client.until(lambda m: m.get('topic') == '/chatter', timeout=2):
                return
        raise AssertionError(f'no /chatter message through {url} in {timeout} s')
    finally:
        client.sock.close()


def test_record_the_pages_of_serve_through_its_relay(install, tmp_path):
    from served_page import explain_page
    from served_page import ServedPage
    path = tmp_path / 'served.mcap'
    tab = [
        {'pkg': 'demo_nodes', 'exe': 'talker', 'start': 'talker'},
        {'until': 'colconWasm.session.bridge && colconWasm.session.bridge.state === '
                  "'connected' && colconWasm.session.bridge.relay"},
        {'wait': 'talker', 'text': "Publishing: 'Hello World: 2'"},
        {'sleep': 14000},
    ]
    with ServedPage(install, args=['--rosbridge', '127.0.0.1:0']) as served:
        with ThreadPoolExecutor(1) as pool:
            page = pool.submit(served.run, tab, 60000)
            _wait_for_a_chatter_message(served.rosbridge_url, page)
            code, out, err = colcon_wasm('record', path, '--url', served.rosbridge_url,
                                         '--install-base', install, '--duration', '8')
            result = page.result(timeout=200)
    assert result['ok'], explain_page(result)
    assert code == 0, out + err
    counts = _chatter_counts(mcap_messages(path))
    logged = [int(n) for n in re.findall(r"Hello World: (\d+)'",
                                         '\n'.join(result['logs']['talker']))]
    assert len(counts) >= 4, (counts, err)  # 8 s at 1 Hz
    assert counts == list(range(counts[0], counts[-1] + 1)), counts
    assert set(counts) <= set(logged), (counts, logged)
