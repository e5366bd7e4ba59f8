# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The rosbridge relay of ``colcon-wasm serve --rosbridge [HOST:]PORT``.

Each page that serve serves has its own bus; its rosbridge client
(``packages/wasm_js/src/bridges/rosbridge/client.mjs``) connects to
``/rosbridge`` of serve and bridges what the page's nodes use. The relay
routes between those clients, and the rosbridge clients (roslibjs,
roslibpy) that connect to the ``--rosbridge`` port, as one graph:

* a ``publish`` goes to every other client subscribed to the topic (never
  back to its sender), as JSON (the relay has no bus and no CDR codec, so
  ``cbor``/``cbor-raw``/``png`` subscriptions get JSON, with a warning);
  ``throttle_rate`` is applied, ``ttl`` passed on;
* ``call_service`` goes to the client that advertised the service, with an
  id of the relay's; its ``service_response`` goes back to the caller with
  the caller's id; no answer within the call's ``timeout`` (default 10 s),
  or the server leaving, is a ``service_response`` with ``result: false``;
* ``send_action_goal``, ``cancel_action_goal``, ``action_feedback`` and
  ``action_result`` are routed the same way between action client and the
  client that advertised the action;
* the rosapi services are answered from what the clients advertised,
  subscribed and (colcon-wasm clients) reported of their nodes
  (``colcon_wasm_graph``), and from the install space's type descriptions.

