# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
What a bag holds, as ``ros2 bag info`` prints it.

A bag written whole ends with an MCAP summary (its Statistics, Channel and
Schema records): the figures come from there, without reading the
messages. A file without one (a recording that was cut off, or a writer
that writes none) is read message by message up to where it stops being
readable, and the text says so.
"""

from dataclasses import dataclass
from dataclasses import field
import os
from pathlib import Path
import time

from colcon_wasm.record import BagError
from colcon_wasm.record.bag_reader import bag_files
from colcon_wasm.record.bag_reader import BoundedFile
from colcon_wasm.record.bag_reader import read_messages
from mcap.reader import make_reader


@dataclass
class TopicInfo:
    """A topic of the bag: its type, message count and encoding."""

    name: str
    type: str
    count: int = 0
    encoding: str = ''


@dataclass
class BagInfo:
    """The figures of a bag (one or more ``.mcap`` files)."""

    files: list
    size: int = 0
    messages: int = 0
    start: int = None     # ns since the epoch, of the first message
    end: int = None       # ns, of the last
    topics: dict = field(default_factory=dict)  # name -> TopicInfo
    notes: list = field(default_factory=list)   # what was read another way, and why

    def _span(self, start, end):
        if start is not None:
            self.start = start if self.start is None else min(self.start, start)
        if end is not None:
            self.end = end if self.end is None else max(self.end, end)

    def _topic(self, name, type_name, encoding):
        return self.topics.setdefault(name, TopicInfo(name, type_name, 0, encoding))


def bag_info(path):
    """
    Gather what a bag holds.

    :param path: a ``.mcap`` file or a rosbag2 directory
    :returns: a :class:`BagInfo`
    :raises BagError: for a path that is no bag
    """
    files = bag_files(path)
    info = BagInfo(files=[str(f) for f in files])
    for f in files:
        info.size += os.path.getsize(f)
        if not _from_summary(info, f):
            _by_reading(info, f)
    return info


def _from_summary(info, path):
    """Add a file's figures from its summary; False when it has none."""
    try:
        with open(path, 'rb') as f:
            summary = make_reader(BoundedFile(f, os.path.getsize(path))).get_summary()
    except Exception:  # noqa: B902 (mcap's, struct's and any decompressor's errors)
        # a damaged summary section: the messages are counted by reading, which names
        # the record that is broken
        return False
    if summary is None or summary.statistics is None:
        return False
    stats = summary.statistics
    info.messages += stats.message_count
    if stats.message_count:
        info._span(stats.message_start_time, stats.message_end_time)
    for channel in summary.channels.values():
        schema = summary.schemas.get(channel.schema_id)
        topic = info._topic(channel.topic, schema.name if schema else '',
                            channel.message_encoding)
        topic.count += stats.channel_message_counts.get(channel.id, 0)
    return True


def _by_reading(info, path):
    """Add a file's figures by reading its messages (a file with no summary)."""
    def on_topic(topic):
        info._topic(topic.name, topic.type, topic.message_encoding)
        return True

    try:
        for topic, log_time, _, _ in read_messages(path, on_topic):
            info.topics[topic.name].count += 1
            info.messages += 1
            info._span(log_time, log_time)
        info.notes.append(f"'{path}' has no summary: its messages were counted by reading it")
    except BagError as e:
        info.notes.append(f'{e}; they are counted here')


def _size_text(size):
    for unit in ('B', 'KiB', 'MiB', 'GiB'):
        if size < 1024 or unit == 'GiB':
            return f'{size} B' if unit == 'B' else f'{size:.1f} {unit}'
        size /= 1024


def _time_text(ns):
    seconds, ms = divmod(ns // 1000000, 1000)
    local = time.localtime(seconds)
    return f"{time.strftime('%b %e %Y %H:%M:%S', local)}.{ms:03d} ({seconds}.{ms:03d})"


def format_info(info):
    """
    Write the figures as ``ros2 bag info`` does (Humble's layout).

    :returns: the text, without a final newline
    """
    width = 19
    lines = [
        'Files:'.ljust(width) + ('\n' + ' ' * width).join(Path(f).name for f in info.files),
        'Bag size:'.ljust(width) + _size_text(info.size),
        'Storage id:'.ljust(width) + 'mcap',
    ]
    if info.start is not None:
        lines += [
            'Duration:'.ljust(width) + f'{(info.end - info.start) / 1e9:.3f}s',
            'Start:'.ljust(width) + _time_text(info.start),
            'End:'.ljust(width) + _time_text(info.end),
        ]
    else:
        lines.append('Duration:'.ljust(width) + '0s')
    lines.append('Messages:'.ljust(width) + str(info.messages))
    topics = [f'Topic: {t.name} | Type: {t.type} | Count: {t.count} | '
              f'Serialization Format: {t.encoding}' for t in info.topics.values()]
    lines.append('Topic information: ' + ('\n' + ' ' * width).join(topics))
    lines += [f'Note: {n}' for n in info.notes]
    return '\n'.join(lines)
