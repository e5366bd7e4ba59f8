# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Record what a rosbridge server carries: ``colcon-wasm record FILE.mcap``.

Beside a running ``colcon-wasm serve --rosbridge`` (its relay joins the
pages' buses into one graph), a ``run``/``launch --rosbridge``, or any
rosbridge v2 server: the recorder asks ``/rosapi/topics`` once a second,
subscribes to each new topic (or each ``--record-topic``) with
``compression: cbor-raw`` and writes the CDR bytes as they come, with no
decode (:class:`colcon_wasm.record.bag_writer.BagWriter`: rosbag2's MCAP
layout, written as it goes). The schemas are the install's; a topic whose
type the install does not describe is named once and skipped.

rosbridge says nothing of QoS: the channels carry no
``offered_qos_profiles`` (``ros2 bag play`` then uses its defaults).
``log_time`` is when a message arrived here, ``publish_time`` the stamp the
server gave it (``secs``/``nsecs``, the time it was sent on).
"""

import itertools
import json
import threading
import time

import cbor2
from colcon_wasm.record import BagError
from colcon_wasm.ros2msg import SchemaError
from colcon_wasm.server.websocket import connect
from colcon_wasm.server.websocket import WebSocketError

DISCOVER_INTERVAL = 1.0
CONNECT_TIMEOUT = 10.0
MAX_MESSAGE_BYTES = 256 * 1024 * 1024


class RemoteRecorder:
    """One recording of a rosbridge server's topics into one bag."""

    def __init__(self, url, *, topics=None, err):
        """
        Prepare (nothing connects before ``connect``).

        :param url: ``ws://HOST:PORT`` of the rosbridge server
        :param topics: the topics to record (None: every one)
        :param err: where warnings go (a text stream)
        """
        self.url = url
        self.writer = None
        self._connection = None
        self.wanted = set(topics) if topics else None
        self.err = err
        self._lock = threading.Lock()
        self._channels = {}
        self._skipped = {}
        self._ids = itertools.count(1)
        self._closed = threading.Event()
        self._stopping = False
        self.lost_connection = None
        self.statuses = []

    def connect(self):
        """
        Connect to the server (before the bag is created: a failure leaves no file).

        :raises BagError: when the server cannot be reached
        """
        try:
            self._connection = connect(self.url, timeout=CONNECT_TIMEOUT,
                                       max_message_bytes=MAX_MESSAGE_BYTES,
                                       max_queued_bytes=16 * 1024 * 1024)
        except WebSocketError as e:
            raise BagError(
                f'{e}; start the rosbridge server first (colcon-wasm serve --rosbridge '
                '[HOST:]PORT, or run/launch --rosbridge), or pass its ws:// URL') from None

    def run(self, writer, duration=None, stop=None):
        """
        Record until ``duration`` seconds passed, ``stop`` is set or the server goes.

        :param writer: the :class:`~colcon_wasm.record.bag_writer.BagWriter` (closed at the end)
        :param stop: a :class:`threading.Event` (e.g. set on SIGINT)
        :returns: a summary dict (messages, topics, skipped, failed, lost_connection)
        """
        self.writer = writer
        connection = self._connection
        reader = threading.Thread(target=self._read, args=(connection,), daemon=True)
        reader.start()
        deadline = None if duration is None else time.monotonic() + duration
        stop = stop or threading.Event()
        try:
            while not stop.is_set() and not self._closed.is_set():
                self._ask_topics(connection)
                with self._lock:
                    if self.writer.failed:
                        break
                    self.writer.flush()
                wait = DISCOVER_INTERVAL
                if deadline is not None:
                    left = deadline - time.monotonic()
                    if left <= 0:
                        break
                    wait = min(wait, left)
                stop.wait(wait)
        finally:
            self._stopping = True
            connection.close(1000, 'recorded')
            reader.join(timeout=5)
            with self._lock:
                self.writer.close()
        return self.summary()

    def summary(self):
        """Return what was recorded: counts per topic, skipped topics, a failure."""
        return {'messages': self.writer.messages,
                'topics': sorted(self._channels),
                'skipped': dict(self._skipped),
                'failed': self.writer.failed,
                'lost_connection': self.lost_connection}

    def _ask_topics(self, connection):
        connection.send(json.dumps({'op': 'call_service', 'service': '/rosapi/topics',
                                    'id': f'colcon-wasm-record-topics-{next(self._ids)}',
                                    'args': {}}))

    def _read(self, connection):
        try:
            connection.run(lambda data, binary: self._on_message(connection, data, binary))
        finally:
            if not self._stopping:
                self.lost_connection = f'{self.url} closed the connection'
            self._closed.set()

    def _on_message(self, connection, data, binary):
        try:
            message = cbor2.loads(data) if binary else json.loads(data)
        except (ValueError, cbor2.CBORDecodeError) as e:
            self._warn(f'a message from {self.url} is not {"CBOR" if binary else "JSON"} '
                       f'({e}); skipped')
            return
        if not isinstance(message, dict):
            return
        op = message.get('op')
        if op == 'publish':
            self._record(message)
        elif op == 'service_response' and str(message.get('id', '')).startswith(
                'colcon-wasm-record-topics-'):
            self._subscribe_new(connection, message.get('values') or {})
        elif op == 'status' and message.get('level') in ('error', 'warning'):
            self.statuses.append(message.get('msg'))
            self._warn(f"{self.url} says: {message.get('msg')}")

    def _subscribe_new(self, connection, values):
        for topic, type_name in zip(values.get('topics') or [], values.get('types') or []):
            if topic in self._channels or topic in self._skipped:
                continue
            if self.wanted is not None and topic not in self.wanted:
                continue
            with self._lock:
                try:
                    channel = self.writer.add_topic(topic, type_name, [])
                except SchemaError as e:
                    self._skipped[topic] = str(e)
                    self._warn(f'not recording {topic}: {e}')
                    continue
            if channel is None:
                continue
            self._channels[topic] = channel
            connection.send(json.dumps({
                'op': 'subscribe', 'id': f'colcon-wasm-record-{topic}', 'topic': topic,
                'type': type_name, 'compression': 'cbor-raw'}))

    def _record(self, message):
        channel = self._channels.get(message.get('topic'))
        body = message.get('msg')
        if channel is None or not isinstance(body, dict) or not isinstance(
                body.get('bytes'), (bytes, bytearray)):
            return
        log_time = time.time_ns()
        secs, nsecs = body.get('secs'), body.get('nsecs')
        publish_time = secs * 1_000_000_000 + nsecs if isinstance(secs, int) and \
            isinstance(nsecs, int) else log_time
        with self._lock:
            self.writer.write(channel, log_time, publish_time, bytes(body['bytes']))

    def _warn(self, text):
        print(f'colcon-wasm record: {text}', file=self.err, flush=True)
