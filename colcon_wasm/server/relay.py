# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The rosbridge relay of ``colcon-wasm serve --rosbridge [HOST:]PORT``.

Each page that serve serves has its own bus; its rosbridge client
(``packages/wasm_js/src/bridges/rosbridge/client.mjs``) connects to
``/rosbridge`` of serve and bridges what the page's nodes use. The relay
routes between those clients, and the rosbridge clients (roslibjs,
roslibpy) that connect to the ``--rosbridge`` port, as one graph:

* a ``publish`` goes to every other client subscribed to the topic (never
  back to its sender), in the form the subscription asks for: CDR bytes
  (a CBOR publish of a colcon-wasm client) to ``cbor-raw`` subscribers as
  rosbridge's cbor-raw ``publish``; JSON to ``none``, ``png`` (rosbridge's
  png op) and ``cbor`` (built from the JSON with the type descriptions,
  relay_forms.py) subscribers, and to ``cbor-raw`` ones when its publisher
  sends no CDR (a third-party client; one warning per subscription).
  colcon-wasm publishers are told which forms the others need
  (``colcon_wasm_forms``). ``throttle_rate``, ``queue_length`` and
  ``fragment_size`` as the Node.js server applies them (relay_topics.py);
  ``ttl`` passed on;
* ``call_service`` goes to the client that advertised the service, with an
  id of the relay's; its ``service_response`` goes back to the caller with
  the caller's id; no answer within the call's ``timeout`` (default 10 s),
  or the server leaving, is a ``service_response`` with ``result: false``;
* ``send_action_goal``, ``cancel_action_goal``, ``action_feedback`` and
  ``action_result`` are routed the same way between action client and the
  client that advertised the action;
* the rosapi services are answered from what the clients advertised,
  subscribed and (colcon-wasm clients) reported of their nodes and of which
  node holds which endpoint (``colcon_wasm_graph``), and from the install
  space's type descriptions.

Requests are JSON text or CBOR (binary). Bad input gets a ``status`` error
naming the field, with the request's id; a client that stops reading is cut
off at ``max_queued_bytes`` (websocket.py), never blocking the others. The
relay greets each client with ``{"op": "colcon_wasm_relay", "version": 2}``
so that colcon-wasm clients report their nodes and the forms they can send
(``colcon_wasm_graph``); see docs/bridge.md, "The relay".
"""

import itertools
import json
import re
import threading
import time

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.server.relay_forms import decode_request
from colcon_wasm.server.relay_forms import Forms
from colcon_wasm.server.relay_forms import jsonable
from colcon_wasm.server.relay_forms import normalize
from colcon_wasm.server.relay_forms import PRIMITIVES
from colcon_wasm.server.relay_rosapi import Rosapi
from colcon_wasm.server.relay_rosapi import rosapi_service
from colcon_wasm.server.relay_topics import Message
from colcon_wasm.server.relay_topics import Subscription
from colcon_wasm.server.relay_topics import Topics
from colcon_wasm.server.websocket import Connection

logger = colcon_logger.getChild(__name__)

LEVELS = ('none', 'error', 'warning', 'info')
NAME = re.compile(r'^(/[A-Za-z_~][A-Za-z0-9_]*)+$')
# as the Node.js server (session.mjs): incomplete fragmented messages one client may leave
MAX_FRAGMENT_GROUPS = 16
ID_IN_TEXT = re.compile(r'"id"\s*:\s*("(?:[^"\\]|\\.)*"|-?\d+)')


class RequestError(ColconWasmError):
    """A request the relay refuses: the message goes into a status error."""


def _field(msg, name, kind, required=False):
    value = msg.get(name)
    if value is None:
        if required:
            raise RequestError(f"{msg.get('op')}: field '{name}' is missing")
        return None
    ok = {'str': isinstance(value, str), 'int': isinstance(value, int) and
          not isinstance(value, bool), 'bool': isinstance(value, bool),
          'dict': isinstance(value, dict), 'id': isinstance(value, (str, int))}[kind]
    if not ok:
        wanted = {'str': 'a string', 'int': 'an integer', 'bool': 'a boolean',
                  'dict': 'a JSON object', 'id': 'a string or a number'}[kind]
        raise RequestError(
            f"{msg.get('op')}: field '{name}' must be {wanted}, got {type(value).__name__}")
    return value


def _name(msg, field):
    value = _field(msg, field, 'str', required=True)
    full = value if value.startswith('/') else f'/{value}'
    if not NAME.match(full):
        raise RequestError(f"{msg.get('op')}: field '{field}' is not a valid ROS name: '{value}'")
    return full


def _id_of_text(text):
    """Return the id of a request whose JSON could not be parsed, when it can be read anyway."""
    match = ID_IN_TEXT.search(text[:4096])
    if not match:
        return None
    try:
        return json.loads(match.group(1))
    except ValueError:
        return None


def _raw_publish(msg):
    """Whether a (CBOR) request publishes CDR bytes: ``msg`` is ``{bytes, secs, nsecs}``."""
    m = msg.get('msg')
    return msg.get('op') == 'publish' and isinstance(m, dict) and isinstance(
        m.get('bytes'), (bytes, bytearray)) and set(m) <= {'bytes', 'secs', 'nsecs'}


def _jsonable_request(msg):
    """Return a CBOR request in JSON's terms; a publish of CDR bytes keeps its bytes."""
    if not _raw_publish(msg):
        return jsonable(msg)
    raw = msg['msg']
    out = jsonable({k: v for k, v in msg.items() if k != 'msg'})
    out['msg'] = {k: (bytes(v) if k == 'bytes' else jsonable(v)) for k, v in raw.items()}
    return out


