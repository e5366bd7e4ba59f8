# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
``colcon-wasm serve --foxglove [HOST:]PORT``: Foxglove on the served pages' graph.

The pages of serve meet in its rosbridge relay (relay.py); this server is
a client of that relay, over loopback (two links, foxglove_link.py: one
for the data its clients subscribe to, one for its own requests), and speaks
the Foxglove WebSocket protocol (both subprotocols) to Foxglove Studio,
Lichtblick or ``@foxglove/ws-protocol`` clients:

* every topic of the relay's graph is a channel with ``encoding: cdr``,
  ``schemaEncoding: ros2msg`` and the complete definition from the
  install's type descriptions (:mod:`colcon_wasm.ros2msg`, the text
  rosbag2 and the Node.js server use); the data are the CDR bytes the
  pages' publishers send the relay (``cbor-raw``), never decoded;
* ``clientPublish`` and service calls in ``json`` (the relay routes JSON;
  this server has no CDR codec of its own, so it does not offer ``cdr``);
* ``parameters`` and ``parametersSubscribe`` over the nodes' rcl parameter
  services and ``/parameter_events``, which the pages bridge to the relay
  (foxglove_parameters.py), when the install describes rcl_interfaces;
* ``connectionGraph``: which node publishes, subscribes to and serves what,
  from the relay's rosapi, to which the pages report their nodes'
  endpoints (foxglove_graph.py);
* one send queue per subscription (``queue_messages`` newest kept, drops
  counted), sent round robin, so a flood on one topic never starves another;
* ``time``: once ``/clock`` (rosgraph_msgs/msg/Clock) is in the graph, this
  server follows it (in JSON, whoever publishes it) and sends every client
  its time; clients that connect after it appeared see the capability.

