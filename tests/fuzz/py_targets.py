# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Python fuzz targets: each feeds one input to the entry point the server or reader uses.

* ``relay``: serve's rosbridge relay (colcon_wasm/server/relay.py), one
  WebSocket message (text when it is UTF-8, else CBOR) through
  ``Relay.receive``, as ``Relay.serve`` calls it; the peer's connection is
  a stand-in that records what is sent back.
* ``mcap``: the bag reading side of ``colcon-wasm play``, ``bag-info`` and
  the page's bag player (colcon_wasm/server/bag_socket.py): a file read
  with ``BagSpan`` (``read_messages``) and the recorded QoS
  (``player_qos``), then ``bag_info``.
* ``launch_xml``, ``launch_yaml``: colcon-wasm's own launch-file reader
  (colcon_wasm/launch/loader.py ``load_launch_file``).
* ``params``: the parameter-file reader of launch files
  (``parameters_from_file``) and the QoS override file of play
  (colcon_wasm/record/qos.py ``read_overrides``).

Each target has ``one(data)``, which returns the class of the outcome and
raises :class:`Finding` (or lets an unexpected exception out) when the
rule is broken: a malformed input is answered with the protocol's error,
or refused with the reader's own error type, and nothing else; ``check()``,
which feeds a well-formed input to the same instance and raises unless it
gets the right answer; and ``seeds()``, the seed corpus as it is captured
from the project's own tools (``capture()`` writes it).
"""

import json
from pathlib import Path
import re
import shutil
import sys
import tempfile
import threading
import time

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO))
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

CORPUS = REPO / 'tests' / 'fuzz_corpus'
INNER = 'cdr_test_msgs/msg/Inner'


class Finding(Exception):
    """The rule was broken: the message says how."""


def corpus_dir(name):
    """Return the seed corpus folder of a target."""
    return CORPUS / name


def read_corpus(folder):
    """Return the files of a corpus folder (not its regressions/), sorted by name."""
    folder = Path(folder)
    if not folder.is_dir():
        return []
    return [p.read_bytes() for p in sorted(folder.iterdir()) if p.is_file()]


def _types():
    import cdr_fastcdr
    return cdr_fastcdr.load_types()


def _until(predicate, seconds, what):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.005)
    raise Finding(f'{what}: not within {seconds} s')


# ------------------------------------------------------------------ relay

class RecordingConnection:
    """A stand-in for websocket.Connection: it keeps what the relay sends."""

    def __init__(self):  # noqa: D107
        self.sent = []
        self.lock = threading.Lock()
        self.queued_bytes = 0
        self.closed = False

    def send(self, data):
        """Keep a message (the last 2000)."""
        with self.lock:
            self.sent.append(data)
            if len(self.sent) > 2000:
                del self.sent[:1000]
        return True

    def watch_drain(self, level):
        """Say the socket is below ``level`` (nothing waits here)."""
        return False

    def close(self, code=None, reason='', now=False):
        """Mark the connection closed."""
        self.closed = True

    def take(self):
        """Return and forget what was sent since the last call."""
        with self.lock:
            out, self.sent = self.sent, []
        return out


def outcome_of(sent):
    """Classify what came back: ops and status texts, numbers and quotes folded."""
    kinds = set()
    for m in sent:
        if not isinstance(m, str):
            kinds.add('binary')
            continue
        try:
            o = json.loads(m)
        except ValueError:
            kinds.add('text')
            continue
        if o.get('op') == 'status':
            text = re.sub(r"'[^']*'|\"[^\"]*\"", 'Q', str(o.get('msg')))
            kinds.add(f"status {o.get('level')} {re.sub(r'[0-9]+', 'N', text)[:90]}")
        else:
            kinds.add(str(o.get('op')))
    return ' | '.join(sorted(kinds)) or 'silent'


def _json(sent):
    """Return the JSON objects among sent messages."""
    out = []
    for m in list(sent):
        try:
            o = json.loads(m) if isinstance(m, str) else None
        except ValueError:
            o = None
        if isinstance(o, dict):
            out.append(o)
    return out


def as_message(data):
    """Return ``(message, binary)``: text when the bytes are UTF-8, else bytes."""
    try:
        return data.decode('utf-8'), False
    except UnicodeDecodeError:
        return data, True


class RelayTarget:
    """serve's rosbridge relay, one message at a time through ``Relay.receive``."""

    name = 'relay'
    CHECK_TOPIC = '/fuzz_check_relay'

    def __init__(self):  # noqa: D107
        from colcon_wasm.server.relay import Peer
        from colcon_wasm.server.relay import Relay
        self.relay = Relay(types=[_types()], max_message_bytes=1 << 20, call_timeout=0.3)
        self.conn = RecordingConnection()
        self.watcher = RecordingConnection()
        self.peer = Peer(self.relay, self.conn, 1, 'fuzz')
        self.observer = Peer(self.relay, self.watcher, 2, 'observer')
        self.relay.peers.update({self.peer, self.observer})
        self.relay.receive(self.observer, json.dumps(
            {'op': 'subscribe', 'topic': self.CHECK_TOPIC, 'type': INNER}), False)
        self.round = 0

    def one(self, data):
        """Feed one message; return the class of the answer."""
        message, binary = as_message(data)
        self.relay.receive(self.peer, message, binary)
        return outcome_of(self.conn.take())

    def check(self):
        """Check that a rosapi call is answered and a publish reaches the other client."""
        self.round += 1
        rid = f'check-{self.round}'
        self.conn.take()
        self.relay.receive(self.peer, json.dumps(
            {'op': 'call_service', 'service': '/rosapi/topics', 'id': rid}), False)
        _until(lambda: any(m.get('id') == rid and m.get('op') == 'service_response'
                           and m.get('result') is True for m in _json(self.conn.sent)),
               3, f'the rosapi call {rid}')
        self.watcher.take()
        self.relay.receive(self.peer, json.dumps(
            {'op': 'publish', 'topic': self.CHECK_TOPIC, 'type': INNER,
             'msg': {'tag': 1, 'x': 0.5, 'label': rid}}), False)
        _until(lambda: any(m.get('op') == 'publish' and (m.get('msg') or {}).get('label') == rid
                           for m in _json(self.watcher.sent)), 3,
               f'a publish of {rid} at the other client')
        self.conn.take()

    def close(self):
        """Stop the relay."""
        self.relay.close()

    @classmethod
    def capture(cls):
        """Return ``[(name, bytes)]``: a scripted session's requests and the relay's answers."""
        from colcon_wasm.server.relay import Peer
        from colcon_wasm.server.relay import Relay
        relay = Relay(types=[_types()], call_timeout=0.5)
        a, b = RecordingConnection(), RecordingConnection()
        pa, pb = Peer(relay, a, 1, 'a'), Peer(relay, b, 2, 'b')
        relay.peers.update({pa, pb})
        seeds = []

        def send(peer, name, msg):
            data = msg if isinstance(msg, (str, bytes)) else json.dumps(msg)
            seeds.append((f'request-{name}', data.encode('utf-8') if isinstance(data, str)
                          else data))
            relay.receive(peer, data, isinstance(data, bytes))
            time.sleep(0.03)

        inner = {'tag': 7, 'x': 2.5, 'label': 'hello'}
        send(pb, 'set-level', {'op': 'set_level', 'level': 'info'})
        send(pb, 'subscribe', {'op': 'subscribe', 'id': 's1', 'topic': '/chatter', 'type': INNER,
                               'queue_length': 2, 'throttle_rate': 0})
        send(pb, 'subscribe-fragments', {'op': 'subscribe', 'id': 's2', 'topic': '/chatter',
                                         'type': INNER, 'fragment_size': 24})
        send(pb, 'subscribe-cbor', {'op': 'subscribe', 'topic': '/nested',
                                    'type': 'cdr_test_msgs/msg/Nested', 'compression': 'cbor'})
        send(pb, 'subscribe-cbor-raw', {'op': 'subscribe', 'topic': '/seq',
                                        'type': 'cdr_test_msgs/msg/Sequences',
                                        'compression': 'cbor-raw'})
        send(pb, 'subscribe-png', {'op': 'subscribe', 'topic': '/chatter', 'type': INNER,
                                   'compression': 'png', 'id': 's3'})
        send(pa, 'graph', {'op': 'colcon_wasm_graph', 'version': 2, 'nodes': ['/talker'],
                           'endpoints': {'/talker': {'publishing': ['/chatter'],
                                                     'subscribing': [], 'services': ['/add']}}})
        send(pa, 'advertise', {'op': 'advertise', 'topic': '/chatter', 'type': INNER})
        send(pa, 'publish', {'op': 'publish', 'topic': '/chatter', 'msg': inner})
        send(pa, 'publish-nested', {'op': 'publish', 'topic': '/nested',
                                    'type': 'cdr_test_msgs/msg/Nested',
                                    'msg': {'lead': 1, 'inner': inner, 'more': [inner]}})
        # the CBOR publish of colcon-wasm's rosbridge client (client_topics.mjs cdrPublish),
        # as the Node.js target captured it
        cdr = corpus_dir('rosbridge') / 'request-publish-cdr'
        if cdr.is_file():
            send(pa, 'publish-cdr', cdr.read_bytes())
        send(pb, 'advertise-service', {'op': 'advertise_service', 'service': '/add',
                                       'type': 'cdr_test_msgs/srv/AddTwoInts'})
        send(pa, 'call-service', {'op': 'call_service', 'id': 'c1', 'service': '/add',
                                  'args': {'a': 2, 'b': 40}})
        call = next((json.loads(m) for m in b.sent if isinstance(m, str)
                     and '"call_service"' in m), None)
        if call:
            send(pb, 'service-response', {'op': 'service_response', 'id': call['id'],
                                          'service': '/add', 'values': {'sum': 42},
                                          'result': True})
        for service in ('topics', 'nodes', 'services', 'topic_type', 'message_details'):
            send(pa, f'rosapi-{service}', {'op': 'call_service', 'id': f'r-{service}',
                                           'service': f'/rosapi/{service}',
                                           'args': {'topic': '/chatter', 'type': INNER}})
        send(pb, 'advertise-action', {'op': 'advertise_action', 'action': '/fib',
                                      'type': 'cdr_test_msgs/action/Fibonacci'})
        send(pa, 'send-action-goal', {'op': 'send_action_goal', 'id': 'g1', 'action': '/fib',
                                      'action_type': 'cdr_test_msgs/action/Fibonacci',
                                      'args': {'order': 3}, 'feedback': True})
        send(pa, 'fragment-0', {'op': 'fragment', 'id': 'f1', 'num': 0, 'total': 2,
                                'data': '{"op":"call_service","service":'})
        send(pa, 'fragment-1', {'op': 'fragment', 'id': 'f1', 'num': 1, 'total': 2,
                                'data': '"/rosapi/services","id":"f1"}'})
        send(pa, 'unadvertise', {'op': 'unadvertise', 'topic': '/chatter'})
        send(pb, 'unsubscribe', {'op': 'unsubscribe', 'topic': '/chatter', 'id': 's1'})
        send(pa, 'malformed', '{"op": "publish", "id": "m1", ')
        time.sleep(0.3)
        kinds = set()
        for who, conn in (('a', a), ('b', b)):
            for m in conn.sent:
                kind = json.loads(m).get('op') if isinstance(m, str) else 'binary'
                if (who, kind) in kinds:
                    continue
                kinds.add((who, kind))
                seeds.append((f'sent-{who}-{kind}', m.encode('utf-8') if isinstance(m, str)
                              else bytes(m)))
        relay.close()
        return seeds