class Peer:
    """One WebSocket client of the relay."""

    def __init__(self, relay, conn, number, where):  # noqa: D107
        self.relay = relay
        self.conn = conn
        self.number = number
        self.where = where
        self.level = 'error'
        self.subscriptions = {}   # topic -> relay_topics.Subscription
        self.publications = {}    # topic -> type
        self.nodes = []
        self.endpoints = {}       # node -> {'publishing', 'subscribing', 'services'}: names
        self.fragments = {}
        self.version = 0          # a colcon-wasm client's (colcon_wasm_graph), else 0
        self.forms = {}           # topic -> (json, cdr) last asked of this colcon-wasm publisher
        self.draining = set()     # subscriptions waiting for the socket to drain

    def send(self, obj):
        """Send a protocol message (a dict as JSON text; str and bytes as they are)."""
        return self.conn.send(obj if isinstance(obj, (str, bytes)) else json.dumps(obj))

    def status(self, level, text, rid=None):
        """Send a status message when the client's level shows it."""
        if self.level == 'none' or LEVELS.index(level) > LEVELS.index(self.level):
            return
        out = {'op': 'status', 'level': level, 'msg': text}
        if rid is not None:
            out['id'] = rid
        self.send(out)

    @property
    def label(self):
        """The node names it stands for in rosapi answers."""
        return self.nodes or [f'/rosbridge_relay/client_{self.number}']

    def holders(self, kind, name):
        """
        Name the nodes of this client that hold an endpoint.

        :param kind: ``publishing``, ``subscribing`` or ``services``
        :returns: the nodes whose reported endpoints have ``name``; the
          client's label when none does (a third-party client, an older
          colcon-wasm one, or a graph not reported yet)
        """
        nodes = [n for n, e in self.endpoints.items() if name in e[kind]]
        return nodes or self.label