See docs/bridge.md, "serve --foxglove".
"""

import collections
from concurrent.futures import ThreadPoolExecutor
from http.server import BaseHTTPRequestHandler
from http.server import ThreadingHTTPServer
import itertools
import json
import socket
import struct
import threading
import time

from colcon_core.logging import colcon_logger
from colcon_wasm.ros2msg import SchemaError
from colcon_wasm.server import foxglove_wire as wire
from colcon_wasm.server.foxglove_assets import AssetError
from colcon_wasm.server.foxglove_assets import fetch_asset_response
from colcon_wasm.server.foxglove_graph import ConnectionGraph
from colcon_wasm.server.foxglove_link import RelayLink
from colcon_wasm.server.foxglove_parameters import EVENTS_TOPIC
from colcon_wasm.server.foxglove_parameters import ParameterError
from colcon_wasm.server.foxglove_parameters import Parameters
from colcon_wasm.server.http import bind_error
from colcon_wasm.server.relay_http import refuse
from colcon_wasm.server.websocket import Connection
from colcon_wasm.server.websocket import handshake_response

logger = colcon_logger.getChild(__name__)

CATALOG_INTERVAL = 1.0
SEND_HIGH_WATER = 8 * 1024 * 1024
CALL_TIMEOUT = 10.0
CLOCK_TOPIC = '/clock'
CLOCK_TYPE = 'rosgraph_msgs/msg/Clock'


class FoxgloveRelayServer(ThreadingHTTPServer):
    """The listener, the relay link and the channel catalog shared by the sessions."""

    daemon_threads = True
    allow_reuse_address = True

    def __init__(self, relay_url, schemas, host, port, queue_messages=10, assets=None):
        """
        Bind ``host:port`` (port 0 picks one) and connect to the relay at ``relay_url``.

        :param assets: the install's share folders (foxglove_assets.Assets) that
          ``fetchAsset`` serves ``package://`` files from; none: no ``assets``

        :raises ServeError: when the address is taken or cannot be bound
        """
        self.schemas = schemas
        self.queue_messages = queue_messages
        self.assets = assets
        self.lock = threading.RLock()
        self.sessions = set()
        self.channels = {}      # topic -> channel dict (id, topic, encoding, schemaName, ...)
        self.services = {}      # name -> service dict
        self.skipped = set()
        self.upstream = collections.Counter()  # topic -> sessions subscribed
        self.calls = {}         # relay call id -> (session, service id, call id, deadline)
        self._ids = itertools.count(1)
        self._channel_ids = itertools.count(1)
        self._service_ids = itertools.count(1)
        self.clock = False      # following /clock: the time capability
        self._clock_type = None  # /clock's type in the relay's topics
        self._stop = threading.Event()
        if ':' in host:
            self.address_family = socket.AF_INET6
        try:
            super().__init__((host, port), _FoxgloveRequestHandler)
        except OSError as e:
            raise bind_error(e, host, port, other='another Foxglove server or foxglove_bridge?',
                             fix='--foxglove HOST:PORT (port 0 picks a free port)',
                             option='--foxglove') from None
        self.link = RelayLink(relay_url, self._from_relay)
        # this server's own requests, and /parameter_events in JSON: the relay sends a
        # client one form of a topic, and a Foxglove client may subscribe to it in CDR
        self.control = RelayLink(relay_url, self._from_control)
        self.parameters = Parameters(self)
        self.parameters.follow()
        self.graph = ConnectionGraph(self)
        self.requests = ThreadPoolExecutor(4, thread_name_prefix='foxglove-request')
        threading.Thread(target=self._catalog_loop, daemon=True).start()

    @property
    def url(self):
        """Return ws://host:port of the server."""
        host, port = self.server_address[:2]
        return f"ws://{(f'[{host}]' if ':' in host else host)}:{port}"

    def server_close(self):
        """Stop the catalog, close the sessions and the link."""
        self._stop.set()
        self.graph.stop()
        for session in list(self.sessions):
            session.conn.close(1001, 'the server is stopping')
        self.link.close()
        self.control.close()
        self.requests.shutdown(wait=False, cancel_futures=True)
        super().server_close()

    def capabilities(self):
        """Return the capabilities a client connecting now is told."""
        return ['clientPublish', 'services', 'connectionGraph'] + (
            ['parameters', 'parametersSubscribe'] if self.parameters.available else []) + (
            ['time'] if self.clock else []) + (
            ['assets'] if self.assets and self.assets.available else [])

    # ------------------------------------------------------------ catalog

    def _catalog_loop(self):
        while not self._stop.is_set():
            self._ask('/rosapi/topics', {})
            self._ask('/rosapi/services', {})
            self._expire_calls()
            self._stop.wait(CATALOG_INTERVAL)

    def _ask(self, service, args, kind=None):
        self.link.send(op='call_service', service=service, args=args,
                       id=f'foxglove-catalog:{kind or service}')

    def _from_relay(self, msg):
        op = msg.get('op')
        if op == 'publish':
            if msg.get('topic') == CLOCK_TOPIC and self.clock:
                self.tick(msg.get('msg'))
            self._deliver(msg)
        elif op == 'service_response':
            rid = str(msg.get('id', ''))
            if rid == 'foxglove-catalog:/rosapi/topics' and msg.get('result'):
                self._update_topics(msg.get('values') or {})
            elif rid == 'foxglove-catalog:/rosapi/services' and msg.get('result'):
                for name in (msg.get('values') or {}).get('services', []):
                    if name not in self.services and not name.startswith('/rosapi/'):
                        self._ask('/rosapi/service_type', {'service': name},
                                  kind=f'type:{name}')
                self._drop_services(set((msg.get('values') or {}).get('services', [])))
            elif rid == 'foxglove-catalog:clock-publishers' and msg.get('result'):
                # this server's own /clock subscription keeps /clock in the relay's
                # topics: follow it while someone publishes it
                publishers = (msg.get('values') or {}).get('publishers') or []
                self._follow_clock(self._clock_type if publishers else None)
            elif rid.startswith('foxglove-catalog:type:') and msg.get('result'):
                self._add_service(rid[len('foxglove-catalog:type:'):],
                                  (msg.get('values') or {}).get('type', ''))
            elif rid in self.calls:
                self._answer(rid, msg)

    def _from_control(self, msg):
        if msg.get('op') == 'publish' and msg.get('topic') == EVENTS_TOPIC:
            self.parameters.event(msg.get('msg'))

    def _schema(self, type_name, what):
        try:
            return self.schemas.full_text(type_name)
        except SchemaError as e:
            if what not in self.skipped:
                self.skipped.add(what)
                logger.warning(f'serve --foxglove: not offering {what}: {e}')
            return None

    def _update_topics(self, values):
        topics = dict(zip(values.get('topics') or [], values.get('types') or []))
        added, removed = [], []
        with self.lock:
            for topic, type_name in topics.items():
                if topic in self.channels or not type_name:
                    continue
                full = self.schemas.resolve(type_name) or type_name
                schema = self._schema(full, f'topic {topic} ({type_name})')
                if schema is None:
                    continue
                channel = {'id': next(self._channel_ids), 'topic': topic, 'encoding': 'cdr',
                           'schemaName': full, 'schema': schema, 'schemaEncoding': 'ros2msg'}
                self.channels[topic] = channel
                added.append(channel)
            for topic in [t for t in self.channels if t not in topics]:
                removed.append(self.channels.pop(topic)['id'])
            sessions = list(self.sessions)
        self._clock_type = topics.get(CLOCK_TOPIC)
        if self._clock_type:
            self._ask('/rosapi/publishers', {'topic': CLOCK_TOPIC}, kind='clock-publishers')
        else:
            self._follow_clock(None)
        for session in sessions:
            if added:
                session.send_json(op='advertise', channels=added)
            if removed:
                session.forget_channels(removed)

    def _add_service(self, name, type_name):
        if not type_name:
            return
        request = self._schema(f'{type_name}_Request', f'service {name} ({type_name})')
        response = request and self._schema(f'{type_name}_Response',
                                            f'service {name} ({type_name})')
        if not response:
            return

        def part(suffix, schema):
            return {'encoding': 'json', 'schemaName': f'{type_name}{suffix}',
                    'schemaEncoding': 'ros2msg', 'schema': schema}
        with self.lock:
            if name in self.services:
                return
            service = {'id': next(self._service_ids), 'name': name, 'type': type_name,
                       'request': part('_Request', request),
                       'response': part('_Response', response),
                       'requestSchema': request, 'responseSchema': response}
            self.services[name] = service
            sessions = list(self.sessions)
        for session in sessions:
            session.send_json(op='advertiseServices', services=[service])

    def _drop_services(self, present):
        with self.lock:
            gone = [self.services.pop(n)['id'] for n in list(self.services) if n not in present]
            sessions = list(self.sessions)
        if gone:
            for session in sessions:
                session.send_json(op='unadvertiseServices', serviceIds=gone)

    # ------------------------------------------------------------ time

    def _follow_clock(self, type_name):
        """Subscribe to /clock (JSON) while it is in the graph with the Clock type."""
        present = bool(type_name) and (self.schemas.resolve(type_name) or type_name) == CLOCK_TYPE
        if present == self.clock:
            return
        self.clock = present
        if present:
            # JSON, not cbor-raw: the relay converts whatever form the publisher sent
            self.link.send(op='subscribe', id='foxglove-time', topic=CLOCK_TOPIC, type=CLOCK_TYPE)
        else:
            self.link.send(op='unsubscribe', id='foxglove-time', topic=CLOCK_TOPIC)

    def tick(self, body):
        """
        Send every session the time of one /clock message (while /clock is followed).

        The relay does not send this server what it published itself, so a
        Foxglove client's own /clock comes here from its session too.

        The relay sends one form per topic to a client: JSON, or the CDR bytes
        (``cbor-raw``) when a Foxglove client subscribed to the /clock channel
        too; Clock's CDR is the encapsulation, then int32 sec and uint32 nanosec.
        """
        if not self.clock or not isinstance(body, dict):
            return
        if isinstance(body.get('bytes'), (bytes, bytearray)):
            data = body['bytes']
            if len(data) < 12:
                return
            sec, nanosec = struct.unpack_from('<iI' if data[1] == 1 else '>iI', data, 4)
        elif isinstance(body.get('clock'), dict):
            sec, nanosec = body['clock'].get('sec'), body['clock'].get('nanosec')
        else:
            return
        if not isinstance(sec, int) or not isinstance(nanosec, int) or sec < 0:
            return
        message = wire.time_message(sec * 1_000_000_000 + nanosec)
        with self.lock:
            sessions = list(self.sessions)
        for session in sessions:
            session.conn.send(message)

    # ------------------------------------------------------------ data

    def want(self, topic, wanted):
        """Count a session's interest in a topic; subscribe or unsubscribe upstream."""
        with self.lock:
            channel = self.channels.get(topic)
            before = self.upstream[topic]
            self.upstream[topic] += 1 if wanted else -1
            if self.upstream[topic] <= 0:
                del self.upstream[topic]
            after = self.upstream[topic] if topic in self.upstream else 0
        if before == 0 and after > 0 and channel is not None:
            self.link.send(op='subscribe', id=f'foxglove:{topic}', topic=topic,
                           type=channel['schemaName'], compression='cbor-raw')
        elif before > 0 and after == 0:
            self.link.send(op='unsubscribe', id=f'foxglove:{topic}', topic=topic)

    def _deliver(self, msg):
        body = msg.get('msg')
        if not isinstance(body, dict) or not isinstance(body.get('bytes'), (bytes, bytearray)):
            return  # a JSON publish: this server sends CDR only
        secs, nsecs = body.get('secs'), body.get('nsecs')
        stamp = secs * 1_000_000_000 + nsecs if isinstance(secs, int) and \
            isinstance(nsecs, int) else time.time_ns()
        with self.lock:
            sessions = list(self.sessions)
        for session in sessions:
            session.offer(msg.get('topic'), stamp, body['bytes'])

    def call(self, session, service_id, call_id, payload):
        """Make a service call for a session (json payload)."""
        with self.lock:
            service = next((s for s in self.services.values() if s['id'] == service_id), None)
        if service is None:
            session.send_json(op='serviceCallFailure', serviceId=service_id, callId=call_id,
                              message=f'no service with id {service_id} is advertised')
            return
        try:
            args = json.loads(bytes(payload).decode('utf-8'))
        except (ValueError, UnicodeDecodeError) as e:
            session.send_json(op='serviceCallFailure', serviceId=service_id, callId=call_id,
                              message=f"the request to {service['name']} is not JSON: {e}")
            return
        rid = f'foxglove-call:{next(self._ids)}'
        with self.lock:
            self.calls[rid] = (session, service_id, call_id, time.monotonic() + CALL_TIMEOUT,
                               service['name'])
        self.link.send(op='call_service', service=service['name'], args=args, id=rid,
                       timeout=CALL_TIMEOUT)

    def _answer(self, rid, msg):
        with self.lock:
            session, service_id, call_id, _, name = self.calls.pop(rid)
        if msg.get('result'):
            payload = json.dumps(msg.get('values') or {}).encode('utf-8')
            session.conn.send(wire.service_call_response(service_id, call_id, 'json', payload))
        else:
            session.send_json(op='serviceCallFailure', serviceId=service_id, callId=call_id,
                              message=f"{name}: {msg.get('values')}")

    def _expire_calls(self):
        now = time.monotonic()
        with self.lock:
            late = [rid for rid, c in self.calls.items() if c[3] + 1 < now]
            expired = [self.calls.pop(rid) for rid in late]
        for session, service_id, call_id, _, name in expired:
            session.send_json(op='serviceCallFailure', serviceId=service_id, callId=call_id,
                              message=f'{name} did not answer within {CALL_TIMEOUT:g} s')


