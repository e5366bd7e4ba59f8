# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Write a bag: rosbag2's MCAP layout (records encoded by Foxglove's ``mcap``).

As Humble's rosbag2_storage_mcap writes it: profile ``ros2``; one schema per
type (encoding ``ros2msg``, the complete definition of
:mod:`colcon_wasm.ros2msg`); one channel per topic (encoding ``cdr``,
metadata ``offered_qos_profiles``); messages with their log and publish
times; chunked, with message indexes and a summary. Like rosbag2 from Iron
on (and rosbags), a metadata record ``rosbag2`` holds ``serialized_metadata``,
the bag's metadata.yaml.

The file is written as it goes: a chunk is closed when it is full or
``flush_interval`` seconds after its first message, and goes to the file at
once (unbuffered). A crash loses at most the open chunk; the file up to it
is readable by stream readers. When the disk is full (or the file size
limit is reached) the partly written record is cut off and a footer is
written when there is room for it, so the file ends after its last whole
chunk.

Chunks come whole from the Node host, which writes them into the file
itself when they are not compressed (``host_writes``: this side writes the
header, hands over the Schema and Channel records, indexes what the host
reports, and writes the summary), or sends them to be compressed
(``write_chunk``); or they are built here a message at a time (``write``).
:class:`colcon_wasm.record.mcap_file.McapFile` keeps the file's records and
indexes either way.
"""

import errno
import os
import time

from colcon_wasm import __version__
from colcon_wasm.record import BagError
from colcon_wasm.record.mcap_file import ChunkBuffer
from colcon_wasm.record.mcap_file import drop_channels
from colcon_wasm.record.mcap_file import McapFile
from colcon_wasm.record.page_cache import WrittenPages
from colcon_wasm.record.qos import to_rosbag2
from mcap.data_stream import RecordBuilder
from mcap.records import DataEnd
from mcap.records import Footer
from mcap.writer import MCAP0_MAGIC
import yaml
DEFAULT_CHUNK_SIZE = 1024 * 1024
DEFAULT_FLUSH_INTERVAL = 1.0
_FULL = (errno.ENOSPC, errno.EFBIG, errno.EDQUOT)


class _FileSink:
    """An unbuffered file the bag is written to; it knows the last whole write."""

    def __init__(self, path):
        self.path = path
        self.fd = os.open(str(path), os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        self.position = 0
        # the end of the last write that reached the file whole (each write
        # is whole records)
        self.good = 0
        # while the host writes the file: what is written here is kept for it
        self.captured = None
        # what is written is let go of from the page cache behind the writer
        self.pages = WrittenPages(self.fd)

    def hand_over(self):
        """Let the host write the file from here on (``write`` keeps the bytes for it)."""
        self.captured = bytearray()

    def take_captured(self):
        """Return the bytes written since the last call, for the host to write."""
        data = bytes(self.captured)
        self.captured.clear()
        return data

    def host_wrote_up_to(self, end):
        """Note that the host's writes reached ``end``: the pages behind it can go."""
        self.pages.wrote_up_to(end)

    def take_back(self, good):
        """
        Write the file here again, after the host's last whole write.

        :param good: where that write ends: anything after it (a chunk cut
          off when the host died) is cut off
        """
        self.captured = None
        self.position = self.good = good
        os.ftruncate(self.fd, good)
        os.lseek(self.fd, good, os.SEEK_SET)

    def write(self, *parts):
        if self.captured is not None:
            for data in parts:
                self.captured += data
            return sum(len(memoryview(data).cast('B')) for data in parts)
        total = 0
        for data in parts:
            view = memoryview(data).cast('B')
            while view:
                n = os.write(self.fd, view)
                self.position += n
                total += n
                view = view[n:]
        self.good = self.position
        self.pages.wrote_up_to(self.position)
        return total

    def tell(self):
        return self.position

    def flush(self):
        pass

    def cut_to_good(self):
        os.ftruncate(self.fd, self.good)
        os.lseek(self.fd, self.good, os.SEEK_SET)
        self.position = self.good

    def close(self):
        os.close(self.fd)


