# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
An MCAP file written chunk by chunk, from chunks built elsewhere.

The records of a chunk (Message records) and its MessageIndex records are
built where the messages are: in the Node host's recording worker for
``--record`` (packages/wasm_js/src/bridges/record/chunk_builder.mjs), or
by :class:`ChunkBuffer` here for the recorders that get one message at a
time (``colcon-wasm record``, the page's Record). This module puts them in
a file: the Chunk record around the records (compressed with ``zstandard``
or ``lz4``, with the CRC of the uncompressed records), the MessageIndex
records after it, and the summary (schemas, channels, statistics, chunk
indexes, metadata indexes, summary offsets) at the end. Uncompressed
chunks of ``--record`` are written by the recording worker itself, which
reports where (:meth:`McapFile.note_chunk`).

Every other record is encoded by Foxglove's ``mcap`` package
(``mcap.records``). The Chunk record's head is packed here, so that a chunk
of images is not copied into another buffer on its way to the file, and
``mcap.writer.Writer`` is not used because it takes messages one at a time
(docs/record.md measures what that costs).
"""

import struct
import zlib

from mcap.data_stream import RecordBuilder
from mcap.opcode import Opcode
from mcap.records import Channel
from mcap.records import ChunkIndex
from mcap.records import DataEnd
from mcap.records import Footer
from mcap.records import Header
from mcap.records import Metadata
from mcap.records import MetadataIndex
from mcap.records import Schema
from mcap.records import Statistics
from mcap.records import SummaryOffset
from mcap.writer import MCAP0_MAGIC

COMPRESSIONS = ('none', 'zstd', 'lz4')

# opcode, record length, start, end, uncompressed size, uncompressed CRC
_CHUNK_HEAD = struct.Struct('<BQQQQI')
# channel id, sequence, log time, publish time (after opcode and length)
_MESSAGE_HEAD = struct.Struct('<BQHIQQ')
_MESSAGE_INDEX_HEAD = struct.Struct('<BQHI')
_INDEX_ENTRY = struct.Struct('<QQ')


def _compressor(name):
    if name == 'zstd':
        import zstandard
        return zstandard.ZstdCompressor().compress
    if name == 'lz4':
        import lz4.frame
        return lz4.frame.compress
    return None


class ChunkBuffer:
    """
    The records of one chunk and its message indexes, a message at a time.

    The Python twin of the tools worker's chunk builder, for recorders that
    receive messages one by one.
    """

    def __init__(self):
        """Start an empty chunk."""
        self.records = bytearray()
        self.index = {}
        self.start = None
        self.end = None
        self.messages = 0

    def add(self, channel, log_time, publish_time, data, sequence=0):
        """Append one Message record (times in nanoseconds)."""
        offset = len(self.records)
        self.records += _MESSAGE_HEAD.pack(Opcode.MESSAGE, 22 + len(data), channel,
                                           sequence, log_time, publish_time)
        self.records += data
        self.index.setdefault(channel, []).append((log_time, offset))
        self.start = log_time if self.start is None else min(self.start, log_time)
        self.end = log_time if self.end is None else max(self.end, log_time)
        self.messages += 1

    def message_indexes(self):
        """Encode the MessageIndex records: ``(bytes, [(channel, count, length), ...])``."""
        out = bytearray()
        channels = []
        for channel, entries in self.index.items():
            body = b''.join(_INDEX_ENTRY.pack(t, o) for t, o in entries)
            out += _MESSAGE_INDEX_HEAD.pack(Opcode.MESSAGE_INDEX, 6 + len(body), channel,
                                            len(body))
            out += body
            channels.append((channel, len(entries), 15 + len(body)))
        return bytes(out), channels


def drop_channels(records, drop):
    """
    Rebuild a chunk's records without the messages of the channels in ``drop``.

    :returns: a :class:`ChunkBuffer` with the other messages
    :raises ValueError: on records that are not Message records
    """
    kept = ChunkBuffer()
    view = memoryview(records)
    at = 0
    while at < len(view):
        opcode, length, channel, sequence, log_time, publish_time = \
            _MESSAGE_HEAD.unpack_from(view, at)
        if opcode != Opcode.MESSAGE or length < 22:
            raise ValueError(f'chunk byte {at}: opcode {opcode:#x} (length {length}) '
                             'is no Message record')
        end = at + 9 + length
        if channel not in drop:
            kept.add(channel, log_time, publish_time, view[at + _MESSAGE_HEAD.size:end],
                     sequence)
        at = end
    return kept


class McapFile:
    """
    One MCAP file written as it goes: each chunk reaches the sink at once.

    ``sink`` has ``write(*parts)`` (bytes-like parts, written in one go)
    and ``tell()``; each ``write`` is whole records, so a sink that knows
    the last whole write can cut a failed write off
    (:mod:`colcon_wasm.record.bag_writer`).
    """

    def __init__(self, sink, *, compression='none', profile='', library=''):
        """Write the magic and the Header."""
        if compression not in COMPRESSIONS:
            raise ValueError(f"unknown chunk compression '{compression}': "
                             f"use one of {', '.join(COMPRESSIONS)}")
        self._sink = sink
        self._compression = '' if compression == 'none' else compression
        self._compress = _compressor(compression)
        self._schemas = []
        self._channels = []
        self._chunk_indexes = []
        self._metadata_indexes = []
        self._counts = {}
        self._messages = 0
        self._start = None
        self._end = None
        builder = RecordBuilder()
        builder.write(MCAP0_MAGIC)
        Header(profile=profile, library=library).write(builder)
        sink.write(builder.end())

    def add_schema(self, schema_id, name, encoding, data):
        """Write a Schema record (also repeated in the summary)."""
        schema = Schema(id=schema_id, name=name, encoding=encoding, data=data)
        self._write_records([schema])
        self._schemas.append(schema)

    def add_channel(self, channel_id, topic, message_encoding, schema_id, metadata):
        """Write a Channel record (also repeated in the summary)."""
        channel = Channel(id=channel_id, topic=topic, message_encoding=message_encoding,
                          schema_id=schema_id, metadata=metadata)
        self._write_records([channel])
        self._channels.append(channel)
        self._counts.setdefault(channel_id, 0)

    def add_chunk(self, records, start, end, indexes, channels):
        """
        Write a chunk: its Chunk record, then its MessageIndex records.

        :param records: the chunk's Message records (bytes-like)
        :param start: the earliest log time in it (ns)
        :param end: the latest log time in it (ns)
        :param indexes: its MessageIndex records, one per channel, in ``channels`` order
        :param channels: ``[(channel id, message count, index record length), ...]``
        """
        size = len(records)
        crc = zlib.crc32(records)
        data = self._compress(records) if self._compress else records
        compression = self._compression.encode('ascii')
        length = 8 + 8 + 8 + 4 + 4 + len(compression) + 8 + len(data)
        head = (_CHUNK_HEAD.pack(Opcode.CHUNK, length, start, end, size, crc)
                + struct.pack('<I', len(compression)) + compression
                + struct.pack('<Q', len(data)))
        chunk_start = self._sink.tell()
        self._sink.write(head, data)
        self._sink.write(indexes)
        self._index_chunk(chunk_start, len(head) + len(data), start, end, channels,
                          len(indexes), self._compression, len(data), size)

    def note_chunk(self, offset, chunk_length, start, end, channels, index_length, size):
        """
        Index an uncompressed chunk written into the file by someone else.

        The Node host's recording worker writes chunks into the bag itself
        (packages/wasm_js/src/bridges/record/file_sink.mjs): the Chunk
        record at ``offset`` (``chunk_length`` bytes), then its MessageIndex
        records, one per channel in ``channels`` order.

        :param channels: ``[(channel id, message count, index record length), ...]``
        :param size: the length of its records
        """
        self._index_chunk(offset, chunk_length, start, end, channels, index_length, '', size,
                          size)

    def _index_chunk(self, chunk_start, chunk_length, start, end, channels, index_length,
                     compression, compressed_size, size):
        offsets = {}
        at = chunk_start + chunk_length
        for channel, count, channel_index_length in channels:
            offsets[channel] = at
            at += channel_index_length
            self._counts[channel] = self._counts.get(channel, 0) + count
            self._messages += count
        self._chunk_indexes.append(ChunkIndex(
            message_start_time=start, message_end_time=end, chunk_start_offset=chunk_start,
            chunk_length=chunk_length, message_index_offsets=offsets,
            message_index_length=index_length, compression=compression,
            compressed_size=compressed_size, uncompressed_size=size))
        self._start = start if self._start is None else min(self._start, start)
        self._end = end if self._end is None else max(self._end, end)

    def add_buffer(self, chunk):
        """Write the chunk of a :class:`ChunkBuffer` (nothing when it is empty)."""
        if not chunk.messages:
            return
        indexes, channels = chunk.message_indexes()
        self.add_chunk(chunk.records, chunk.start, chunk.end, indexes, channels)

    def add_metadata(self, name, data):
        """Write a Metadata record (indexed in the summary)."""
        offset = self._sink.tell()
        length = self._write_records([Metadata(name=name, metadata=data)])
        self._metadata_indexes.append(MetadataIndex(offset=offset, length=length, name=name))

    def finish(self):
        """Write DataEnd, the summary, the Footer and the closing magic."""
        self._write_records([DataEnd(data_section_crc=0)])
        summary_start = self._sink.tell()
        builder = RecordBuilder()
        offsets = []
        statistics = Statistics(
            message_count=self._messages, schema_count=len(self._schemas),
            channel_count=len(self._channels), attachment_count=0,
            metadata_count=len(self._metadata_indexes), chunk_count=len(self._chunk_indexes),
            message_start_time=self._start or 0, message_end_time=self._end or 0,
            channel_message_counts=dict(self._counts))
        groups = ((Opcode.SCHEMA, self._schemas), (Opcode.CHANNEL, self._channels),
                  (Opcode.STATISTICS, [statistics]), (Opcode.CHUNK_INDEX, self._chunk_indexes),
                  (Opcode.METADATA_INDEX, self._metadata_indexes))
        for opcode, group in groups:
            if not group:
                continue
            group_start = builder.count
            for record in group:
                record.write(builder)
            offsets.append(SummaryOffset(group_opcode=opcode,
                                         group_start=summary_start + group_start,
                                         group_length=builder.count - group_start))
        summary_offset_start = summary_start + builder.count
        for offset in offsets:
            offset.write(builder)
        summary = builder.end()
        crc = zlib.crc32(summary)
        crc = zlib.crc32(struct.pack('<BQQQ', Opcode.FOOTER, 20, summary_start,
                                     summary_offset_start), crc)
        tail = RecordBuilder()
        Footer(summary_start=summary_start, summary_offset_start=summary_offset_start,
               summary_crc=crc).write(tail)
        tail.write(MCAP0_MAGIC)
        self._sink.write(summary)
        self._sink.write(tail.end())

    def _write_records(self, records):
        builder = RecordBuilder()
        for record in records:
            record.write(builder)
        data = builder.end()
        self._sink.write(data)
        return len(data)