# ------------------------------------------------------------------- mcap

class McapTarget:
    """The bag reading side: BagSpan (read_messages, player_qos) and bag_info."""

    name = 'mcap'

    def __init__(self):  # noqa: D107
        self.folder = Path(tempfile.mkdtemp(prefix='fuzz-mcap-'))
        self.path = self.folder / 'input.mcap'
        seeds = sorted(p for p in corpus_dir(self.name).glob('*.mcap'))
        self.good = seeds[0].read_bytes() if seeds else None

    def _read(self, data):
        from colcon_wasm.record import BagError
        from colcon_wasm.record.bag_info import bag_info
        from colcon_wasm.record.bag_info import format_info
        from colcon_wasm.record.paced_player import BagSpan
        from colcon_wasm.record.qos import player_qos
        self.path.write_bytes(data)
        topics = []

        def on_topic(topic):
            # what the page's bag player does with a channel (bag_socket.py _open_bag)
            topics.append((topic.name, topic.type, player_qos(topic.qos)))
            return True
        span = BagSpan(self.path, on_topic)
        outcome = f'{span.count and "messages"} '
        outcome += f'error {_fold(span.error)}' if span.error else ''
        try:
            info = bag_info(self.path)
            format_info(info)
            outcome += ' | info'
        except BagError as e:
            outcome += f' | info refused {_fold(str(e))}'
        return outcome, span, topics

    def one(self, data):
        """Read one file; return the class of the result."""
        return self._read(data)[0]

    def check(self):
        """Check that a well-formed bag is read whole."""
        if self.good is None:
            return
        _, span, topics = self._read(self.good)
        if span.error or span.count < 1 or not topics:
            raise Finding(f'a well-formed bag was not read: {span.error}, {span.count} messages')

    def close(self):
        """Remove the temporary folder."""
        shutil.rmtree(self.folder, ignore_errors=True)

    @classmethod
    def capture(cls):
        """Return ``[(name, bytes)]``: small bags written by the project's BagWriter."""
        from colcon_wasm.record.bag_writer import BagWriter
        from colcon_wasm.ros2msg import Ros2MsgSchemas
        import cdr_fastcdr
        types = cdr_fastcdr.load_types()
        schemas = Ros2MsgSchemas.from_documents([types])
        # small types: the seeds stay a few KB
        cases = [c for c in _golden_cases() if c[1] in (INNER, 'cdr_test_msgs/msg/Empty')]
        seeds = []
        folder = Path(tempfile.mkdtemp(prefix='fuzz-mcap-capture-'))
        qos = [{'history': 'keep_last', 'depth': 10, 'reliability': 'reliable',
                'durability': 'transient_local', 'lifespanMs': 0, 'deadlineMs': 0}]
        for compression in ('none', 'zstd'):
            path = folder / f'{compression}.mcap'
            writer = BagWriter(path, schemas, compression=compression)
            channels = {}
            t = 1_700_000_000_000_000_000
            for name, type_name, data in cases:
                if type_name not in channels:
                    channels[type_name] = writer.add_topic(
                        f"/{type_name.split('/')[-1].lower()}", type_name, qos)
                writer.write(channels[type_name], t, t, data)
                t += 1_000_000
            writer.close()
            seeds.append((f'bag-{compression}.mcap', path.read_bytes()))
        shutil.rmtree(folder, ignore_errors=True)
        return seeds