Bad input gets a ``status`` error naming the field, with the request's id;
a client that stops reading is cut off at ``max_queued_bytes``
(websocket.py), never blocking the others. The relay greets each client with
``{"op": "colcon_wasm_relay"}`` so that colcon-wasm clients switch to JSON
and report their nodes.
"""

import itertools
import json
import re
import threading
import time

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.server.websocket import Connection

logger = colcon_logger.getChild(__name__)

LEVELS = ('none', 'error', 'warning', 'info')
NAME = re.compile(r'^(/[A-Za-z_~][A-Za-z0-9_]*)+$')
ID_IN_TEXT = re.compile(r'"id"\s*:\s*("(?:[^"\\]|\\.)*"|-?\d+)')
ROSAPI = ('topics', 'topics_for_type', 'services', 'nodes', 'node_details', 'topic_type',
          'service_type', 'publishers', 'subscribers', 'service_providers', 'message_details',
          'action_servers', 'get_time', 'get_ros_version')
PRIMITIVES = {'bool', 'byte', 'char', 'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32',
              'int64', 'uint64', 'float32', 'float64', 'string', 'wstring'}
ROSAPI_NAMES = {'float64': 'double', 'float32': 'float', 'bool': 'boolean', 'byte': 'octet'}


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
    full = value if value.startswith('/') else '/' + value
    if not NAME.match(full):
        raise RequestError(f"{msg.get('op')}: field '{field}' is not a valid ROS name: '{value}'")
    return full


def _normalize(type_name, kind='msg'):
    parts = type_name.strip().split('/')
    return f'{parts[0]}/{kind}/{parts[1]}' if len(parts) == 2 else type_name.strip()


class Peer:
    """One WebSocket client of the relay."""

    def __init__(self, relay, conn, number, where):  # noqa: D107
        self.relay = relay
        self.conn = conn
        self.number = number
        self.where = where
        self.level = 'error'
        self.subscriptions = {}   # topic -> {'type', 'throttle', 'last', 'ids'}
        self.publications = {}    # topic -> type
        self.nodes = []
        self.fragments = {}

    def send(self, obj):
        """Send a protocol message."""
        return self.conn.send(obj if isinstance(obj, str) else json.dumps(obj))

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
        self.max_message_bytes = max_message_bytes
        self.max_queued_bytes = max_queued_bytes
        self.call_timeout = call_timeout
        self._numbers = itertools.count(1)
        self._ids = itertools.count(1)
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
                          on_cut_off=cut_off)
        peer = Peer(self, conn, next(self._numbers), where)
        with self.lock:
            self.peers.add(peer)
        peer.send({'op': 'colcon_wasm_relay', 'version': 1})
        try:
            conn.run(lambda data, binary: self.receive(peer, data, binary))
        finally:
            self._leave(peer)

    def _leave(self, peer):
        with self.lock:
            self.peers.discard(peer)
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
        """Handle one message of a client."""
        if binary:
            peer.status('error', 'the relay reads rosbridge requests as JSON text, not binary')
            return
        try:
            msg = json.loads(data)
        except ValueError as e:
            match = ID_IN_TEXT.search(data[:4096])
            peer.status('error', f'malformed JSON: {e}; the request was dropped',
                        json.loads(match.group(1)) if match else None)
            return
        if not isinstance(msg, dict) or not isinstance(msg.get('op'), str):
            peer.status('error', "a rosbridge request must be a JSON object with an 'op' field",
                        msg.get('id') if isinstance(msg, dict) else None)
            return
        handler = getattr(self, '_op_' + msg['op'], None)
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
        parts = peer.fragments.setdefault(fid, {})
        parts[num] = data
        if len(parts) == total:
            del peer.fragments[fid]
            self.receive(peer, ''.join(parts[i] for i in range(total)), False)

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

    def _known_type(self, topic):
        for p in self.peers:
            if topic in p.publications:
                return p.publications[topic]
            sub = p.subscriptions.get(topic)
            if sub and sub['type']:
                return sub['type']
        return None

    def _op_advertise(self, peer, msg):
        topic = _name(msg, 'topic')
        type_name = _normalize(_field(msg, 'type', 'str', True))
        self._check_type('advertise', 'type', type_name)
        known = self._known_type(topic)
        if known and known != type_name:
            raise RequestError(f"advertise: field 'type' is {type_name}, but topic '{topic}' has "
                               f'type {known}')
        peer.publications[topic] = type_name

    def _op_unadvertise(self, peer, msg):
        peer.publications.pop(_name(msg, 'topic'), None)

    def _op_subscribe(self, peer, msg):
        topic = _name(msg, 'topic')
        given = _field(msg, 'type', 'str')
        type_name = _normalize(given) if given else self._known_type(topic)
        compression = _field(msg, 'compression', 'str') or 'none'
        if compression not in ('none', 'png', 'cbor', 'cbor-raw'):
            raise RequestError("subscribe: field 'compression' must be one of none, png, cbor, "
                               'cbor-raw')
        if compression != 'none':
            peer.status('warning', f'the relay of colcon-wasm serve forwards JSON: {topic} is '
                                   'sent as '
                                   'JSON (compression none)', msg.get('id'))
        sub = peer.subscriptions.setdefault(topic, {'type': type_name, 'throttle': 0, 'last': 0,
                                                    'ids': set()})
        sub['ids'].add(msg.get('id'))
        sub['throttle'] = (_field(msg, 'throttle_rate', 'int') or 0) / 1000.0
        if type_name and not sub['type']:
            sub['type'] = type_name

    def _op_unsubscribe(self, peer, msg):
        topic = _name(msg, 'topic')
        sub = peer.subscriptions.get(topic)
        if sub is None:
            return
        sub['ids'].discard(msg.get('id'))
        if msg.get('id') is None or not sub['ids']:
            del peer.subscriptions[topic]

    def _op_publish(self, peer, msg):
        topic = _name(msg, 'topic')
        if 'msg' not in msg:
            raise RequestError("publish: field 'msg' is missing (the message to publish)")
        if not isinstance(msg['msg'], dict):
            raise RequestError("publish: field 'msg' must be a JSON object")
        if topic not in peer.publications:
            known = self._known_type(topic) or (_normalize(msg['type'])
                                                if isinstance(msg.get('type'), str) else None)
            if not known:
                raise RequestError(f"publish: cannot infer the type of topic '{topic}': advertise "
                                   'it '
                                   'with a type first')
            peer.publications[topic] = known
        self._check('publish', peer.publications[topic], msg['msg'])
        out = {'op': 'publish', 'topic': topic, 'msg': msg['msg']}
        if isinstance(msg.get('ttl'), (int, float)):
            if msg['ttl'] <= 0:
                return
            out['ttl'] = msg['ttl']
        text = json.dumps(out)
        now = time.monotonic()
        for other in self.peers:
            sub = other.subscriptions.get(topic)
            if other is peer or sub is None:
                continue
            if sub['throttle'] and now - sub['last'] < sub['throttle']:
                continue
            sub['last'] = now
            other.send(text)

    def _provider(self, table, name, what):
        entry = table.get(name)
        if entry is None:
            raise RequestError(f'{what} {name} does not exist: no client of the relay advertised '
                               'it')
        return entry

    def _op_advertise_service(self, peer, msg):
        name = _name(msg, 'service')
        type_name = _normalize(_field(msg, 'type', 'str', True), 'srv')
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
        if name.startswith('/rosapi/') and name[8:] in ROSAPI:
            out = {'op': 'service_response', 'service': msg['service'], 'result': True,
                   'values': self._rosapi(name[8:], msg.get('args') or {})}
            if msg.get('id') is not None:
                out['id'] = msg['id']
            peer.send(out)
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
            p = path + '.' + key if path else key
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
            self._check(op, _normalize(kind), v, path)
            return
        if not ok:
            raise RequestError(f"{where}'{path}': expected {label}, got {json.dumps(v)[:40]}")

    # ------------------------------------------------------------ rosapi

    def _topics(self):
        topics = {}
        for p in self.peers:
            for topic, type_name in p.publications.items():
                topics.setdefault(topic, type_name)
            for topic, sub in p.subscriptions.items():
                if sub['type']:
                    topics.setdefault(topic, sub['type'])
        return dict(sorted(topics.items()))

    def _rosapi(self, name, args):
        def arg(key):
            value = args.get(key) if isinstance(args, dict) else None
            return value if isinstance(value, str) else ''

        def full(value):
            return value if value.startswith('/') else '/' + value

        topics = self._topics()
        services = sorted(set(self.services) | {'/rosapi/' + n for n in ROSAPI})
        if name == 'topics':
            return {'topics': list(topics), 'types': list(topics.values())}
        if name == 'topics_for_type':
            return {'topics': [t for t, ty in topics.items() if ty == _normalize(arg('type'))]}
        if name == 'services':
            return {'services': services}
        if name == 'nodes':
            nodes = {'/rosapi', '/rosbridge_websocket'}
            for p in self.peers:
                nodes.update(p.label)
            return {'nodes': sorted(nodes)}
        if name == 'node_details':
            return {'subscribing': [], 'publishing': [], 'services': []}
        if name == 'topic_type':
            return {'type': topics.get(full(arg('topic')), '')}
        if name == 'service_type':
            entry = self.services.get(full(arg('service')))
            return {'type': entry[1] if entry else ''}
        if name in ('publishers', 'subscribers'):
            topic = full(arg('topic'))
            table = 'publications' if name == 'publishers' else 'subscriptions'
            return {name: sorted({n for p in self.peers if topic in getattr(p, table)
                                  for n in p.label})}
        if name == 'service_providers':
            entry = self.services.get(full(arg('service')))
            return {'providers': entry[0].label if entry else []}
        if name == 'action_servers':
            return {'action_servers': sorted(self.actions)}
        if name == 'message_details':
            return {'typedefs': self._typedefs(arg('type'))}
        if name == 'get_time':
            now = time.time()
            return {'time': {'sec': int(now), 'nanosec': int((now % 1) * 1e9)}}
        return {'version': 2, 'distro': 'humble'}

    def _typedefs(self, type_name):
        out, seen = [], set()

        def visit(full):
            if full in seen or full not in self.messages:
                return
            seen.add(full)
            fields = self.messages[full].get('fields', [])
            nested = []
            td = {'type': full.replace('/msg/', '/'), 'fieldnames': [], 'fieldtypes': [],
                  'fieldarraylen': [], 'examples': [], 'constnames': [], 'constvalues': []}
            for f in fields:
                primitive = f['type'] in PRIMITIVES
                td['fieldnames'].append(f['name'])
                td['fieldtypes'].append(ROSAPI_NAMES.get(f['type'], f['type']) if primitive
                                        else _normalize(f['type']).replace('/msg/', '/'))
                length = f.get('array_size', 0 if f.get('sequence') else -1)
                td['fieldarraylen'].append(length)
                td['examples'].append('[]' if length >= 0 else '{}' if not primitive else '0')
                if not primitive:
                    nested.append(_normalize(f['type']))
            for c in self.messages[full].get('constants', []):
                td['constnames'].append(c['name'])
                td['constvalues'].append(str(c.get('value')))
            out.append(td)
            for n in nested:
                visit(n)

        visit(_normalize(type_name))
        return out
