# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's record and replay: the ``/bag`` WebSocket of ``colcon-wasm serve``.

The page has the bus, serve has the MCAP library (``mcap``, with zstd and
lz4): the page streams what it records to serve, which writes the bag as
it goes (:class:`colcon_wasm.record.bag_writer.BagWriter`) and offers it
for download; a bag dropped on the page is uploaded to serve, which reads
it (damaged files up to the damage) and sends the messages back in their
recorded timing (:class:`colcon_wasm.record.paced_player.PacedPlayer`), for
the page to publish. One connection is one recording or one replay.

Page to serve (text is JSON, ``op`` first):

* ``record {name, compression}``, then ``topic {id, topic, type, qos}`` for
  each topic and binary messages (``<u32 id><f64 log ms><f64 publish ms>``
  then the CDR bytes, epoch milliseconds), then ``stop``: answered by
  ``recorded {url, name, messages, bytes, skipped, error}``;
* ``upload {name, size}`` then ``size`` bytes in binary messages: answered
  by ``bag {name, count, duration_ms, topics: [{id, topic, type, qos}],
  skipped: [{topic, why}], error}``; then ``play``, ``pause``, ``step``,
  ``seek {position_ms}``, ``rate {rate}``, ``clock {hz}`` (0: none).

Serve to page: ``state {state, position_ms, sent, rate, error?}``, played
messages as binary ``<u32 id><f64 position ms>`` then the CDR bytes, the
bag time for ``/clock`` as binary ``<u32 0><f64 position ms><u64 ns>``, and
``error {msg}`` for a request it refuses (the connection stays up).
Recordings stay downloadable at ``/bag/files/TOKEN/NAME`` until serve stops.
"""

import json
import os
from pathlib import Path
import re
import secrets
import shutil
import struct
import tempfile
import threading

from colcon_core.logging import colcon_logger
from colcon_wasm.record import BagError
from colcon_wasm.record.bag_reader import unplayable
from colcon_wasm.record.bag_writer import BagWriter
from colcon_wasm.record.frames import decode_recorded
from colcon_wasm.record.mcap_file import COMPRESSIONS
from colcon_wasm.record.paced_player import BagSpan
from colcon_wasm.record.paced_player import PacedPlayer
from colcon_wasm.record.qos import player_qos
from colcon_wasm.ros2msg import SchemaError
from colcon_wasm.server.websocket import Connection

logger = colcon_logger.getChild(__name__)

BAG_PATH = '/bag'
FILES_PREFIX = '/bag/files/'
MAX_MESSAGE_BYTES = 256 * 1024 * 1024
MAX_QUEUED_BYTES = 256 * 1024 * 1024
_PLAYED = struct.Struct('<Id')
_CLOCK = struct.Struct('<IdQ')
_SAFE_NAME = re.compile(r'[^A-Za-z0-9._-]+')


class BagService:
    """The recordings and uploads of one serve, in a folder removed when it stops."""

    def __init__(self, install_space):
        """Make the folder (lazily, on first use)."""
        self.install_space = install_space
        self._folder = None
        self._lock = threading.Lock()
        self._schemas = None
        self.files = {}

    def folder(self):
        """Return the scratch folder of this serve."""
        with self._lock:
            if self._folder is None:
                self._folder = Path(tempfile.mkdtemp(prefix='colcon-wasm-bags-'))
            return self._folder

    def schemas(self):
        """Read the install's ros2msg schemas once, and return them."""
        with self._lock:
            if self._schemas is None:
                self._schemas = self.install_space.ros2msg_schemas()
            return self._schemas

    def new_file(self, name):
        """Make a folder for a new file called (a safe form of) ``name``: ``(token, path)``."""
        name = _SAFE_NAME.sub('_', os.path.basename(name or 'bag.mcap')) or 'bag.mcap'
        if not name.endswith('.mcap'):
            name += '.mcap'
        token = secrets.token_hex(8)
        folder = self.folder() / token
        folder.mkdir()
        path = folder / name
        self.files[token] = path
        return token, path

    def download(self, url_path):
        """Return the path of a recording for ``/bag/files/TOKEN/NAME``, or None."""
        rest = url_path[len(FILES_PREFIX):].split('/')
        if len(rest) != 2:
            return None
        path = self.files.get(rest[0])
        return path if path is not None and path.name == rest[1] and path.is_file() else None

    def serve(self, sock, peer):
        """Run one page connection until it closes."""
        session = _PageBagSession(self, peer)
        connection = Connection(sock, max_message_bytes=MAX_MESSAGE_BYTES,
                                max_queued_bytes=MAX_QUEUED_BYTES)
        session.connection = connection
        try:
            connection.run(session.on_message)
        finally:
            session.close()

    def close(self):
        """Remove the folder and what is in it."""
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)