def _golden_cases():
    """Return ``[(name, type, bytes)]`` of the golden CDR vectors (tests/data/cdr)."""
    out = []
    for path in sorted((REPO / 'tests' / 'data' / 'cdr').glob('*.json')):
        for v in json.loads(path.read_text(encoding='utf-8'))['vectors']:
            out.append((v['name'], v['type'], bytes.fromhex(v['hex'])))
    return out


def _fold(text):
    text = re.sub(r"'[^']*'|\"[^\"]*\"", 'Q', str(text))
    return re.sub(r'[0-9]+', 'N', text)[:100]


# ----------------------------------------------------------------- launch

LAUNCH_SEEDS = ('demo/src/demo_nodes/launch/demo.launch.yaml',
                'demo/src/demo_nodes/launch/talker_listener.launch.xml',
                'tests/data/pyodide/services.launch.xml',
                'tests/ros_fixtures/launch_cases/launch/listener.launch.yaml')

GOOD_XML = """<launch>
  <arg name="rate" default="5"/>
  <group>
    <push-ros-namespace namespace="robot"/>
    <node pkg="demo_nodes" exec="talker" name="talker" args="--count 3">
      <param name="rate" value="$(var rate)"/>
      <remap from="chatter" to="/robot/chatter"/>
    </node>
  </group>
  <node pkg="demo_nodes" exec="listener" if="$(eval '1 + 1 == 2')"/>
</launch>
"""

