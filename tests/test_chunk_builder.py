# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Chunks built in the recording worker, put into a bag with the launcher.

`--record` copies each message from the bus into the MCAP Message records
of a chunk in the Node host's recording worker
(packages/wasm_js/src/bridges/record/chunk_builder.mjs). Uncompressed, the
worker writes each chunk into the bag itself (file_sink.mjs) after the
Schema and Channel records the launcher hands it, and the launcher indexes
what it reports and writes the summary; compressed, the chunks go through
the pipe's frame format to the launcher, which wraps them in their Chunk
records (colcon_wasm/record/mcap_file.py). Here a real bus in Node.js
carries small messages and ~900 KiB frames on two topics into that builder,
both ways, and Foxglove's `mcap` (with CRC checks) and `rosbags` read the
file: every message, in order, with its bytes, on its channel, with the
chunk and message indexes. No build is needed (the end-to-end path is
tests/test_record.py).
"""

import io
import json
from pathlib import Path
import struct
import subprocess

from colcon_wasm.record import frames
from colcon_wasm.record.bag_writer import BagWriter
from colcon_wasm.record.mcap_file import ChunkBuffer
from colcon_wasm.record.mcap_file import drop_channels
import mcap.reader as mcap_reader
import mcap.stream_reader as stream_reader
import pytest
import rosbags.highlevel as rosbags_highlevel

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / 'packages' / 'wasm_js' / 'src'
TYPE = 'test_msgs/msg/Bytes'


def _frame(round_):
    """Return the check's frame number `round_` (tests/js/chunk_builder_check.mjs)."""
    pattern = bytes((7 * j + 13 * round_) & 255 for j in range(256))
    size = 900 * 1024 + round_
    return (pattern * (size // 256 + 1))[:size]


class _Schemas:
    """The one type of the check, described as rosbag2 would."""

    def full_text(self, type_name):
        assert type_name == TYPE
        return 'uint8[] data\n'


def _check(*args, pass_fds=()):
    done = subprocess.run(['node', str(HERE / 'js' / 'chunk_builder_check.mjs'), str(SRC),
                           *map(str, args)], capture_output=True, text=True, timeout=120,
                          pass_fds=pass_fds)
    assert done.returncode == 0, done.stdout + done.stderr
    return json.loads(done.stdout)


def _worker_chunks(tmp_path):
    """Run the JS side in pipe mode; return (report, chunk frames)."""
    out = tmp_path / 'chunks.bin'
    report = _check('pipe', out)
    chunks = [bytes(body) for kind, body in frames.read_frames(io.BytesIO(out.read_bytes()))
              if kind == frames.CHUNK]
    return report, chunks


def _uncompressed(chunk):
    if chunk.compression == 'zstd':
        import zstandard
        return zstandard.ZstdDecompressor().decompress(chunk.data, chunk.uncompressed_size)
    if chunk.compression == 'lz4':
        import lz4.frame
        return lz4.frame.decompress(chunk.data)
    return chunk.data


def _record(path, chunks, channels, compression='none'):
    writer = BagWriter(path, _Schemas(), compression=compression)
    for channel, topic in channels:
        assert writer.add_topic(topic, TYPE, [], channel=channel) == channel
    for body in chunks:
        writer.write_chunk(*frames.decode_chunk(body))
    writer.close()
    assert not writer.failed
    return writer


def _written_by_the_worker(path, tmp_path):
    """File mode: the launcher's BagWriter and the worker's file sink share the bag."""
    writer = BagWriter(path, _Schemas(), host_writes=True)
    for channel, topic in ((1, '/small'), (2, '/frames')):
        assert writer.add_topic(topic, TYPE, [], channel=channel) == channel
    records = tmp_path / 'records.bin'
    records.write_bytes(writer.records_for_host())
    report = _check('file', writer.fileno(), writer.host_offset, records,
                    pass_fds=(writer.fileno(),))
    for written in report['reports']:
        writer.host_wrote(written)
    writer.close()
    assert not writer.failed
    return report, writer


@pytest.mark.parametrize('compression', ['file', 'none', 'zstd', 'lz4'])
def test_worker_chunks_make_a_bag_that_mcap_and_rosbags_read(tmp_path, compression):
    bag = tmp_path / 'worker.mcap'
    if compression == 'file':
        report, writer = _written_by_the_worker(bag, tmp_path)
        chunks = report['chunks']
        # the records first, then one report per chunk, two chunks a write
        writes = [[r['kind'] for r in written] for written in report['reports']]
        assert [kind for w in writes for kind in w] == ['records'] + ['chunk'] * len(chunks)
        assert ['chunk', 'chunk'] in writes, writes
        # chunks built in pool slots (staged, moved in place) and in buffers of their own
        assert 0 < report['inSlots'] < len(chunks), report['inSlots']
    else:
        report, chunks = _worker_chunks(tmp_path)
        writer = _record(bag, chunks, [(1, '/small'), (2, '/frames')], compression)
    published = report['published']
    # a 900 KiB frame leaves no room for the next in a 1 MiB chunk
    assert len(chunks) >= 6, f'{len(chunks)} chunks for six frames'
    assert writer.messages == len(published)

    with open(bag, 'rb') as f:
        reader = mcap_reader.make_reader(f)
        summary = reader.get_summary()
        assert summary.statistics.message_count == len(published)
        assert summary.statistics.channel_message_counts == {
            1: sum(1 for p in published if p[0] == 1), 2: 6}
        assert len(summary.chunk_indexes) == len(chunks)
        assert all(c.message_index_offsets for c in summary.chunk_indexes)
        assert {c.compression for c in summary.chunk_indexes} == {
            '' if compression in ('none', 'file') else compression}
        got = {1: [], 2: []}
        times = {1: [], 2: []}
        # the message indexes are used here (log_time_order): they must point at the records
        for _, channel, message in reader.iter_messages(log_time_order=True):
            got[channel.id].append((len(message.data), message.data[0]))
            if channel.id == 2:
                # every byte of a frame, wherever its record lies in the chunk
                assert message.data == _frame(len(message.data) - 900 * 1024)
            times[channel.id].append(message.log_time)
            assert message.publish_time == message.log_time
    for channel in (1, 2):
        assert got[channel] == [(n, b) for c, n, b in published if c == channel]
        assert times[channel] == sorted(times[channel])
    # the bus times are nanoseconds since the epoch
    assert 1.6e18 < times[1][0] < 4e18

    # every record, with the chunk and summary CRCs checked, read as a stream
    with open(bag, 'rb') as f:
        records = list(stream_reader.StreamReader(f, validate_crcs=True).records)
    assert sum(type(r).__name__ == 'Message' for r in records) == len(published)
    with open(bag, 'rb') as f:
        records = list(stream_reader.StreamReader(f, validate_crcs=True, emit_chunks=True).records)
    chunk_records = [r for r in records if type(r).__name__ == 'Chunk']
    assert len(chunk_records) == len(chunks)
    assert all(r.uncompressed_crc for r in chunk_records)
    # each message index entry points at a Message record of its channel and time
    chunk = None
    indexed = 0
    for r in records:
        if type(r).__name__ == 'Chunk':
            chunk = _uncompressed(r)
        elif type(r).__name__ == 'MessageIndex':
            for log_time, offset in r.records:
                opcode, _, channel, _, at_time = struct.unpack_from('<BQHIQ', chunk, offset)
                assert (opcode, channel, at_time) == (0x05, r.channel_id, log_time)
                indexed += 1
    assert indexed == len(published)

    with rosbags_highlevel.AnyReader([bag]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        assert counts == {'/small': len(published) - 6, '/frames': 6}
        frames_read = [raw for c, _, raw in reader.messages() if c.topic == '/frames']
        assert [bytes(f) for f in frames_read] == [_frame(r) for r in range(6)]


def test_a_channel_the_bag_has_no_topic_for_is_left_out(tmp_path):
    report, chunks = _worker_chunks(tmp_path)
    bag = tmp_path / 'small_only.mcap'
    writer = _record(bag, chunks, [(1, '/small')])
    small = [p for p in report['published'] if p[0] == 1]
    assert writer.messages == len(small)
    with open(bag, 'rb') as f:
        reader = mcap_reader.make_reader(f)
        got = [(len(m.data), m.data[0]) for _, _, m in reader.iter_messages()]
        assert reader.get_summary().statistics.channel_message_counts == {1: len(small)}
    assert got == [(n, b) for _, n, b in small]


def test_drop_channels_rejects_records_that_are_no_messages():
    chunk = ChunkBuffer()
    chunk.add(1, 5, 5, b'abc')
    broken = bytes(chunk.records[:1]) and b'\x06' + bytes(chunk.records[1:])
    with pytest.raises(ValueError, match=r'chunk byte 0: opcode 0x6'):
        drop_channels(broken, {2})
    kept = drop_channels(bytes(chunk.records), {2})
    assert kept.messages == 1 and bytes(kept.records) == bytes(chunk.records)