class BagWriter:
    """
    One MCAP file being recorded.

    ``add_topic`` then ``write`` (or ``write_chunk``); ``close`` writes the
    summary. Once the disk is full, ``failed`` holds the message and later
    writes are ignored.
    """

    def __init__(self, path, schemas, *, compression='none', chunk_size=DEFAULT_CHUNK_SIZE,
                 flush_interval=DEFAULT_FLUSH_INTERVAL, host_writes=False):
        """
        Create the file and write its header.

        :param schemas: :class:`colcon_wasm.ros2msg.Ros2MsgSchemas` of the install
        :param compression: ``none``, ``zstd`` or ``lz4``
        :param host_writes: the Node host writes the data section (uncompressed
          chunks) into the file through ``fileno()`` from ``host_offset`` on;
          the Schema and Channel records of ``add_topic`` are then handed to
          it (``records_for_host``), and ``host_wrote`` reports each write
        :raises BagError: when the file cannot be created
        """
        self.path = path
        self._schemas = schemas
        self._chunk_size = chunk_size
        self._flush_interval = flush_interval
        try:
            self._sink = _FileSink(path)
        except OSError as e:
            raise BagError(f"cannot create the bag '{path}': {e.strerror}") from None
        self._compression = compression
        self._schema_ids = {}
        self._topics = {}
        self.failed = None
        self.messages = 0
        self._first = None
        self._last = None
        self._chunk = ChunkBuffer()
        self._chunk_opened = None
        self._file = self._guard(lambda: McapFile(
            self._sink, compression=compression, profile='ros2',
            library=f'colcon-wasm {__version__}'))
        self._host = host_writes and compression == 'none' and not self.failed
        self.host_offset = self._sink.tell()
        # the end of the host's last whole write
        self._host_good = self.host_offset
        if self._host:
            self._sink.hand_over()

    def fileno(self):
        """Return the file descriptor (the host writes through it when ``host_writes``)."""
        return self._sink.fd

    def records_for_host(self):
        """Return the Schema and Channel records ``add_topic`` made since the last call."""
        return self._sink.take_captured() if self._host else b''

    def host_wrote(self, reports):
        """
        Take note of a write of the host into the file (a WRITTEN frame).

        :param reports: what one write put into the file, in file order, a
          report per record run or chunk: ``{"kind": "records", "offset",
          "end"}`` or ``{"kind": "chunk", "offset", "chunkLength",
          "indexLength", "size", "start", "end", "messages", "channels"}``
          (colcon_wasm/record/frames.py)
        """
        if not self._host or self.failed:
            return
        for report in reports:
            self._host_wrote_one(report)

    def _host_wrote_one(self, report):
        if report['kind'] != 'chunk':
            self._host_good = report['end']
            return
        channels = [tuple(c) for c in report['channels']]
        start, end = int(report['start']), int(report['end'])
        self._file.note_chunk(report['offset'], report['chunkLength'], start, end, channels,
                              report['indexLength'], report['size'])
        for channel, count, _ in channels:
            self._count(channel, count, start, end)
        self._host_good = report['offset'] + report['chunkLength'] + report['indexLength']
        self._sink.host_wrote_up_to(self._host_good)

    def host_failed(self, report):
        """
        End the file after its last whole record: a write of the host failed (FAILED).

        :param report: ``{"code": "ENOSPC", "message", "kept": bytes in the file or None}``
        """
        if not self._host or self.failed:
            return
        kept = report.get('kept')
        self._sink.take_back(self._host_good if kept is None else kept)
        number = getattr(errno, str(report.get('code')), errno.EIO)
        self._fail(OSError(number, os.strerror(number)))

    def add_topic(self, topic, type_name, qos_profiles, channel=None):
        """
        Add a channel for a topic (and the schema of its type, once).

        :param qos_profiles: the offered QoS of its publishers (JS form)
        :param channel: the channel id to give it (the ids of chunks built
          elsewhere); by default the next free one
        :returns: the channel id, or None when the file failed
        :raises colcon_wasm.ros2msg.SchemaError: for a type the install does not describe
        """
        if self.failed:
            return None
        if type_name not in self._schema_ids:
            text = self._schemas.full_text(type_name)
            schema_id = len(self._schema_ids) + 1
            if self._guard(lambda: self._file.add_schema(
                    schema_id, type_name, 'ros2msg', text.encode('utf-8')), True) is None:
                return None
            self._schema_ids[type_name] = schema_id
        if channel is None:
            channel = max(self._topics, default=0) + 1
        if channel in self._topics:
            raise BagError(f"channel {channel} of '{topic}' is taken by "
                           f"'{self._topics[channel]['name']}'")
        qos_text = to_rosbag2(qos_profiles)
        if self._guard(lambda: self._file.add_channel(
                channel, topic, 'cdr', self._schema_ids[type_name],
                {'offered_qos_profiles': qos_text}), True) is None:
            return None
        self._topics[channel] = {'name': topic, 'type': type_name, 'qos': qos_text,
                                 'count': 0}
        return channel

    def write(self, channel, log_time, publish_time, data, sequence=0):
        """Add one message (times in nanoseconds since the epoch; data: bytes or memoryview)."""
        if self.failed:
            return
        now = time.monotonic()
        if self._chunk_opened is None:
            self._chunk_opened = now
        self._chunk.add(channel, log_time, publish_time, data, sequence)
        self._count(channel, 1, log_time, log_time)
        if (len(self._chunk.records) >= self._chunk_size
                or now - self._chunk_opened >= self._flush_interval):
            self.flush()

    def write_chunk(self, records, start, end, indexes, channels):
        """
        Add a chunk built elsewhere (the Node host's tools worker).

        Its messages on channels this bag has no topic for (types the
        install does not describe) are left out.

        :param records: the chunk's Message records
        :param indexes: its MessageIndex records
        :param channels: ``[(channel id, message count, index record length), ...]``
        """
        if self.failed:
            return
        self.flush()
        unknown = {c for c, _, _ in channels if c not in self._topics}
        if unknown:
            kept = drop_channels(records, unknown)
            for channel, entries in kept.index.items():
                self._count(channel, len(entries), kept.start, kept.end)
            self._guard(lambda: self._file.add_buffer(kept))
            return
        if self._guard(lambda: self._file.add_chunk(records, start, end, indexes,
                                                    channels), True) is None:
            return
        for channel, count, _ in channels:
            self._count(channel, count, start, end)

    def _count(self, channel, count, first, last):
        self.messages += count
        if channel in self._topics:
            self._topics[channel]['count'] += count
        self._first = first if self._first is None else min(self._first, first)
        self._last = last if self._last is None else max(self._last, last)

    def flush(self):
        """Close the open chunk (it goes to the file)."""
        self._chunk_opened = None
        if self.failed or not self._chunk.messages:
            return
        chunk, self._chunk = self._chunk, ChunkBuffer()
        self._guard(lambda: self._file.add_buffer(chunk))

    def close(self):
        """Write the rosbag2 metadata and the summary, and close the file."""
        if self._host and self._sink.captured is not None:
            # the host is done: on from its last whole write
            self._guard(lambda: self._sink.take_back(self._host_good))
        self.flush()
        if not self.failed:
            self._guard(lambda: self._file.add_metadata(
                'rosbag2', {'serialized_metadata': self.metadata_yaml()}))
        if not self.failed:
            self._guard(self._file.finish)
        self._sink.close()

    def metadata_yaml(self):
        """Write the bag's metadata.yaml (rosbag2 version 5, as Humble writes it) as text."""
        start = self._first or 0
        duration = (self._last - self._first) if self._first is not None else 0
        name = os.path.basename(str(self.path))
        info = {
            'version': 5,
            'storage_identifier': 'mcap',
            'duration': {'nanoseconds': duration},
            'starting_time': {'nanoseconds_since_epoch': start},
            'message_count': self.messages,
            'topics_with_message_count': [
                {'topic_metadata': {'name': t['name'], 'type': t['type'],
                                    'serialization_format': 'cdr',
                                    'offered_qos_profiles': t['qos']},
                 'message_count': t['count']}
                for t in self._topics.values()],
            'compression_format': '',
            'compression_mode': '',
            'relative_file_paths': [name],
            'files': [{'path': name, 'starting_time': {'nanoseconds_since_epoch': start},
                       'duration': {'nanoseconds': duration},
                       'message_count': self.messages}],
        }
        return yaml.safe_dump({'rosbag2_bagfile_information': info}, sort_keys=False)

    def _guard(self, action, default=None):
        """Run a write; on a full disk end the file after its last whole record."""
        try:
            result = action()
            return default if result is None and default is not None else result
        except OSError as e:
            if e.errno not in _FULL:
                raise
            self._fail(e)
            return None

    def _fail(self, error):
        kept = self._sink.good
        self._sink.cut_to_good()
        ended = 'the file ends after its last whole chunk, without a summary'
        try:
            builder = RecordBuilder()
            DataEnd(0).write(builder)
            Footer(summary_start=0, summary_offset_start=0, summary_crc=0).write(builder)
            builder.write(MCAP0_MAGIC)
            self._sink.write(builder.end())
            ended = 'the file ends after its last whole chunk, with a footer and no summary'
        except OSError:
            self._sink.good = kept
            self._sink.cut_to_good()
        why = {errno.ENOSPC: 'the disk is full', errno.EFBIG: 'the file size limit is reached',
               errno.EDQUOT: 'the disk quota is used up'}.get(error.errno, error.strerror)
        self.failed = (f"recording to '{self.path}' stopped: {why} ({error.strerror}) after "
                       f'{kept} bytes; {ended} and stays readable (messages kept: those of the '
                       'chunks written); free some space and record again')