GOOD_YAML = """launch:
- arg: {name: rate, default: '5'}
- node:
    pkg: demo_nodes
    exec: talker
    name: talker
    param: [{name: rate, value: $(var rate)}]
    remap: [{from: chatter, to: /chatter}]
- node: {pkg: demo_nodes, exec: listener}
"""


class LaunchTarget:
    """colcon-wasm's launch-file reader: load_launch_file of one XML or YAML file."""

    def __init__(self, suffix):  # noqa: D107
        self.suffix = suffix
        self.name = f'launch_{suffix}'
        self.folder = Path(tempfile.mkdtemp(prefix=f'fuzz-{self.name}-'))
        self.path = self.folder / f'input.launch.{suffix}'
        self.good = GOOD_XML if suffix == 'xml' else GOOD_YAML

    def _load(self, data):
        from colcon_wasm.launch import load_launch_file
        self.path.write_bytes(data)
        return load_launch_file(self.path, {}, environ={'HOME': '/nonexistent'})

    def one(self, data):
        """Load one file; return the class of the result."""
        from colcon_wasm.launch import LaunchError
        try:
            plan = self._load(data)
        except LaunchError as e:
            return f'LaunchError {_fold(str(e).replace(str(self.path), "F"))}'
        return f'plan of {min(len(plan.processes), 3)} processes'

    def check(self):
        """Check that a well-formed launch file gives its two nodes."""
        plan = self._load(self.good.encode('utf-8'))
        if len(plan.processes) != 2 or plan.processes[0].name != 'talker':
            raise Finding(f'a well-formed launch file gave {plan.processes}')

    def close(self):
        """Remove the temporary folder."""
        shutil.rmtree(self.folder, ignore_errors=True)

    def capture(self):
        """Return ``[(name, bytes)]``: the project's own launch files of this kind."""
        seeds = [(f'good.launch.{self.suffix}', self.good.encode('utf-8'))]
        for rel in LAUNCH_SEEDS:
            if rel.endswith(f'.{self.suffix}'):
                seeds.append((Path(rel).name, (REPO / rel).read_bytes()))
        return seeds


