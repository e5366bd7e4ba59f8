# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The launcher page's record and replay, in headless Chromium (tests/js/page_bag.mjs).

Record: the demo talker and camera run in the page; Record, 4 s, Stop: the
downloaded bag is read by the third-party `mcap` + `mcap-ros2-support` and
`rosbags`, and holds what the page's nodes published. Replay: a bag written
by `rosbags` is dropped on the page, whose C++ listener hears it through
Step, seek, Play and Pause. serve's `/bag` (colcon_wasm/server/bag_socket.py)
does the MCAP side. All on 127.0.0.1, every wait bounded. The header shows a
red REC chip while the page records; the playback bar at the bottom shows the
player's state; screenshots go to artifacts/screenshots/bag/.
"""

import json
from pathlib import Path
import re
import subprocess
import sys

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from served_page import CHROMIUM  # noqa: E402
from served_page import JS  # noqa: E402
from served_page import ServedPage  # noqa: E402
from test_record import _write_rosbags_bag  # noqa: E402
from test_record import frame_pixels  # noqa: E402
from test_record import mcap_messages  # noqa: E402

GAP_MS = 200
COUNT = 20
SCREENSHOTS = Path(__file__).resolve().parents[1] / 'artifacts' / 'screenshots' / 'bag'


@pytest.fixture(scope='module')
def served():
    """Serve the demo install for the module."""
    with ServedPage(demo_build.demo_install()) as page:
        yield page


def _drive(served, **options):
    completed = subprocess.run(
        ['node', str(JS / 'page_bag.mjs'), json.dumps(
            dict(options, url=served.url, chromium=CHROMIUM, screenshots=str(SCREENSHOTS)))],
        capture_output=True, text=True, timeout=240)
    lines = completed.stdout.strip().splitlines()
    assert lines, f'page_bag.mjs printed nothing: {completed.stderr[-3000:]}'
    result = json.loads(lines[-1])
    assert result['ok'], json.dumps(result, indent=1)[-6000:]
    return result


def test_record_on_the_page_downloads_the_bag_of_its_nodes(served, tmp_path):
    out = tmp_path / 'download.mcap'
    result = _drive(served, mode='record', out=str(out))
    assert result['suggested'] == 'launcher.mcap', result
    assert re.search(r'launcher\.mcap: \d+ messages', result['chip']), result['chip']
    rec = result['rec']
    for seen in (rec['first'], rec['last']):  # while recording: red, in the window, the time
        assert seen['shown'] and seen['inWindow'], rec
        assert re.fullmatch(r'REC\d+:\d\d', seen['text']), rec
        assert seen['background'] == 'rgb(208, 53, 43)', rec  # --red
    minutes, seconds = re.fullmatch(r'REC(\d+):(\d\d)', rec['last']['text']).groups()
    assert int(minutes) * 60 + int(seconds) >= 3, rec  # 4 s later
    assert not rec['after']['shown'], rec  # gone once it stopped
    messages = mcap_messages(out)
    chatter = [d for topic, _, _, d, _ in messages if topic == '/chatter']
    counts = [d.count for d in chatter]
    talker = '\n'.join(result['logs']['talker'])
    logged = [int(n) for n in re.findall(r"Hello World: (\d+)'", talker)]
    assert len(counts) >= 3, counts  # 4 s at 1 Hz
    assert counts == list(range(counts[0], counts[-1] + 1)), counts
    assert set(counts) <= set(logged), (counts, logged)
    assert all(d.data == f'Hello World: {d.count}' for d in chatter)
    frames = [d for topic, _, _, d, _ in messages if topic == '/camera/image']
    assert len(frames) >= 20, len(frames)  # 4 s at 10 Hz
    first = next(k for k in range(10000) if bytes(frames[0].data) == frame_pixels(k))
    for i, d in enumerate(frames):
        assert bytes(d.data) == frame_pixels(first + i), f'frame {first + i}'
    assert all(0 <= log - publish < 1e9 for _, log, publish, _, _ in messages)
    from rosbags import highlevel
    with highlevel.AnyReader([out]) as reader:
        qos = {c.topic: c.ext.offered_qos_profiles for c in reader.connections}
        assert qos['/chatter'], qos  # the page knows its publishers' QoS
        assert sum(1 for _ in reader.messages()) == len(messages)


def test_a_bag_dropped_on_the_page_plays_with_step_seek_and_pause(served, tmp_path):
    bag = tmp_path / 'bag'
    _write_rosbags_bag(bag, served.install, [GAP_MS] * COUNT)
    mcap = next(bag.glob('*.mcap'))
    seek_ms = 10 * GAP_MS
    result = _drive(served, mode='play', bag=str(mcap), seekMs=seek_ms)
    info = result['info']
    assert info['count'] == COUNT, info  # /odd is not counted: its type is unknown
    assert [t['topic'] for t in info['topics']] == ['/chatter'], info
    assert [s['topic'] for s in info['skipped']] == ['/odd'], info
    assert 'does not know its type' in info['skipped'][0]['why'], info
    assert info['topics'][0]['qos']['durability'] == 'transient_local', info
    marks = result['marks']
    assert marks['afterSteps'] == [0, 1, 2], marks
    # seek to 10 gaps: the next message is the 11th (played 10), nothing between is sent
    assert marks['afterPause'][3:5] == [10, 11], marks
    assert marks['afterPauseWait'] == marks['afterPause'], marks
    assert marks['end'] == [0, 1, 2] + list(range(10, COUNT)), marks
    assert result['state']['state'] == 'ended', result['state']
    bar = result['bar']
    expected = {'opened': 'paused', 'stepped': 'paused', 'playing': 'playing',
                'paused': 'paused', 'ended': 'ended'}
    assert {k: (v['state'], v['label']) for k, v in bar.items()} == \
        {k: (s, s) for k, s in expected.items()}, bar
    assert {k: v['icon'] for k, v in bar.items()} == {
        'opened': 'play', 'stepped': 'play', 'playing': 'pause', 'paused': 'play',
        'ended': 'replay'}, bar
    assert all(v['iconDrawn'] for v in bar.values()), bar
    duration = re.fullmatch(r'0\.0 s / (\d+\.\d s)', bar['opened']['position']).group(1)
    assert bar['ended']['position'] == f'{duration} / {duration}', bar
    # the position field keeps one line and one width; the bar does not grow
    assert {v['positionLines'] for v in bar.values()} == {1}, bar
    assert len({v['positionWidth'] for v in bar.values()}) == 1, bar
    assert not any(v['positionClipped'] for v in bar.values()), bar
    assert len({v['barHeight'] for v in bar.values()}) == 1, bar
    # at 1024 px, the narrowest width the page is made for
    assert not any(v['barOverflow'] > 0 or v['pageOverflow'] > 0 for v in bar.values()), bar
    assert not any(v['inHeader'] for v in bar.values()), bar


def test_the_page_replay_drives_a_use_sim_time_rclcpp_node_with_clock(tmp_path):
    """/clock ticked on the page gives the probe's sim_time (rclcpp) the bag's time."""
    from rclcpp_build import rclcpp_build
    from test_play_sim_time import _write_bag, COUNT, GAP_NS, START_NS
    install = rclcpp_build().install
    bag = tmp_path / 'bag'
    _write_bag(bag)
    with ServedPage(install) as page:
        result = _drive(page, mode='clock', bag=str(next(bag.glob('*.mcap'))),
                        pkg='rmw_wasm_cpp_node_tests', exe='probe',
                        args=['sim_time', '--ros-args', '-p', 'use_sim_time:=true'],
                        until=r'SIM_TIME \d+')
    log = '\n'.join(result['logs']['node'])
    assert 'USE_SIM_TIME true' in log, log
    seconds = float(re.search(r'SIM_TIME (\d+\.\d)', log).group(1))
    first, last = START_NS / 1e9, (START_NS + (COUNT - 1) * GAP_NS) / 1e9
    assert first <= seconds <= last + 0.1, (seconds, first, last, log)
