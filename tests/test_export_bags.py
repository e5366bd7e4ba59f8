# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Bags in an exported page (issue 41): played and recorded in the page, with no serve.

The demo is exported with ``--run demo_nodes/listener`` and served by
Python's ``http.server`` (tests/test_export.py's ``static_server``). In
Chromium (tests/js/page_bag.mjs, as a user clicks): a bag written by the
Python ``mcap`` writer in rosbag2's layout is dropped on the page, which
reads it itself (templates/launcher/bag_local.mjs) and plays it into the
exported listener through Step, seek, Play and Pause; the page records its
talker and camera and offers the MCAP file it built as a download, which
``mcap``, ``mcap-ros2-support`` and ``rosbags`` read; a zstd bag, a file
that is no MCAP and a cut bag are refused or named in the bar.
"""

import json
from pathlib import Path
import re
import subprocess
import sys

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from served_page import browser_skip_reason  # noqa: E402
from served_page import CHROMIUM  # noqa: E402
from served_page import JS  # noqa: E402
from test_export import _colcon_wasm  # noqa: E402
from test_export import static_server  # noqa: E402
from test_record import CHATTER  # noqa: E402
from test_record import frame_pixels  # noqa: E402
from test_record import mcap_messages  # noqa: E402

GAP_MS = 200
COUNT = 20
START_NS = 1_700_000_000_000_000_000
# what Humble's rosbag2 writes for a transient local, depth 5 publisher
HUMBLE_QOS = """- history: 1
  depth: 5
  reliability: 1
  durability: 1
  deadline:
    sec: 9223372036
    nsec: 854775807
  lifespan:
    sec: 9223372036
    nsec: 854775807
  liveliness: 1
  liveliness_lease_duration:
    sec: 9223372036
    nsec: 854775807
  avoid_ros_namespace_conventions: false"""


@pytest.fixture(scope='module')
def site(tmp_path_factory):
    """Export the demo with its listener, and serve the folder statically."""
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    install = demo_build.demo_install()
    target = tmp_path_factory.mktemp('export_bags') / 'site'
    done = _colcon_wasm('export', str(target), '--install-base', str(install),
                        '--run', 'demo_nodes/listener')
    assert done.returncode == 0, done.stderr
    with static_server(target) as url:
        yield {'target': target, 'url': url, 'install': install}


def _drive(site, **options):
    completed = subprocess.run(
        ['node', str(JS / 'page_bag.mjs'), json.dumps(
            dict(options, url=site['url'], chromium=CHROMIUM))],
        capture_output=True, text=True, timeout=240)
    lines = completed.stdout.strip().splitlines()
    assert lines, f'page_bag.mjs printed nothing: {completed.stderr[-3000:]}'
    result = json.loads(lines[-1])
    assert result['ok'], json.dumps(result, indent=1)[-6000:]
    assert not result['pageErrors'], result['pageErrors']
    return result


def _chatter_cdr(text, count):
    """demo_interfaces/msg/Chatter in CDR (little endian): string data, uint32 count."""
    data = text.encode() + b'\0'
    body = len(data).to_bytes(4, 'little') + data
    body += b'\0' * (-len(body) % 4)
    return b'\0\1\0\0' + body + count.to_bytes(4, 'little')


def _write_bag(path, install, compression='none', chunk_size=256):
    """Write /chatter (COUNT messages 'played i', GAP_MS apart) and /odd of an unknown type."""
    from colcon_wasm.launch.install_space import InstallSpace
    from mcap.writer import CompressionType, Writer
    text = InstallSpace(install).ros2msg_schemas().full_text(CHATTER)
    with open(path, 'wb') as f:
        writer = Writer(f, chunk_size=chunk_size,
                        compression={'none': CompressionType.NONE,
                                     'zstd': CompressionType.ZSTD}[compression])
        writer.start(profile='ros2', library='rosbag2 test')
        chatter = writer.register_channel(
            '/chatter', 'cdr', writer.register_schema(CHATTER, 'ros2msg', text.encode()),
            {'offered_qos_profiles': HUMBLE_QOS})
        odd = writer.register_channel(
            '/odd', 'cdr', writer.register_schema('robot_msgs/msg/Odd', 'ros2msg',
                                                  b'int32 value\n'),
            {'offered_qos_profiles': ''})
        for i in range(COUNT):
            t = START_NS + i * GAP_MS * 1_000_000
            writer.add_message(chatter, t, _chatter_cdr(f'played {i}', i), t)
            writer.add_message(odd, t + 1000, b'\0\1\0\0' + i.to_bytes(4, 'little'), t + 1000)
        writer.finish()


def test_the_export_says_the_page_does_bags_itself(site):
    workspace = json.loads((site['target'] / 'workspace.json').read_text())
    assert workspace['bag'] == {'local': True, 'problem': None}
    for name in ('launcher/bag_local.mjs', 'wasm_js/page/mcap_reader.mjs',
                 'wasm_js/page/mcap_writer.mjs', 'wasm_js/bridges/record/chunk_builder.mjs'):
        assert (site['target'] / name).is_file(), name


def test_a_bag_dropped_on_the_exported_page_plays_into_its_listener(site, tmp_path):
    bag = tmp_path / 'chatter.mcap'
    _write_bag(bag, site['install'])
    seek_ms = 10 * GAP_MS
    result = _drive(site, mode='play', bag=str(bag), seekMs=seek_ms, listener='autorun')
    info = result['info']
    assert info['count'] == COUNT, info  # /odd is not counted: its type is unknown
    assert info['error'] is None, info
    assert [t['topic'] for t in info['topics']] == ['/chatter'], info
    assert info['topics'][0]['type'] == CHATTER, info
    assert info['topics'][0]['qos'] == {'history': 'keep_last', 'depth': 5,
                                        'reliability': 'reliable',
                                        'durability': 'transient_local'}, info
    assert [s['topic'] for s in info['skipped']] == ['/odd'], info
    assert "does not know its type 'robot_msgs/msg/Odd'" in info['skipped'][0]['why'], info
    assert result['chip'] == 'chatter.mcap: 20 messages on 1 topic, 1 topic skipped', \
        result['chip']
    marks = result['marks']
    assert marks['afterSteps'] == [0, 1, 2], marks
    # seek to 10 gaps: the next message is the 11th, nothing between is sent
    assert marks['afterPause'][3:5] == [10, 11], marks
    assert marks['afterPauseWait'] == marks['afterPause'], marks  # nothing while paused
    assert marks['end'] == [0, 1, 2] + list(range(10, COUNT)), marks
    assert result['state']['state'] == 'ended', result['state']
    # the listener printed the recorded strings, in order
    heard = [line for line in result['logs']['listener'] if 'I heard' in line]
    assert [re.search(r'I heard: \[(played \d+)\]', line).group(1) for line in heard] == \
        [f'played {i}' for i in marks['end']], heard
    bar = result['bar']
    assert {k: v['state'] for k, v in bar.items()} == {
        'opened': 'paused', 'stepped': 'paused', 'playing': 'playing', 'paused': 'paused',
        'ended': 'ended'}, bar
    assert bar['ended']['position'] == '3.8 s / 3.8 s', bar


def test_recording_in_the_exported_page_downloads_an_mcap_file(site, tmp_path):
    from colcon_wasm.launch.install_space import InstallSpace
    from mcap.reader import make_reader
    out = tmp_path / 'download.mcap'
    blob = tmp_path / 'blob.mcap'
    result = _drive(site, mode='record', out=str(out), blobOut=str(blob), recordMs=2500)
    assert result['suggested'] == 'launcher.mcap', result
    assert result['blobUrl'].startswith('blob:'), result
    assert out.read_bytes() == blob.read_bytes()
    assert re.fullmatch(r'launcher\.mcap: \d+ messages', result['chip']), result['chip']
    messages = mcap_messages(out)
    chatter = [d for topic, _, _, d, _ in messages if topic == '/chatter']
    counts = [d.count for d in chatter]
    talker = '\n'.join(result['logs']['talker'])
    logged = [int(n) for n in re.findall(r"Hello World: (\d+)'", talker)]
    assert len(counts) >= 2, counts  # 2.5 s at 1 Hz
    assert counts == list(range(counts[0], counts[-1] + 1)), counts
    assert set(counts) <= set(logged), (counts, logged)
    assert all(d.data == f'Hello World: {d.count}' for d in chatter)
    frames = [d for topic, _, _, d, _ in messages if topic == '/camera/image']
    assert len(frames) >= 15, len(frames)  # 2.5 s at 10 Hz
    first = next(k for k in range(10000) if bytes(frames[0].data) == frame_pixels(k))
    for i, d in enumerate(frames):
        assert bytes(d.data) == frame_pixels(first + i), f'frame {first + i}'
    assert all(0 <= log - publish < 1e9 for _, log, publish, _, _ in messages)
    schemas = InstallSpace(site['install']).ros2msg_schemas()
    with open(out, 'rb') as f:
        reader = make_reader(f, validate_crcs=True)
        assert reader.get_header().profile == 'ros2'
        summary = reader.get_summary()
        assert summary.statistics.message_count == len(messages)
        assert summary.chunk_indexes
        for channel in summary.channels.values():
            schema = summary.schemas[channel.schema_id]
            assert schema.encoding == 'ros2msg' and channel.message_encoding == 'cdr'
            assert schema.data.decode() == schemas.full_text(schema.name), schema.name
    from rosbags import highlevel
    with highlevel.AnyReader([out]) as reader:
        qos = {c.topic: c.ext.offered_qos_profiles for c in reader.connections}
        assert qos['/chatter'], qos  # the page knows its publishers' QoS
        assert sum(1 for _ in reader.messages()) == len(messages)


def test_compressed_foreign_and_cut_bags_are_named_in_the_bar(site, tmp_path):
    zstd = tmp_path / 'zstd.mcap'
    _write_bag(zstd, site['install'], compression='zstd', chunk_size=1 << 20)
    foreign = tmp_path / 'notes.mcap'
    foreign.write_text('these are notes, not a bag\n')
    whole = tmp_path / 'whole.mcap'
    _write_bag(whole, site['install'])
    from mcap.reader import make_reader
    with open(whole, 'rb') as f:
        chunks = make_reader(f).get_summary().chunk_indexes
    middle = chunks[len(chunks) // 2].chunk_start_offset
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(whole.read_bytes()[:middle + 20])  # in the middle chunk
    result = _drive(site, mode='refuse', bags=[str(zstd), str(foreign), str(cut)])
    refused_zstd, refused_foreign, cut_open = result['refused']
    assert refused_zstd['status'].startswith(
        "'zstd.mcap': its chunks are compressed with zstd (the Chunk record at byte offset"), \
        refused_zstd
    assert "play it under 'colcon-wasm serve'" in refused_zstd['status'], refused_zstd
    assert 'mcap decompress IN.mcap -o OUT.mcap' in refused_zstd['status'], refused_zstd
    assert refused_zstd['playerHidden'] and refused_zstd['state'] == 'closed', refused_zstd
    assert refused_foreign['status'] == \
        "'notes.mcap' is not an MCAP file: it does not start with the MCAP magic", refused_foreign
    assert refused_foreign['playerHidden'], refused_foreign
    # a cut bag opens with what came before the cut, and says where it ends
    assert cut_open['status'].startswith(
        f"'cut.mcap': the Chunk record at byte offset {middle} is cut off"), cut_open
    assert not cut_open['playerHidden'] and cut_open['state'] == 'paused', cut_open