class _PageBagSession:
    """One page connection: a recording or a replay."""

    def __init__(self, service, peer):
        self.service = service
        self.peer = peer
        self.connection = None
        self.writer = None
        self.token = None
        self.channels = {}
        self.skipped = {}
        self.upload = None
        self.player = None
        self.failure_sent = False

    def send(self, op, **fields):
        self.connection.send(json.dumps(dict({'op': op}, **fields)))

    def on_message(self, data, binary):
        try:
            if binary:
                self._binary(data)
            else:
                self._request(json.loads(data))
        except (ValueError, KeyError, TypeError) as e:
            self.send('error', msg=f'bad request ({type(e).__name__}: {e})')
        except (BagError, SchemaError) as e:
            self.send('error', msg=str(e))

    def _request(self, request):
        op = request.get('op') if isinstance(request, dict) else None
        if op == 'record':
            self._start_recording(request)
        elif op == 'topic':
            self._add_topic(request)
        elif op == 'stop':
            self._stop_recording()
        elif op == 'upload':
            self._start_upload(request)
        elif op in ('play', 'pause', 'step', 'seek', 'rate', 'clock'):
            self._control(op, request)
        else:
            self.send('error', msg=f'unknown op {op!r}: record, topic, stop, upload, play, '
                                   'pause, step, seek, rate or clock')

    def _start_recording(self, request):
        if self.writer is not None or self.upload is not None:
            raise BagError('this connection already records or plays: open another one')
        compression = request.get('compression', 'zstd')
        if compression not in COMPRESSIONS:
            raise BagError(f'compression {compression!r} is not one of {sorted(COMPRESSIONS)}')
        self.token, path = self.service.new_file(request.get('name'))
        self.writer = BagWriter(path, self.service.schemas(), compression=compression)
        logger.info(f'{self.peer}: recording into {path}')
        self.send('recording', name=path.name)

    def _add_topic(self, request):
        if self.writer is None:
            raise BagError('topic before record')
        try:
            channel = self.writer.add_topic(request['topic'], request['type'],
                                            request.get('qos') or [])
        except SchemaError as e:
            self.skipped[request['topic']] = str(e)
            self.send('skipped', topic=request['topic'], why=str(e))
            return
        if channel is not None:
            self.channels[int(request['id'])] = channel

    def _stop_recording(self):
        if self.writer is None:
            raise BagError('stop without record')
        writer, self.writer = self.writer, None
        writer.close()
        path = self.service.files[self.token]
        self.send('recorded', url=f'{FILES_PREFIX}{self.token}/{path.name}', name=path.name,
                  messages=writer.messages, bytes=path.stat().st_size, skipped=self.skipped,
                  error=writer.failed)

    def _start_upload(self, request):
        if self.writer is not None or self.upload is not None:
            raise BagError('this connection already records or plays: open another one')
        size = int(request['size'])
        if size <= 0:
            raise BagError(f"'{request.get('name')}' is empty")
        _, path = self.service.new_file(request.get('name'))
        self.upload = {'path': path, 'size': size, 'got': 0, 'file': open(path, 'wb')}

    def _binary(self, data):
        if self.writer is not None:
            channel, log_time, publish_time, payload = decode_recorded(data)
            target = self.channels.get(channel)
            if target is not None:
                self.writer.write(target, log_time, publish_time, payload)
                if self.writer.failed and not self.failure_sent:
                    self.failure_sent = True
                    self.send('error', msg=self.writer.failed)
            return
        upload = self.upload
        if upload is None or upload['file'] is None:
            raise BagError('binary data before record or upload')
        upload['file'].write(data)
        upload['got'] += len(data)
        if upload['got'] >= upload['size']:
            upload['file'].close()
            upload['file'] = None
            self._open_bag(upload['path'])

    def _open_bag(self, path):
        schemas = self.service.schemas()
        topics = []
        skipped = []
        channels = {}

        def on_topic(topic):
            if topic.name in channels:
                return True
            why = unplayable(topic, schemas)
            if why:
                skipped.append({'topic': topic.name, 'why': why})
                return False
            channels[topic.name] = len(channels) + 1
            topics.append({'id': channels[topic.name], 'topic': topic.name,
                           'type': schemas.resolve(topic.type), 'qos': player_qos(topic.qos)})
            return True
        span = BagSpan(path, on_topic)
        self.send('bag', name=path.name, count=span.count,
                  duration_ms=((span.end - span.start) / 1e6) if span.count else 0,
                  topics=topics, skipped=skipped, error=span.error)
        if span.count:
            self.player = PacedPlayer(path, channels, span.start, self._send_played,
                                      lambda state: self.send('state', **state),
                                      tick=self._send_clock)
            self._start = span.start

    def _send_clock(self, time_ns):
        self.connection.send(_CLOCK.pack(0, (time_ns - self._start) / 1e6, time_ns))

    def _send_played(self, channel, position_ms, data):
        self.connection.send(_PLAYED.pack(channel, position_ms) + bytes(data))

    def _control(self, op, request):
        if self.player is None:
            raise BagError(f'{op} before a bag was uploaded')
        if op == 'seek':
            self.player.seek(float(request['position_ms']))
        elif op == 'rate':
            self.player.set_rate(float(request['rate']))
        elif op == 'clock':
            self.player.set_clock(float(request['hz']))
        else:
            getattr(self.player, op)()

    def close(self):
        if self.writer is not None:
            self.writer.close()
        if self.upload is not None and self.upload['file'] is not None:
            self.upload['file'].close()
        if self.player is not None:
            self.player.close()
