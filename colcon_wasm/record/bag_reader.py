# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Read a bag for replay, with Foxglove's ``mcap`` stream reader.

The file is read from the start, record by record, in file order (a bag
written as it went is in time order), so a truncated or corrupt file plays
up to the record that is broken; the error then names that record and its
byte offset. A bag is a ``.mcap`` file or a rosbag2 directory (metadata.yaml
naming its ``.mcap`` files).
"""

from pathlib import Path
import struct

from colcon_wasm.record import BagError
from mcap.exceptions import McapError
from mcap.opcode import Opcode
from mcap.records import Channel
from mcap.records import Chunk
from mcap.records import Footer
from mcap.records import Message
from mcap.records import Schema
from mcap.stream_reader import breakup_chunk
from mcap.stream_reader import CRCValidationError
from mcap.stream_reader import StreamReader
import yaml

MAGIC = b'\x89MCAP0\r\n'
_RECORD_NAMES = {op.value: op.name.title().replace('_', '') for op in Opcode}


class BoundedFile:
    """
    A file whose ``read(n)`` never asks for more than the file still holds.

    The mcap library reads a record's inner lengths (a Chunk's records, a
    Schema's data) with ``read(length)``: a corrupt length of 2^63 would be
    an allocation of that size (MemoryError) before it finds the file too
    short. Bounded, it gets the bytes there are and says the record ends
    early (EndOfFile), which reads as a broken record.
    """

    def __init__(self, f, size):  # noqa: D107
        self._f = f
        self._size = size

    def read(self, n=-1):
        """Read at most ``n`` bytes, never past the end of the file."""
        left = max(0, self._size - self._f.tell())
        return self._f.read(left if n is None or n < 0 else min(n, left))

    def tell(self):
        """Return the position in the file."""
        return self._f.tell()

    def seek(self, offset, whence=0):
        """Move in the file."""
        return self._f.seek(offset, whence)

    def seekable(self):
        """Whether the file can seek."""
        return self._f.seekable()


class Topic:
    """A channel of the bag: its topic, type, schema and recorded QoS."""

    def __init__(self, channel, schema):
        """Describe a channel with its schema (None: no schema)."""
        self.id = channel.id
        self.name = channel.topic
        self.message_encoding = channel.message_encoding
        self.type = schema.name if schema else ''
        self.schema_encoding = schema.encoding if schema else ''
        self.schema_text = schema.data.decode('utf-8', 'replace') if schema else ''
        self.qos = channel.metadata.get('offered_qos_profiles', '')


def unplayable(topic, schemas):
    """
    Say why a bag's topic cannot be played into this workspace, or None.

    :param topic: a :class:`Topic`
    :param schemas: the install's :class:`colcon_wasm.ros2msg.Ros2MsgSchemas`
    """
    from colcon_wasm.ros2msg import SchemaError
    if topic.message_encoding != 'cdr':
        return f"its messages are encoded as '{topic.message_encoding}', not cdr"
    if not topic.type:
        return 'it has no schema'
    try:
        schemas.full_text(topic.type)
    except SchemaError:
        return (f"the workspace does not know its type '{topic.type}': build its "
                "interface package with 'colcon build --wasm'")
    return None


def bag_files(path):
    """
    List the ``.mcap`` files of a bag, in order.

    :raises BagError: for a path that is no bag
    """
    path = Path(path)
    if path.is_file():
        return [path]
    if path.is_dir():
        meta = path / 'metadata.yaml'
        names = []
        if meta.is_file():
            try:
                info = yaml.safe_load(meta.read_text(encoding='utf-8'))
                names = info['rosbag2_bagfile_information']['relative_file_paths']
            except (yaml.YAMLError, KeyError, TypeError) as e:
                raise BagError(f"the bag '{path}' has an unreadable metadata.yaml: {e}") from None
        files = [path / n for n in names if n.endswith('.mcap')] or sorted(path.glob('*.mcap'))
        if not files:
            raise BagError(f"the bag '{path}' has no .mcap file (other storage, such as "
                           'sqlite3, is not supported)')
        return files
    raise BagError(f"no bag at '{path}': name a .mcap file or a rosbag2 directory")


def read_messages(path, on_topic):
    """
    Yield the messages of one ``.mcap`` file in file order.

    ``on_topic(topic)`` is called once per channel before its first message
    and returns whether its messages are wanted.

    :returns: a generator of ``(topic, log_time, publish_time, data)``
    :raises BagError: naming the record and byte offset where the file
      stops being readable (after yielding what came before)
    """
    path = Path(path)
    size = path.stat().st_size
    with open(path, 'rb') as f:
        magic = f.read(len(MAGIC))
        if magic != MAGIC:
            raise BagError(f"'{path}' is not an MCAP file: it does not start with the MCAP "
                           f'magic (found {magic!r})')
        reader = StreamReader(BoundedFile(f, size), skip_magic=True, emit_chunks=True,
                              validate_crcs=True, record_size_limit=max(size, 1))
        records = iter(reader.records)
        schemas = {}
        topics = {}
        wanted = {}
        while True:
            offset = f.tell()
            try:
                record = next(records)
            except StopIteration:
                break
            except (McapError, CRCValidationError, struct.error, UnicodeDecodeError,
                    ValueError) as e:
                raise _broken(path, f, offset, size, e) from None
            inner = [record]
            if isinstance(record, Chunk):
                try:
                    inner = breakup_chunk(record, validate_crc=True)
                except Exception as e:  # noqa: B902 (any decompressor's error)
                    raise _broken(path, f, offset, size, e) from None
            for r in inner:
                if isinstance(r, Schema):
                    schemas[r.id] = r
                elif isinstance(r, Channel):
                    if r.id not in topics:
                        topics[r.id] = Topic(r, schemas.get(r.schema_id))
                        wanted[r.id] = bool(on_topic(topics[r.id]))
                elif isinstance(r, Message):
                    if r.channel_id not in topics:
                        raise BagError(f"'{path}': the message at or after byte {offset} is on "
                                       f'channel {r.channel_id}, which no Channel record before '
                                       'it describes')
                    if wanted[r.channel_id]:
                        yield topics[r.channel_id], r.log_time, r.publish_time, r.data
            if isinstance(record, Footer):
                break


def _broken(path, f, offset, size, error):
    f.seek(offset)
    opcode = f.read(1)
    if not opcode:
        return BagError(f"'{path}' ends at byte {offset} without a Footer record: it was cut "
                        'off (the recording did not finish); the messages before it were read')
    name = _RECORD_NAMES.get(opcode[0], f'unknown (opcode 0x{opcode[0]:02x})')
    head = f.read(8)
    length = struct.unpack('<Q', head)[0] if len(head) == 8 else None
    if length is None or offset + 9 + length > size:
        what = ('is cut off: the file ends at byte '
                f"{size}{('' if length is None else f' of its {length} bytes')}")
    else:
        what = f'is corrupt ({type(error).__name__}: {error})'
    return BagError(f"'{path}': the {name} record at byte offset {offset} {what}; the messages "
                    'before it were read')