class FoxgloveSession:
    """One Foxglove client: its subscriptions, its channels and its send queues."""

    def __init__(self, server, conn, subprotocol):
        """Greet the client and advertise what the catalog holds."""
        self.server = server
        self.conn = conn
        self.subscriptions = {}   # subscription id -> topic
        self.client_channels = {}  # channel id -> {topic, encoding, schemaName}
        self.queues = {}          # subscription id -> deque of (stamp, bytes)
        self.dropped = collections.Counter()
        self._ready = threading.Condition()
        self._closed = False
        threading.Thread(target=self._send_loop, daemon=True).start()
        self.send_json(op='serverInfo', name='colcon-wasm serve',
                       capabilities=server.capabilities(),
                       supportedEncodings=['json'], metadata={'subprotocol': subprotocol},
                       sessionId=str(id(self)))
        with server.lock:
            channels = list(server.channels.values())
            services = list(server.services.values())
            server.sessions.add(self)
        if channels:
            self.send_json(op='advertise', channels=channels)
        if services:
            self.send_json(op='advertiseServices', services=services)

    def send_json(self, **msg):
        """Send one JSON message."""
        self.conn.send(json.dumps(msg))

    def status(self, level, message, rid=None):
        """Send a status message (with the id of the request it answers, when given)."""
        self.send_json(op='status', level=level, message=message,
                       **({} if rid is None else {'id': rid}))

    def on_message(self, data, binary):
        """Handle one client message; bad input gets a status and the connection stays."""
        if binary:
            try:
                decoded = wire.decode_client_binary(data)
            except wire.WireError as e:
                self.status(wire.ERROR, str(e))
                return
            if decoded[0] == 'publish':
                self._publish(decoded[1], decoded[2])
            else:
                _, service, call, encoding, payload = decoded
                if encoding != 'json':
                    self.send_json(op='serviceCallFailure', serviceId=service, callId=call,
                                   message='this server (serve --foxglove) takes json service '
                                           f'calls, not {encoding!r}')
                    return
                self.server.call(self, service, call, payload)
            return
        try:
            msg = json.loads(data)
        except ValueError as e:
            self.status(wire.ERROR, f'malformed JSON: {e}')
            return
        handler = getattr(self, f"_op_{msg.get('op')}", None) if isinstance(msg, dict) else None
        if handler is None:
            op = msg.get('op') if isinstance(msg, dict) else None
            self.status(wire.ERROR, f'unknown or unsupported op {op!r} (this server offers '
                                    'subscribe, unsubscribe, advertise, unadvertise, '
                                    'getParameters, setParameters, subscribeParameterUpdates, '
                                    'unsubscribeParameterUpdates, subscribeConnectionGraph, '
                                    'unsubscribeConnectionGraph, fetchAsset and binary '
                                    'clientPublish and serviceCallRequest)')
            return
        try:
            handler(msg)
        except ParameterError as e:
            self.status(wire.ERROR, str(e), msg.get('id'))
        except (KeyError, TypeError, ValueError) as e:
            self.status(wire.ERROR, f"{msg.get('op')}: bad request ({type(e).__name__}: {e})",
                        msg.get('id'))

    def _op_subscribe(self, msg):
        with self.server.lock:
            by_id = {c['id']: c['topic'] for c in self.server.channels.values()}
        for sub in msg['subscriptions']:
            topic = by_id.get(sub['channelId'])
            if topic is None:
                self.status(wire.WARNING, f"subscribe: no channel {sub['channelId']}")
                continue
            with self._ready:
                self.subscriptions[sub['id']] = topic
                self.queues[sub['id']] = collections.deque(maxlen=self.server.queue_messages)
            self.server.want(topic, True)

    def _op_unsubscribe(self, msg):
        for sid in msg['subscriptionIds']:
            with self._ready:
                topic = self.subscriptions.pop(sid, None)
                self.queues.pop(sid, None)
            if topic is not None:
                self.server.want(topic, False)

    def _op_advertise(self, msg):
        for channel in msg['channels']:
            self.client_channels[channel['id']] = channel
            if channel.get('encoding') == 'json':
                self.server.link.send(op='advertise', topic=channel['topic'],
                                      type=channel['schemaName'])

    def _op_unadvertise(self, msg):
        for cid in msg['channelIds']:
            self.client_channels.pop(cid, None)

    def _publish(self, channel_id, payload):
        channel = self.client_channels.get(channel_id)
        if channel is None:
            self.status(wire.ERROR, f'clientPublish on channel {channel_id}, which this client '
                                    'did not advertise')
            return
        if channel.get('encoding') != 'json':
            self.status(wire.ERROR, f"clientPublish on {channel['topic']}: this server (serve "
                                    f"--foxglove) takes json, not {channel.get('encoding')!r}")
            return
        try:
            message = json.loads(bytes(payload).decode('utf-8'))
        except (ValueError, UnicodeDecodeError) as e:
            self.status(wire.ERROR, f"clientPublish on {channel['topic']}: not JSON ({e})")
            return
        self.server.link.send(op='publish', topic=channel['topic'], msg=message)
        if channel['topic'] == CLOCK_TOPIC:
            self.server.tick(message)

    # ------------------------------------------------------------ parameters, graph

    def _parameters(self, msg):
        """Return the server's parameters; raise ParameterError when the install has none."""
        if not self.server.parameters.available:
            raise ParameterError(f"{msg['op']}: parameters need the rcl_interfaces type "
                                 'descriptions in the install: build rcl_interfaces with '
                                 'colcon build --wasm')
        return self.server.parameters

    def _in_pool(self, op, msg):
        """Run a parameter request off the reader thread (it waits for the nodes)."""
        def run():
            try:
                op(self, msg)
            except ParameterError as e:
                self.status(wire.ERROR, str(e), msg.get('id'))
            except Exception as e:  # noqa: B902 (a thread of the pool: say it, keep serving)
                logger.warning(f"serve --foxglove: {msg['op']} failed: {e}")
                self.status(wire.ERROR, f"{msg['op']} failed: {e}", msg.get('id'))
        self.server.requests.submit(run)

    def _op_getParameters(self, msg):
        self._in_pool(self._parameters(msg).get_parameters, msg)

    def _op_setParameters(self, msg):
        self._in_pool(self._parameters(msg).set_parameters, msg)

    def _op_subscribeParameterUpdates(self, msg):
        self._parameters(msg).subscribe(self, msg)

    def _op_unsubscribeParameterUpdates(self, msg):
        self.server.parameters.unsubscribe(self, msg)

    def _op_subscribeConnectionGraph(self, msg):
        self.server.graph.subscribe(self)

    def _op_unsubscribeConnectionGraph(self, msg):
        self.server.graph.unsubscribe(self)

    def _op_fetchAsset(self, msg):
        rid = msg.get('requestId')
        if not isinstance(rid, int) or isinstance(rid, bool) or not 0 <= rid < 2 ** 32:
            self.status(wire.ERROR, "fetchAsset needs an integer 'requestId' (the response "
                                    'carries it)')
            return
        assets = self.server.assets

        def fetch():
            data, error = b'', None
            if not assets or not assets.available:
                error = (f"fetchAsset {msg.get('uri')}: this server has no install space to "
                         "serve assets from (no 'assets' capability)")
            else:
                try:
                    data = assets.fetch(msg.get('uri'))
                except AssetError as e:
                    error = str(e)
            self.conn.send(fetch_asset_response(rid, error, data))
        self.server.requests.submit(fetch)

    def forget_channels(self, ids):
        """Unadvertise channels that left the graph (their subscriptions end)."""
        self.send_json(op='unadvertise', channelIds=ids)

    def offer(self, topic, stamp, data):
        """Queue a message for every subscription of this session to ``topic``."""
        with self._ready:
            for sid, t in self.subscriptions.items():
                if t == topic:
                    queue = self.queues[sid]
                    if len(queue) == queue.maxlen:
                        self.dropped[topic] += 1
                    queue.append((stamp, data))
            self._ready.notify()

    def _send_loop(self):
        while True:
            with self._ready:
                while not self._closed and not any(self.queues.values()):
                    self._ready.wait()
                if self._closed:
                    return
                batch = [(sid, q.popleft()) for sid, q in self.queues.items() if q]
            for sid, (stamp, data) in batch:
                while self.conn.queued_bytes > SEND_HIGH_WATER and not self.conn.closed:
                    time.sleep(0.002)
                if not self.conn.send(wire.message_data(sid, stamp, data)):
                    return

    def close(self):
        """End the session: its upstream subscriptions go."""
        with self._ready:
            self._closed = True
            topics = list(self.subscriptions.values())
            self.subscriptions.clear()
            self._ready.notify()
        for topic in topics:
            self.server.want(topic, False)
        self.server.parameters.forget(self)
        self.server.graph.unsubscribe(self)


class _FoxgloveRequestHandler(BaseHTTPRequestHandler):
    """Every GET is a Foxglove WebSocket."""

    protocol_version = 'HTTP/1.1'
    server_version = 'colcon-wasm'

    def do_GET(self):  # noqa: N802
        """Upgrade with a Foxglove subprotocol, or refuse."""
        subprotocol = wire.choose_subprotocol(self.headers)
        response = handshake_response(self.headers, subprotocol) if subprotocol else None
        if response is None:
            refuse(self, 400, 'a Foxglove WebSocket server: connect with the subprotocol '
                              f"{' or '.join(wire.SUBPROTOCOLS)}")
            return
        self.connection.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.connection.sendall(response)
        self.close_connection = True
        conn = Connection(self.connection, max_message_bytes=64 << 20,
                          max_queued_bytes=256 << 20)
        server = self.server
        session = FoxgloveSession(server, conn, subprotocol)
        try:
            conn.run(session.on_message)
        finally:
            with server.lock:
                server.sessions.discard(session)
            session.close()

    def log_message(self, format, *args):  # noqa: A002
        """Log nothing."""