class Relay:
    """The routing state of all clients; ``serve(sock, where)`` runs one."""

    def __init__(self, *, types=(), max_message_bytes=16 << 20, max_queued_bytes=64 << 20,
                 call_timeout=10.0):
        """Create it; ``types`` are types.json documents (rosapi message_details)."""
        self.lock = threading.RLock()
        self.peers = set()
        self.services = {}   # name -> (peer, type)
        self.actions = {}    # name -> (peer, type)
        self.pending = {}    # relay id -> dict(caller, id, kind, name, provider, deadline)
        self.messages = {}
        self.service_types = {}
        for doc in types:
            self.messages.update(doc.get('messages', {}))
            self.service_types.update(doc.get('services', {}))
        self.forms = Forms(self.messages)
        self.max_message_bytes = max_message_bytes
        self.max_queued_bytes = max_queued_bytes
        self.call_timeout = call_timeout
        self.stats = {'dropped': 0, 'expired': 0}
        self.topics = Topics(self)
        self._numbers = itertools.count(1)
        self._ids = itertools.count(1)
        self.rosapi = Rosapi(self)
        self._stop = threading.Event()
        threading.Thread(target=self._expire_loop, daemon=True).start()

    # ------------------------------------------------------------ connections

    def serve(self, sock, where):
        """Run one client's connection until it closes (blocking)."""
        peer = None

        def oversize(n):
            if peer:
                peer.status('error', f'a message of {n} bytes is larger than the limit of '
                                     f'{self.max_message_bytes} bytes; '
                                     'it was dropped')

        def cut_off(n):
            logger.warning(f'rosbridge relay: client {peer.number} ({where}) cut off: it did not '
                           'read, more than '
                           f'{self.max_queued_bytes} bytes were waiting')

        conn = Connection(sock, max_message_bytes=self.max_message_bytes,
                          max_queued_bytes=self.max_queued_bytes, on_oversize=oversize,
                          on_cut_off=cut_off, on_drain=lambda: self.topics.drained(peer))
        peer = Peer(self, conn, next(self._numbers), where)
        with self.lock:
            self.peers.add(peer)
        peer.send({'op': 'colcon_wasm_relay', 'version': 2})
        try:
            conn.run(lambda data, binary: self.receive(peer, data, binary))
        finally:
            self._leave(peer)

    def _leave(self, peer):
        with self.lock:
            self.peers.discard(peer)
            for topic, sub in list(peer.subscriptions.items()):
                self.topics.close(sub)
                del peer.subscriptions[topic]
                self._update_forms(topic)
            for table in (self.services, self.actions):
                for name in [n for n, (p, _) in table.items() if p is peer]:
                    del table[name]
            for rid, call in list(self.pending.items()):
                if call['caller'] is peer:
                    del self.pending[rid]
                elif call['provider'] is peer:
                    del self.pending[rid]
                    self._fail(call, f"{call['name']} left before answering")

    def close(self):
        """Stop the relay and close every client."""
        self._stop.set()
        self.topics.scheduler.stop()
        with self.lock:
            peers = list(self.peers)
        for peer in peers:
            peer.conn.close(1001, 'the server is stopping')

    def _expire_loop(self):
        while not self._stop.wait(0.1):
            now = time.monotonic()
            with self.lock:
                for rid, call in list(self.pending.items()):
                    if call['deadline'] is not None and now > call['deadline']:
                        del self.pending[rid]
                        self._fail(call, f"{call['name']} did not answer within "
                                         f"{call['timeout']:g} s")

    def _fail(self, call, text):
        caller = call['caller']
        if call['kind'] == 'service':
            out = {'op': 'service_response', 'service': call['name'], 'values': text,
                   'result': False}
        else:
            out = {'op': 'action_result', 'action': call['name'], 'values': text, 'status': 0,
                   'result': False}
        if call['id'] is not None:
            out['id'] = call['id']
        caller.send(out)
        caller.status('error', f"{call['name']}: {text}", call['id'])

    # ------------------------------------------------------------ requests

    def receive(self, peer, data, binary):
        """Handle one message of a client: JSON text, or CBOR (binary)."""
        if binary:
            try:
                msg = decode_request(data)
                if isinstance(msg, dict):
                    msg = _jsonable_request(msg)
            except ValueError as e:
                peer.status('error', f'{e}; the request was dropped')
                return
        else:
            try:
                msg = json.loads(data)
            except ValueError as e:
                peer.status('error', f'malformed JSON: {e}; the request was dropped',
                            _id_of_text(data))
                return
        if not isinstance(msg, dict) or not isinstance(msg.get('op'), str):
            peer.status('error', "a rosbridge request must be a JSON object with an 'op' field",
                        msg.get('id') if isinstance(msg, dict) else None)
            return
        handler = getattr(self, f"_op_{msg['op']}", None)
        if handler is None:
            peer.status('error', f"unknown operation \"{msg['op']}\"", msg.get('id'))
            return
        try:
            with self.lock:
                handler(peer, msg)
        except RequestError as e:
            peer.status('error', str(e), msg.get('id'))

    def _op_fragment(self, peer, msg):
        fid = _field(msg, 'id', 'id', required=True)
        num, total = _field(msg, 'num', 'int', True), _field(msg, 'total', 'int', True)
        data = _field(msg, 'data', 'str', True)
        if not 0 <= num < total:
            raise RequestError("fragment: field 'num' must be from 0 to total - 1")
        group = peer.fragments.get(fid)
        if group is None:
            if len(peer.fragments) >= MAX_FRAGMENT_GROUPS:
                raise RequestError(f'fragment: more than {MAX_FRAGMENT_GROUPS} fragmented '
                                   f'messages are incomplete; fragment {num} of {fid!r} was '
                                   'dropped')
            group = peer.fragments[fid] = {'total': total, 'parts': {}, 'bytes': 0}
        if total != group['total']:
            raise RequestError(f"fragment: field 'total' is {total}, but earlier fragments of "
                               f"{fid!r} said {group['total']}")
        if num in group['parts']:
            return
        group['parts'][num] = data
        group['bytes'] += len(data)
        if group['bytes'] > self.max_message_bytes:
            del peer.fragments[fid]
            raise RequestError(f'fragment: the fragmented message {fid!r} is larger than the '
                               f'limit of {self.max_message_bytes} bytes')
        if len(group['parts']) == total:
            del peer.fragments[fid]
            self.receive(peer, ''.join(group['parts'][i] for i in range(total)), False)

    def _op_set_level(self, peer, msg):
        level = _field(msg, 'level', 'str', True)
        if level not in LEVELS:
            raise RequestError(f"set_level: field 'level' must be one of {', '.join(LEVELS)}")
        peer.level = level

    def _op_status(self, peer, msg):
        pass

    def _op_colcon_wasm_graph(self, peer, msg):
        nodes = msg.get('nodes')
        if isinstance(nodes, list):
            peer.nodes = [n for n in nodes if isinstance(n, str)]
        endpoints = msg.get('endpoints')
        if isinstance(endpoints, dict):
            def names(value):
                return {n for n in value if isinstance(n, str)} if isinstance(value, list) \
                    else set()
            peer.endpoints = {
                node: {kind: names(e.get(kind)) for kind in ('publishing', 'subscribing',
                                                             'services')}
                for node, e in endpoints.items() if isinstance(e, dict)}
        version = msg.get('version')
        if isinstance(version, int) and version != peer.version:
            peer.version = version
            for topic in list(peer.publications):
                self._update_forms(topic)

    def _update_forms(self, topic):
        """
        Tell the colcon-wasm publishers of ``topic`` which forms the others' subscriptions need.

        ``{"op": "colcon_wasm_forms", "topic", "json", "cdr"}``: JSON for
        none/png/cbor subscribers, CDR for cbor-raw ones; sent when it changes.
        """
        subs = [(p, p.subscriptions[topic]) for p in self.peers if topic in p.subscriptions]
        for p in self.peers:
            if p.version < 2 or topic not in p.publications:
                continue
            kinds = {s.compression for q, s in subs if q is not p}
            want = (bool(kinds - {'cbor-raw'}), 'cbor-raw' in kinds)
            if p.forms.get(topic) != want:
                p.forms[topic] = want
                p.send({'op': 'colcon_wasm_forms', 'topic': topic, 'json': want[0],
                        'cdr': want[1]})

    def _known_type(self, topic):
        for p in self.peers:
            if topic in p.publications:
                return p.publications[topic]
            sub = p.subscriptions.get(topic)
            if sub and sub.type:
                return sub.type
        return None

    def _op_advertise(self, peer, msg):
        topic = _name(msg, 'topic')
        type_name = normalize(_field(msg, 'type', 'str', True))
        self._check_type('advertise', 'type', type_name)
        known = self._known_type(topic)
        if known and known != type_name:
            raise RequestError(f"advertise: field 'type' is {type_name}, but topic '{topic}' "
                               f'has type {known}')
        if topic not in peer.publications:
            peer.publications[topic] = type_name
            self._update_forms(topic)

    def _op_unadvertise(self, peer, msg):
        topic = _name(msg, 'topic')
        peer.publications.pop(topic, None)
        peer.forms.pop(topic, None)

    def _op_subscribe(self, peer, msg):
        topic = _name(msg, 'topic')
        given = _field(msg, 'type', 'str')
        type_name = normalize(given) if given else self._known_type(topic)
        if given:
            self._check_type('subscribe', 'type', type_name)
        compression = _field(msg, 'compression', 'str') or 'none'
        if compression not in ('none', 'png', 'cbor', 'cbor-raw'):
            raise RequestError("subscribe: field 'compression' must be one of none, png, cbor, "
                               f"cbor-raw, got '{compression}'")
        request = {'compression': compression}
        for key in ('throttle_rate', 'queue_length', 'fragment_size'):
            request[key.split('_rate')[0]] = max(0, _field(msg, key, 'int') or 0)
        sub = peer.subscriptions.get(topic)
        if sub is None:
            sub = peer.subscriptions[topic] = Subscription(peer, topic, type_name)
        elif type_name and sub.type and type_name != sub.type:
            raise RequestError(f"subscribe: field 'type' is {type_name}, but this client is "
                               f"subscribed to '{topic}' as {sub.type}")
        sub.requests[msg.get('id')] = request
        self.stats['dropped'] += sub.update()
        if type_name and not sub.type:
            sub.type = type_name
        if not sub.queue_length:
            self.topics.flush(sub, everything=True)
        self._update_forms(topic)

    def _op_unsubscribe(self, peer, msg):
        topic = _name(msg, 'topic')
        sub = peer.subscriptions.get(topic)
        if sub is None:
            return
        sub.requests.pop(msg.get('id'), None)
        if msg.get('id') is None or not sub.requests:
            del peer.subscriptions[topic]
            self.topics.close(sub)
        else:
            self.stats['dropped'] += sub.update()
        self._update_forms(topic)

    def _op_publish(self, peer, msg):
        topic = _name(msg, 'topic')
        if 'msg' not in msg:
            raise RequestError("publish: field 'msg' is missing (the message to publish)")
        if not isinstance(msg['msg'], dict):
            raise RequestError("publish: field 'msg' must be a JSON object")
        if topic not in peer.publications:
            known = self._known_type(topic) or (normalize(msg['type'])
                                                if isinstance(msg.get('type'), str) else None)
            if not known:
                raise RequestError(f"publish: cannot infer the type of topic '{topic}': advertise "
                                   'it with a type first')
            peer.publications[topic] = known
            self._update_forms(topic)
        type_name = peer.publications[topic]
        ttl = msg.get('ttl')
        if not isinstance(ttl, (int, float)) or isinstance(ttl, bool):
            ttl = None
        elif ttl <= 0:
            self.stats['expired'] += 1
            return
        if _raw_publish(msg):
            raw = msg['msg']
            m = Message(topic, type_name, cdr=bytes(raw['bytes']), secs=raw.get('secs'),
                        nsecs=raw.get('nsecs'), ttl=ttl)
        else:
            self._check('publish', type_name, msg['msg'])
            m = Message(topic, type_name, json_msg=msg['msg'], ttl=ttl)
        # JSON goes to cbor-raw subscribers only when its publisher sends no CDR form
        gives_cdr = peer.forms.get(topic, (True, False))[1]
        for other in self.peers:
            sub = other.subscriptions.get(topic)
            if other is peer or sub is None:
                continue
            if m.cdr is not None:
                if sub.compression != 'cbor-raw':
                    continue
            elif sub.compression == 'cbor-raw' and gives_cdr:
                continue
            self.topics.offer(sub, m)

    def _provider(self, table, name, what):
        entry = table.get(name)
        if entry is None:
            raise RequestError(f'{what} {name} does not exist: no client of the relay advertised '
                               'it')
        return entry

    def _op_advertise_service(self, peer, msg):
        name = _name(msg, 'service')
        type_name = normalize(_field(msg, 'type', 'str', True), 'srv')
        if self.service_types and type_name not in self.service_types:
            raise RequestError("advertise_service: field 'type' names an unknown service type "
                               f"'{type_name}'")
        self.services[name] = (peer, type_name)

    def _op_unadvertise_service(self, peer, msg):
        name = _name(msg, 'service')
        if self.services.get(name, (None,))[0] is peer:
            del self.services[name]

    def _op_call_service(self, peer, msg):
        name = _name(msg, 'service')
        rosapi = rosapi_service(name)
        if rosapi:
            def answer(values):
                out = {'op': 'service_response', 'service': msg['service'], 'result': True,
                       'values': values}
                if msg.get('id') is not None:
                    out['id'] = msg['id']
                peer.send(out)
                if values.get('successful') is False:
                    peer.status('warning', f"call_service {name}: {values.get('reason')}",
                                msg.get('id'))
            self.rosapi.call(rosapi, msg.get('args') or {}, answer)
            return
        timeout = msg.get('timeout')
        timeout = self.call_timeout if not isinstance(timeout, (int, float)) else (
            timeout if timeout > 0 else None)
        if name not in self.services:
            out = {'op': 'service_response', 'service': msg['service'], 'result': False,
                   'values': f"service '{name}' does not exist (no client of the relay serves it)"}
            if msg.get('id') is not None:
                out['id'] = msg['id']
            peer.send(out)
            peer.status('error', f"call_service {name}: {out['values']}", msg.get('id'))
            return
        provider, service_type = self.services[name]
        entry = self.service_types.get(service_type)
        if entry and isinstance(msg.get('args'), dict):
            self._check('call_service', entry['request'], msg['args'])
        rid = f'relay:{next(self._ids)}'
        self.pending[rid] = {'caller': peer, 'id': msg.get('id'), 'kind': 'service', 'name': name,
                             'provider': provider, 'timeout': timeout,
                             'deadline': None if timeout is None else time.monotonic() + timeout}
        provider.send({'op': 'call_service', 'id': rid, 'service': name,
                       'args': msg.get('args') or {}})

    def request(self, name, args, timeout, caller):
        """
        Call a client's service for the relay itself (under its lock).

        :param name: the service, which a client advertised
        :param args: the request (rosbridge JSON)
        :param timeout: seconds until the call fails
        :param caller: gets the ``service_response`` (``send``) as a client would,
          ``result: false`` with the reason when the call failed
        """
        provider, _ = self.services[name]
        rid = f'relay:{next(self._ids)}'
        self.pending[rid] = {'caller': caller, 'id': None, 'kind': 'service', 'name': name,
                             'provider': provider, 'timeout': timeout,
                             'deadline': time.monotonic() + timeout}
        provider.send({'op': 'call_service', 'id': rid, 'service': name, 'args': args})

    def _op_service_response(self, peer, msg):
        rid = str(_field(msg, 'id', 'id', True))
        call = self.pending.get(rid)
        if call is None or call['provider'] is not peer:
            raise RequestError(f"service_response: field 'id' ('{rid}') names no pending call of "
                               'this client')
        del self.pending[rid]
        out = {'op': 'service_response', 'service': call['name'], 'values': msg.get('values'),
               'result': bool(msg.get('result'))}
        if call['id'] is not None:
            out['id'] = call['id']
        call['caller'].send(out)

    def _op_advertise_action(self, peer, msg):
        self.actions[_name(msg, 'action')] = (peer, _field(msg, 'type', 'str', True))

    def _op_unadvertise_action(self, peer, msg):
        name = _name(msg, 'action')
        if self.actions.get(name, (None,))[0] is peer:
            del self.actions[name]

    def _op_send_action_goal(self, peer, msg):
        name = _name(msg, 'action')
        provider, type_name = self._provider(self.actions, name, 'action')
        rid = f'relay:{next(self._ids)}'
        self.pending[rid] = {'caller': peer, 'id': msg.get('id'), 'kind': 'action', 'name': name,
                             'provider': provider, 'timeout': None, 'deadline': None,
                             'feedback': bool(msg.get('feedback'))}
        provider.send({'op': 'send_action_goal', 'id': rid, 'action': name,
                       'action_type': msg.get('action_type') or type_name,
                       'args': msg.get('args') or {}, 'feedback': True})

    def _op_cancel_action_goal(self, peer, msg):
        gid = _field(msg, 'id', 'id', True)
        for rid, call in self.pending.items():
            if call['caller'] is peer and call['id'] == gid and call['kind'] == 'action':
                call['provider'].send({'op': 'cancel_action_goal', 'id': rid,
                                       'action': call['name']})
                return
        raise RequestError(f"cancel_action_goal: field 'id' ('{gid}') names no goal of this "
                           'client '
                           'in progress')

    def _goal(self, peer, msg):
        rid = str(_field(msg, 'id', 'id', True))
        call = self.pending.get(rid)
        if call is None or call['provider'] is not peer:
            raise RequestError(f"{msg['op']}: field 'id' ('{rid}') names no goal sent to this "
                               'client')
        return rid, call

    def _op_action_feedback(self, peer, msg):
        _, call = self._goal(peer, msg)
        if call['feedback']:
            out = {'op': 'action_feedback', 'action': call['name'], 'values': msg.get('values')}
            if call['id'] is not None:
                out['id'] = call['id']
            call['caller'].send(out)

    def _op_action_result(self, peer, msg):
        rid, call = self._goal(peer, msg)
        del self.pending[rid]
        out = {'op': 'action_result', 'action': call['name'], 'values': msg.get('values'),
               'status': msg.get('status', 0), 'result': bool(msg.get('result'))}
        if call['id'] is not None:
            out['id'] = call['id']
        call['caller'].send(out)

    # ------------------------------------------------------------ checks

    def _check_type(self, op, field, type_name):
        if self.messages and type_name not in self.messages:
            raise RequestError(f"{op}: field '{field}' names an unknown type '{type_name}': no "
                               'types.json of the '
                               'install space describes it')

    def _check(self, op, type_name, value, path=''):
        """Check a JSON message against its type description (when the install space has it)."""
        description = self.messages.get(type_name)
        if description is None:
            return
        where = f'{op}: {type_name}: field '
        if not isinstance(value, dict):
            raise RequestError(f"{where}'{path or '.'}': expected a JSON object, got "
                               f'{type(value).__name__}')
        fields = {f['name']: f for f in description.get('fields', [])}
        for key, item in value.items():
            p = f'{path}.{key}' if path else key
            f = fields.get(key)
            if f is None:
                raise RequestError(f"{where}'{p}': {type_name} has no field '{key}' (fields: "
                                   f"{', '.join(fields)})")
            items = [item]
            if f.get('sequence') or 'array_size' in f:
                if f['type'] in ('uint8', 'char', 'byte') and isinstance(item, str):
                    continue
                if not isinstance(item, list):
                    raise RequestError(f"{where}'{p}': expected an array of {f['type']}, got "
                                       f'{type(item).__name__}')
                items = item
            for v in items:
                self._check_value(op, where, p, f['type'], v)

    def _check_value(self, op, where, path, kind, v):
        if kind in ('string', 'wstring'):
            ok, label = isinstance(v, str), 'a string'
        elif kind == 'bool':
            ok, label = isinstance(v, bool), 'a boolean'
        elif kind in ('float32', 'float64'):
            ok, label = v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)), \
                'a number'
        elif kind in PRIMITIVES:
            ok, label = (isinstance(v, int) and not isinstance(v, bool)) or (
                kind in ('int64', 'uint64') and isinstance(v, str) and v.strip().lstrip(
                    '-').isdigit()), f'an integer ({kind})'
        else:
            self._check(op, normalize(kind), v, path)
            return
        if not ok:
            raise RequestError(f"{where}'{path}': expected {label}, got {json.dumps(v)[:40]}")
