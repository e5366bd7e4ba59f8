# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Record and replay (colcon_wasm/record/, packages/wasm_js/src/bridges/record/).

Third-party code on both sides: what `--record` writes from the demo (built
by real Emscripten, run in Node.js) is read by Foxglove's `mcap` and
`mcap-ros2-support` and by `rosbags`; a bag written by `rosbags` plays into
the demo's C++ listener. The played timing is measured by recording the
replay. Bad input: truncated and corrupt files, a type the workspace does
not know, a full disk while recording.
"""

import os
from pathlib import Path
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100
import pytest  # noqa: E402, I100, I202
mcap_reader = pytest.importorskip('mcap.reader')
mcap_ros2_decoder = pytest.importorskip('mcap_ros2.decoder')
rosbags_highlevel = pytest.importorskip('rosbags.highlevel')
rosbags_rosbag2 = pytest.importorskip('rosbags.rosbag2')
rosbags_typesys = pytest.importorskip('rosbags.typesys')
from mcap.records import Chunk, Footer, Message  # noqa: E402, I100
from mcap.stream_reader import breakup_chunk, StreamReader  # noqa: E402, I100

CHATTER = 'demo_interfaces/msg/Chatter'
FRAME = 'demo_interfaces/msg/Frame'


@pytest.fixture(scope='module')
def install():
    """Build the demo workspace (once per test run)."""
    return demo_build.demo_install()


def colcon_wasm(*args, timeout=120, preexec_fn=None):
    """Run the colcon-wasm command; return (exit status, stdout, stderr)."""
    result = subprocess.run([str(demo_build.venv_tool('colcon-wasm')), *map(str, args)],
                            capture_output=True, text=True, timeout=timeout,
                            preexec_fn=preexec_fn)
    return result.returncode, result.stdout, result.stderr


def frame_pixels(frame, width=160, height=120):
    """Draw the demo camera's frame number `frame` (demo/src/demo_nodes/src/camera.cpp)."""
    side = height // 4
    x0 = (frame * 4) % (width - side if width > side else 1)
    y0 = height // 2 - side // 2
    rows = []
    for y in range(height):
        row = bytearray()
        for x in range(width):
            if x0 <= x < x0 + side and y0 <= y < y0 + side:
                row += b'\xff\xff\xff'
            else:
                row += bytes((255 * x // width, 255 * y // height, 96))
        rows.append(bytes(row))
    return b''.join(rows)


def mcap_messages(path):
    """Decode a bag with mcap + mcap-ros2-support: [(topic, log, publish, decoded, raw)]."""
    with open(path, 'rb') as f:
        reader = mcap_reader.make_reader(f, decoder_factories=[mcap_ros2_decoder.DecoderFactory()])
        return [(c.topic, m.log_time, m.publish_time, d, m.data)
                for _, c, m, d in reader.iter_decoded_messages(log_time_order=False)]


@pytest.fixture(scope='module')
def recorded(install, tmp_path_factory):
    """Record the demo talker and camera for 4 s."""
    path = tmp_path_factory.mktemp('record') / 'demo.mcap'
    started = time.time_ns()
    code, out, err = colcon_wasm('launch', '--install-base', install, '--duration', '4',
                                 '--record', path, 'demo_nodes/talker', 'demo_nodes/camera')
    stopped = time.time_ns()
    assert code == 0, out + err
    return {'path': path, 'out': out, 'err': err, 'started': started, 'stopped': stopped}


def test_the_recording_is_rosbag2_mcap_read_by_mcap(install, recorded):
    path = recorded['path']
    assert re.search(r"recorded \d+ messages into '.*demo\.mcap'", recorded['err']), \
        recorded['err']
    with open(path, 'rb') as f:
        reader = mcap_reader.make_reader(f)
        header = reader.get_header()
        summary = reader.get_summary()
        metadata = {m.name: m.metadata for m in reader.iter_metadata()}
    assert header.profile == 'ros2'
    schemas = {s.name: s for s in summary.schemas.values()}
    assert set(schemas) >= {CHATTER, FRAME}
    from colcon_wasm.launch.install_space import InstallSpace
    texts = InstallSpace(install).ros2msg_schemas()
    for name, schema in schemas.items():
        assert schema.encoding == 'ros2msg'
        assert schema.data.decode() == texts.full_text(name)
    channels = {c.topic: c for c in summary.channels.values()}
    assert set(channels) >= {'/chatter', '/camera/image'}
    import yaml
    for c in channels.values():
        assert c.message_encoding == 'cdr'
        offers = yaml.safe_load(c.metadata['offered_qos_profiles'])
        assert offers and offers[0]['reliability'] == 1 and offers[0]['durability'] == 2
    # chunked and indexed, in more than one chunk (closed at least once a second)
    assert len(summary.chunk_indexes) >= 2
    assert all(ci.message_index_offsets for ci in summary.chunk_indexes)
    info = yaml.safe_load(metadata['rosbag2']['serialized_metadata'])
    info = info['rosbag2_bagfile_information']
    assert info['storage_identifier'] == 'mcap'
    assert info['message_count'] == summary.statistics.message_count


def test_every_recorded_message_is_what_the_demo_published(recorded):
    messages = mcap_messages(recorded['path'])
    chatter = [m for m in messages if m[0] == '/chatter']
    frames = [m for m in messages if m[0] == '/camera/image']
    # the talker: 'Hello World: N', counts without a gap, up to the last one it logged
    counts = [d.count for _, _, _, d, _ in chatter]
    assert all(d.data == f'Hello World: {d.count}' for _, _, _, d, _ in chatter)
    logged = [int(n) for n in re.findall(r"Publishing: 'Hello World: (\d+)'", recorded['out'])]
    assert counts == list(range(counts[0], counts[-1] + 1)), counts
    assert counts[0] <= 2 and counts[-1] in (logged[-1], logged[-1] + 1), (counts, logged)
    # the camera: each frame is the demo's picture for consecutive frame numbers
    assert len(frames) >= 10  # 4 s at 10 Hz, less the start-up on a loaded machine
    first = next(k for k in range(40) if bytes(frames[0][3].data) == frame_pixels(k))
    for i, (_, _, _, d, _) in enumerate(frames):
        assert (d.width, d.height, d.encoding, d.step) == (160, 120, 'rgb8', 480)
        assert bytes(d.data) == frame_pixels(first + i), f'frame {first + i}'
    # times: inside the recording, in order per topic, about 100 ms apart for the camera
    for topic in ('/chatter', '/camera/image'):
        times = [m[1] for m in messages if m[0] == topic]
        assert times == sorted(times)
        assert all(recorded['started'] < t < recorded['stopped'] for t in times)
    assert all(m[2] <= m[1] for m in messages)
    gaps = [b[1] - a[1] for a, b in zip(frames, frames[1:])]
    assert 70e6 < sum(gaps) / len(gaps) < 250e6, gaps


def test_rosbags_reads_the_recording(recorded):
    expected = [(m[0], m[1], bytes(m[4])) for m in mcap_messages(recorded['path'])]
    with rosbags_highlevel.AnyReader([Path(recorded['path'])]) as reader:
        types = {c.topic: c.msgtype for c in reader.connections}
        assert types['/chatter'] == CHATTER and types['/camera/image'] == FRAME
        qos = {c.topic: c.ext.offered_qos_profiles for c in reader.connections}
        assert qos['/chatter'][0].reliability == rosbags_rosbag2.metadata.QosReliability.RELIABLE
        got = []
        for connection, timestamp, raw in reader.messages():
            message = reader.deserialize(raw, connection.msgtype)
            if connection.topic == '/chatter':
                assert message.data == f'Hello World: {message.count}'
            got.append((connection.topic, timestamp, bytes(raw)))
    assert sorted(got) == sorted(expected)


def _write_rosbags_bag(path, install, gaps_ms, extra_unknown=True):
    """Write a rosbag2 MCAP bag with rosbags: /chatter at these gaps, and an unknown type."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.rosbag2.metadata import (Qos, QosDurability, QosHistory, QosLiveliness,
                                          QosReliability, QosTime)
    from rosbags.typesys import get_typestore, get_types_from_msg, Stores
    typestore = get_typestore(Stores.EMPTY)
    msgdef = (Path(install).parent / 'src' / 'demo_interfaces' / 'msg' / 'Chatter.msg').read_text()
    typestore.register(get_types_from_msg(msgdef, CHATTER))
    unknown = 'robot_msgs/msg/Odd'
    typestore.register(get_types_from_msg('int32 value\n', unknown))
    infinite = QosTime(sec=9223372036, nsec=854775807)
    qos = Qos(QosHistory.KEEP_LAST, 5, QosReliability.RELIABLE, QosDurability.TRANSIENT_LOCAL,
              infinite, infinite, QosLiveliness.AUTOMATIC, infinite, False)
    Chatter = typestore.types[CHATTER]
    Odd = typestore.types[unknown]
    start = 1_700_000_000_000_000_000
    sent = []
    with Writer(path, version=8, storage_plugin=StoragePlugin.MCAP) as writer:
        chatter = writer.add_connection('/chatter', CHATTER, typestore=typestore,
                                        offered_qos_profiles=[qos])
        odd = writer.add_connection('/odd', unknown, typestore=typestore) \
            if extra_unknown else None
        t = start
        for i, gap in enumerate(gaps_ms):
            t += int(gap * 1e6)
            data = typestore.serialize_cdr(Chatter(data=f'played {i}', count=i),
                                           CHATTER)
            writer.write(chatter, t, data)
            sent.append((t, bytes(data)))
            if odd is not None:
                writer.write(odd, t + 1000, typestore.serialize_cdr(Odd(value=i), unknown))
    return sent


GAPS_MS = [0, 100, 50, 300, 20, 20, 500, 150, 80, 400, 60, 200]


def test_messages_lost_before_the_recorder_took_them_are_counted(install, tmp_path):
    # a talker whose history holds one message, at 2 kHz: the recorder, which
    # wakes at most every few milliseconds, finds most of them overwritten
    path = tmp_path / 'talker_at_2khz.mcap'
    code, out, err = colcon_wasm('run', '--install-base', install, '--duration', '3',
                                 '--record', path, 'demo_nodes', 'talker', '--ros-args',
                                 '-p', 'rate:=2000', '-p', 'depth:=1')
    assert code == 0, out + err
    said = re.search(r'(\d+) messages were lost before the recorder took them', err)
    assert said, err
    lost = int(said.group(1))
    assert re.search(rf"recorded \d+ messages into '.*talker_at_2khz\.mcap' \({lost} lost before",
                     err), err
    counts = [d.count for topic, _, _, d, _ in mcap_messages(path) if topic == '/chatter']
    assert lost > 0 and counts == sorted(counts)
    # every message from the first recorded one to the last published one is
    # either in the bag or counted as lost; none before the subscription is
    assert counts[-1] == max(int(n) for n in re.findall(r'Hello World: (\d+)', out))
    assert counts[-1] - counts[0] + 1 <= len(counts) + lost <= counts[-1]


def test_a_rosbags_bag_plays_into_the_cpp_listener_in_order_and_time(install, tmp_path):
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, GAPS_MS)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 bag, 'demo_nodes/listener')
    assert code == 0, out + err
    heard = re.findall(r'\[listener-1\] .*I heard: \[played (\d+)\]', out)
    assert heard == [str(i) for i in range(len(GAPS_MS))], out + err
    # the unknown type is named and skipped, the rest played
    assert re.search(r"skipping topic '/odd': the workspace does not know its type "
                     r"'robot_msgs/msg/Odd'", err), err
    played = [m for m in mcap_messages(replay) if m[0] == '/chatter']
    assert [bytes(m[4]) for m in played] == [d for _, d in sent]
    # the gaps are kept (generous bound for a loaded 2-core machine)
    want = [(b[0] - a[0]) / 1e6 for a, b in zip(sent, sent[1:])]
    got = [(b[1] - a[1]) / 1e6 for a, b in zip(played, played[1:])]
    assert all(abs(g - w) < 40 for g, w in zip(got, want)), list(zip(want, got))
    # the recorded offers reach the player's publisher (transient_local, depth 5)
    with open(replay, 'rb') as f:
        channels = mcap_reader.make_reader(f).get_summary().channels.values()
    import yaml
    offers = yaml.safe_load(next(c for c in channels if c.topic == '/chatter')
                            .metadata['offered_qos_profiles'])
    assert (offers[0]['durability'], offers[0]['reliability'], offers[0]['depth']) == (1, 1, 5)


def test_rate_and_topics(install, tmp_path):
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0] + [200] * 10)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--rate', '4', bag, '--topics', '/chatter')
    assert code == 0, out + err
    assert '/odd' not in err
    played = [m for m in mcap_messages(replay) if m[0] == '/chatter']
    assert len(played) == len(sent)
    took = (played[-1][1] - played[0][1]) / 1e6
    assert 400 < took < 900, took  # 2 s of bag at 4x: 500 ms


def _count_in(path, chunks):
    """Count the messages of some chunks (their indexes), read by mcap."""
    total = 0
    with open(path, 'rb') as f:
        for ci in chunks:
            f.seek(ci.chunk_start_offset)
            chunk = next(iter(StreamReader(f, skip_magic=True, emit_chunks=True).records))
            assert isinstance(chunk, Chunk)
            total += sum(isinstance(r, Message) for r in breakup_chunk(chunk))
    return total


def test_a_truncated_bag_plays_what_comes_before_and_names_the_record(install, recorded,
                                                                      tmp_path):
    chunks = _summary_chunks(recorded['path'])
    start, length = chunks[1].chunk_start_offset, chunks[1].chunk_length
    cut = tmp_path / 'cut.mcap'
    data = Path(recorded['path']).read_bytes()
    cut.write_bytes(data[:start + length // 2])
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--rate', '5', cut)
    assert code == 1, out + err
    assert (f'the Chunk record at byte offset {start} is cut off: the file ends at '
            f'byte {start + length // 2}') in err, err
    assert len(mcap_messages(replay)) == _count_in(recorded['path'], chunks[:1]), err


def _bag_info(path):
    code, out, err = colcon_wasm('bag-info', path)
    assert code == 0, out + err
    counts = dict(re.findall(r'Topic: (\S+) \| Type: \S+ \| Count: (\d+) \| '
                             r'Serialization Format: cdr', out))
    return out, {topic: int(n) for topic, n in counts.items()}


def test_bag_info_prints_what_ros2_bag_info_prints(install, recorded, tmp_path):
    messages = mcap_messages(recorded['path'])
    times = [m[1] for m in messages]
    want = {}
    for m in messages:
        want[m[0]] = want.get(m[0], 0) + 1
    out, counts = _bag_info(recorded['path'])
    assert counts == want, out
    assert f'\nMessages:          {len(messages)}\n' in out, out
    assert f'\nDuration:          {(max(times) - min(times)) / 1e9:.3f}s\n' in out, out
    start = min(times) // 1000000
    assert f'({start // 1000}.{start % 1000:03d})' in out.split('\nStart:')[1].split('\n')[0]
    assert out.startswith('Files:             demo.mcap\nBag size:') and \
        'Storage id:        mcap' in out, out
    # a rosbag2 directory written by rosbags
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0, 100, 100])
    out, counts = _bag_info(bag)
    assert counts == {'/chatter': len(sent), '/odd': len(sent)}, out
    assert 'Type: robot_msgs/msg/Odd' in out and 'Duration:          0.200s' in out, out
    # a file cut off in its second chunk: what comes before, counted by reading
    chunks = _summary_chunks(recorded['path'])
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(Path(recorded['path']).read_bytes()[:chunks[1].chunk_start_offset + 10])
    out, counts = _bag_info(cut)
    assert sum(counts.values()) == _count_in(recorded['path'], chunks[:1]), out
    assert f'the Chunk record at byte offset {chunks[1].chunk_start_offset} is cut off' in out
    code, out, err = colcon_wasm('bag-info', tmp_path / 'nothing.mcap')
    assert code == 1 and "colcon-wasm bag-info: no bag at '" in err, err


def _summary_chunks(path):
    with open(path, 'rb') as f:
        return mcap_reader.make_reader(f).get_summary().chunk_indexes


def test_a_corrupt_chunk_is_named_by_offset(install, recorded, tmp_path):
    chunks = _summary_chunks(recorded['path'])
    bad = tmp_path / 'bad.mcap'
    data = bytearray(Path(recorded['path']).read_bytes())
    target = chunks[1]
    middle = target.chunk_start_offset + target.chunk_length // 2
    data[middle:middle + 16] = bytes(b ^ 0xff for b in data[middle:middle + 16])
    bad.write_bytes(bytes(data))
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--rate', '5', bad)
    assert code == 1, out + err
    offset = target.chunk_start_offset
    assert re.search(rf'the Chunk record at byte offset {offset} is corrupt \(', err), err
    assert len(mcap_messages(replay)) == _count_in(recorded['path'], chunks[:1])


def test_not_an_mcap_file(install, tmp_path):
    bad = tmp_path / 'bad.mcap'
    bad.write_bytes(b'not a bag at all')
    code, out, err = colcon_wasm('play', '--install-base', install, bad)
    assert code == 1
    assert 'is not an MCAP file' in err, err
    code, out, err = colcon_wasm('play', '--install-base', install, tmp_path / 'missing.mcap')
    assert code == 1 and "no bag at '" in err, err


def _small_disk(tmp_path):
    """Make a 1.6 MB tmpfs when this machine lets us mount one, else a file size limit."""
    mount = tmp_path / 'disk'
    mount.mkdir()
    if os.geteuid() == 0 and shutil.which('mount'):
        r = subprocess.run(['mount', '-t', 'tmpfs', '-o', 'size=1600k', 'tmpfs', str(mount)],
                           capture_output=True)
        if r.returncode == 0:
            return mount, None, 'the disk is full'

    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (1600 * 1024, 1600 * 1024))
    return mount, limit, 'the file size limit is reached'


def test_a_full_disk_stops_recording_and_the_file_stays_readable(install, tmp_path):
    disk, limit, why = _small_disk(tmp_path)
    try:
        path = disk / 'full.mcap'
        code, out, err = colcon_wasm(
            'launch', '--install-base', install, '--duration', '6', '--record', path,
            '--record-compression', 'none', 'demo_nodes/camera', preexec_fn=limit)
        assert code == 1, out + err
        assert re.search(rf"recording to '.*full\.mcap' stopped: {why}", err), err
        # the nodes ran on to the end
        assert 'stopping every process after 6 s (--duration)' in out, out
        # a stream reader reads it to its footer, with no error: whole chunks only
        with open(path, 'rb') as f:
            records = list(StreamReader(f, validate_crcs=True).records)
        assert isinstance(records[-1], Footer)
        kept = [r for r in records if isinstance(r, Message)]
        assert len(kept) >= 5
        assert path.stat().st_size <= 1600 * 1024
    finally:
        if limit is None:
            subprocess.run(['umount', str(disk)], capture_output=True)


def test_record_options_are_checked(install, tmp_path):
    code, out, err = colcon_wasm('launch', '--install-base', install, '--record-topic', '/x',
                                 'demo_nodes/talker')
    assert code == 1 and '--record-topic selects what --record records' in err, err
    code, out, err = colcon_wasm('launch', '--install-base', install, '--record',
                                 tmp_path / 'no' / 'such' / 'x.mcap', 'demo_nodes/talker')
    assert code == 1 and 'does not exist' in err, err
    code, out, err = colcon_wasm('launch', '--install-base', install, '--record-regex', 'a',
                                 'demo_nodes/talker')
    assert code == 1 and '--record-regex selects what --record records' in err, err
    code, out, err = colcon_wasm('launch', '--install-base', install, '--record',
                                 tmp_path / 'x.mcap', '--record-exclude', '(camera',
                                 'demo_nodes/talker')
    assert code == 1 and "--record-exclude '(camera' is not a regular expression" in err, err


def test_record_regex_and_exclude_choose_the_topics(install, tmp_path):
    # the talker publishes /chatter, the camera /camera/image and /camera/camera_info
    topics = {}
    for name, options in [('regex', ['--record-regex', '^/cam.*/image$',
                                     '--record-topic', '/chatter']),
                          ('exclude', ['--record-exclude', 'camera|rosout|parameter'])]:
        path = tmp_path / f'{name}.mcap'
        code, out, err = colcon_wasm('launch', '--install-base', install, '--duration', '3',
                                     '--record', path, *options, 'demo_nodes/talker',
                                     'demo_nodes/camera')
        assert code == 0, out + err
        topics[name] = {m[0] for m in mcap_messages(path)}
    assert topics == {'regex': {'/camera/image', '/chatter'}, 'exclude': {'/chatter'}}, topics


@pytest.mark.parametrize('compression', ['zstd', 'lz4'])
def test_compressed_recordings_are_read_by_mcap_and_rosbags(install, tmp_path, compression):
    path = tmp_path / 'talk.mcap'
    code, out, err = colcon_wasm('launch', '--install-base', install, '--duration', '3',
                                 '--record', path, '--record-compression', compression,
                                 '--record-topic', '/camera/image', 'demo_nodes/camera')
    assert code == 0, out + err
    with open(path, 'rb') as f:
        chunks = mcap_reader.make_reader(f).get_summary().chunk_indexes
    assert chunks and all(ci.compression == compression for ci in chunks)
    assert all(ci.compressed_size < ci.uncompressed_size for ci in chunks)
    frames = mcap_messages(path)
    assert len(frames) >= 15 and {m[0] for m in frames} == {'/camera/image'}
    with rosbags_highlevel.AnyReader([path]) as reader:
        got = [bytes(raw) for _, _, raw in reader.messages()]
    assert got == [bytes(m[4]) for m in frames]


def test_launch_play_and_clock(install, tmp_path):
    bag = tmp_path / 'bag'
    _write_rosbags_bag(bag, install, [0, 100, 100, 100], extra_unknown=False)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('launch', '--install-base', install, '--duration', '4',
                                 '--play', bag, '--clock', '--record', replay,
                                 'demo_nodes/listener')
    assert code == 0, out + err
    assert re.findall(r'I heard: \[played (\d+)\]', out) == ['0', '1', '2', '3'], out
    # /clock is published with its type; this workspace has no rosgraph_msgs to record it
    assert "not recording topic '/clock': no type description of " \
        "'rosgraph_msgs/msg/Clock'" in err, err
    assert 'process stopped' in out  # the nodes ran on after the bag, up to --duration


def test_a_crash_keeps_the_chunks_written_so_far(install, tmp_path):
    path = tmp_path / 'crash.mcap'
    process = subprocess.Popen(
        [str(demo_build.venv_tool('colcon-wasm')), 'launch', '--install-base', str(install),
         '--record', str(path), 'demo_nodes/camera'],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
    try:
        time.sleep(5)  # a chunk is closed at least once a second
    finally:
        os.killpg(process.pid, signal.SIGKILL)  # the launcher and the host, at once
        process.communicate(timeout=30)
    # no summary, no footer: a stream reader reads every whole chunk, then meets the end
    kept = 0
    with open(path, 'rb') as f:
        try:
            for record in StreamReader(f, validate_crcs=True).records:
                kept += isinstance(record, Message)
        except Exception as e:  # noqa: B902 (the end of a cut-off file)
            assert type(e).__name__ == 'EndOfFile', e
    assert kept >= 10
    # and it plays up to there, saying where it ends
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--rate', '10', path)
    assert code == 1, out + err
    assert re.search(r"'.*crash\.mcap' ends at byte \d+ without a Footer record|"
                     r'the Chunk record at byte offset \d+ is cut off', err), err
    assert len(mcap_messages(replay)) == kept


def test_loop_plays_the_bag_again(install, tmp_path):
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0, 100, 100], extra_unknown=False)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--loop', '--duration', '3', bag)
    assert code == 0, out + err
    played = [bytes(m[4]) for m in mcap_messages(replay)]
    rounds = len(played) // len(sent)
    assert rounds >= 3, played
    assert played[:rounds * len(sent)] == [d for _, d in sent] * rounds


def test_start_offset_skips_the_start_of_the_bag_in_every_round(install, tmp_path):
    # messages every 200 ms from 0 to 2 s; 1.1 s in, the first played is the one at 1.2 s
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0] + [200] * 10, extra_unknown=False)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--start-offset', '1.1', bag)
    assert code == 0, out + err
    played = [m for m in mcap_messages(replay) if m[0] == '/chatter']
    assert [bytes(m[4]) for m in played] == [d for _, d in sent[6:]], err
    took = (played[-1][1] - played[0][1]) / 1e6
    assert 600 < took < 1400, took  # 0.8 s of bag, played from its offset at once
    # with --loop, every round starts there, one mean gap after the last message
    replay = tmp_path / 'loop.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--loop', '--duration', '4', '--start-offset', '1.5', bag)
    assert code == 0, out + err
    played = [bytes(m[4]) for m in mcap_messages(replay)]
    rounds = len(played) // 3
    assert rounds >= 3 and played[:rounds * 3] == [d for _, d in sent[8:]] * rounds, played
    # past the last message: nothing is played, and the launcher says why
    code, out, err = colcon_wasm('play', '--install-base', install, '--start-offset', '5',
                                 bag)
    assert code == 0, out + err
    assert "--start-offset 5 s is past the bag's last message (2.000 s in): nothing played" \
        in err, err
    code, out, err = colcon_wasm('play', '--install-base', install, '--start-offset', '-1',
                                 bag)
    assert code == 2, out + err
    assert "argument --start-offset: '-1' is not a number of seconds (0 or more)" in err, err


def test_qos_override_file_sets_the_players_publishers(install, tmp_path):
    # the bag's /chatter was offered reliable, transient local, depth 5 (_write_rosbags_bag)
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0, 100, 100], extra_unknown=False)
    overrides = tmp_path / 'qos.yaml'
    overrides.write_text('/chatter:\n  reliability: best_effort\n  durability: volatile\n'
                         '  history: keep_last\n  depth: 3\n'
                         '  lifespan: {sec: 2, nsec: 500000000}\n', encoding='utf-8')
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay,
                                 '--qos-profile-overrides-path', overrides, bag)
    assert code == 0, out + err
    assert "topic '/chatter' plays with the QoS of the override file: history keep_last, " \
        'depth 3, reliability best_effort, durability volatile, lifespanMs 2500' in err, err
    played = [m for m in mcap_messages(replay) if m[0] == '/chatter']
    assert [bytes(m[4]) for m in played] == [d for _, d in sent]
    # the recorder saw the player's publisher offer the override's QoS
    with open(replay, 'rb') as f:
        channels = mcap_reader.make_reader(f).get_summary().channels.values()
    import yaml
    offer = yaml.safe_load(next(c for c in channels if c.topic == '/chatter')
                           .metadata['offered_qos_profiles'])[0]
    assert (offer['reliability'], offer['durability'], offer['depth']) == (2, 2, 3), offer
    assert offer['lifespan'] == {'sec': 2, 'nsec': 500000000}, offer
    # bad files: named with the topic and key, and nothing runs
    for text, said in [
            ('/chatter: {reliability: sometimes}\n',
             "topic '/chatter': reliability 'sometimes' is none of reliable, best_effort, "
             'system_default'),
            ('/chatter: {speed: 3}\n', "topic '/chatter': unknown key 'speed'"),
            ('- /chatter\n', 'must map topic names to profiles'),
            ('/chatter: {depth: -1}\n', "topic '/chatter': depth -1 is not a whole number")]:
        overrides.write_text(text, encoding='utf-8')
        code, out, err = colcon_wasm('play', '--install-base', install,
                                     '--qos-profile-overrides-path', overrides, bag)
        assert code == 1 and said in err and 'played' not in err, err
    code, out, err = colcon_wasm('play', '--install-base', install,
                                 '--qos-profile-overrides-path', tmp_path / 'none.yaml', bag)
    assert code == 1 and 'cannot read the QoS override file' in err, err


def test_remap_plays_a_topic_on_another_name(install, tmp_path):
    bag = tmp_path / 'bag'
    sent = _write_rosbags_bag(bag, install, [0, 100, 100], extra_unknown=False)
    replay = tmp_path / 'replay.mcap'
    code, out, err = colcon_wasm('play', '--install-base', install, '--record', replay, bag,
                                 '--remap', 'chatter:=/news')
    assert code == 0, out + err
    assert "topic '/chatter' plays on '/news' (--remap)" in err, err
    played = [(m[0], bytes(m[4])) for m in mcap_messages(replay)]
    assert played == [('/news', d) for _, d in sent], played
    for args, said in [
            (['play', bag, '--remap', '/chatter'], "--remap '/chatter' is not FROM:=TO"),
            (['launch', '--remap', 'a:=b', 'demo_nodes/talker'],
             '--remap renames topics of the bag --play plays: add --play BAG')]:
        code, out, err = colcon_wasm(args[0], '--install-base', install, *args[1:])
        assert code == 1 and said in err, err


HUMBLE_OFFER = (  # as `ros2 bag record -s mcap` on Humble writes a DDS publisher's offer
    '- history: 3\n  depth: 0\n  reliability: 2\n  durability: 2\n  deadline:\n'
    '    sec: 9223372036\n    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n'
    '    nsec: 854775807\n  liveliness: 1\n  liveliness_lease_duration:\n'
    '    sec: 9223372036\n    nsec: 854775807\n  avoid_ros_namespace_conventions: false')
IRON_OFFER = (  # Iron and later: policy names
    '- history: keep_last\n  depth: 7\n  reliability: reliable\n  durability: transient_local\n'
    '  deadline:\n    sec: 0\n    nsec: 0\n  lifespan:\n    sec: 2\n    nsec: 500000000\n'
    '  liveliness: automatic\n  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n'
    '  avoid_ros_namespace_conventions: false')


def test_recorded_offers_become_the_players_qos():
    from colcon_wasm.record.qos import player_qos, to_rosbag2
    assert player_qos(HUMBLE_OFFER) == {'history': 'keep_last', 'depth': 10,
                                        'reliability': 'best_effort', 'durability': 'volatile'}
    assert player_qos(IRON_OFFER) == {'history': 'keep_last', 'depth': 7,
                                      'reliability': 'reliable',
                                      'durability': 'transient_local', 'lifespanMs': 2500.0}
    # offers that disagree: reliable and volatile, as rosbag2's player falls back
    both = f'{HUMBLE_OFFER}\n{IRON_OFFER}'
    assert player_qos(both)['reliability'] == 'reliable'
    assert player_qos(both)['durability'] == 'volatile'
    assert player_qos('') == {'history': 'keep_last', 'depth': 10, 'reliability': 'reliable',
                              'durability': 'volatile'}
    # what the recorder writes reads back the same, and rosbags reads it
    text = to_rosbag2([{'history': 'keep_last', 'depth': 5, 'reliability': 'reliable',
                        'durability': 'transient_local', 'lifespanMs': 250}])
    assert player_qos(text) == {'history': 'keep_last', 'depth': 5, 'reliability': 'reliable',
                                'durability': 'transient_local', 'lifespanMs': 250.0}
    from rosbags.rosbag2.metadata import parse_qos, QosDurability
    assert parse_qos(text)[0].durability == QosDurability.TRANSIENT_LOCAL
    assert parse_qos(text)[0].lifespan.nsec == 250000000