# ----------------------------------------------------------------- params

GOOD_PARAMS = """talker:
  ros__parameters:
    rate: 5
    name: talker
    nested: {gain: 0.5, names: [a, b]}
/**:
  ros__parameters:
    use_sim_time: false
"""

GOOD_OVERRIDES = """/chatter:
  reliability: best_effort
  history: keep_last
  depth: 5
  deadline: {sec: 1, nsec: 0}
"""


class ParamsTarget:
    """The parameter-file reader of launch files and play's QoS override file."""

    name = 'params'

    def __init__(self):  # noqa: D107
        self.folder = Path(tempfile.mkdtemp(prefix='fuzz-params-'))
        self.path = self.folder / 'params.yaml'

    def one(self, data):
        """Read one file both ways; return the class of the results."""
        from colcon_wasm.launch import LaunchError
        from colcon_wasm.launch.loader import parameters_from_file
        from colcon_wasm.record.qos import QosOverrideError
        from colcon_wasm.record.qos import read_overrides
        self.path.write_bytes(data)
        try:
            params = parameters_from_file(self.path, 'talker', (self.path, 3))
            outcome = f'parameters {min(len(params), 3)}'
        except LaunchError as e:
            outcome = f'LaunchError {_fold(str(e).replace(str(self.path), "F"))}'
        try:
            outcome += f' | overrides {min(len(read_overrides(self.path)), 3)}'
        except QosOverrideError as e:
            outcome += f' | QosOverrideError {_fold(str(e).replace(str(self.path), "F"))}'
        return outcome

    def check(self):
        """Check that well-formed files give their parameters and profiles."""
        from colcon_wasm.launch.loader import parameters_from_file
        from colcon_wasm.record.qos import read_overrides
        self.path.write_text(GOOD_PARAMS, encoding='utf-8')
        params = parameters_from_file(self.path, 'talker', (self.path, 3))
        if ('rate', '5', 'talker') not in params or len(params) != 5:
            raise Finding(f'a well-formed parameters file gave {params}')
        self.path.write_text(GOOD_OVERRIDES, encoding='utf-8')
        profile = read_overrides(self.path)['/chatter']
        if profile['reliability'] != 'best_effort' or profile['depth'] != 5:
            raise Finding(f'a well-formed QoS override file gave {profile}')

    def close(self):
        """Remove the temporary folder."""
        shutil.rmtree(self.folder, ignore_errors=True)

    @classmethod
    def capture(cls):
        """Return ``[(name, bytes)]``: parameter and override files as the docs write them."""
        return [('params.yaml', GOOD_PARAMS.encode('utf-8')),
                ('overrides.yaml', GOOD_OVERRIDES.encode('utf-8'))]


TARGETS = {
    'relay': RelayTarget,
    'mcap': McapTarget,
    'launch_xml': lambda: LaunchTarget('xml'),
    'launch_yaml': lambda: LaunchTarget('yaml'),
    'params': ParamsTarget,
}


def make(name):
    """Create a target by name."""
    return TARGETS[name]()


def capture(name):
    """Write the seed corpus of a target into tests/fuzz_corpus/NAME; return the count."""
    target = TARGETS[name]
    seeds = target().capture() if name.startswith('launch_') else target.capture()
    folder = corpus_dir(name)
    folder.mkdir(parents=True, exist_ok=True)
    for file_name, data in seeds:
        (folder / file_name).write_bytes(data)
    return len(seeds)
