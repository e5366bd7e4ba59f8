# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's MCAP reader and writer (packages/wasm_js/src/page/mcap_*.mjs) against third parties.

Python writes the inputs (the ``mcap`` writer: uncompressed chunks whose
log times overlap, and zstd chunks; serve's own recorder,
``colcon_wasm.record.bag_writer.BagWriter``), and the expected texts
(``colcon_wasm/ros2msg.py``'s schemas, ``qos.py``'s QoS YAML and player
QoS). tests/js/test_mcap_page.mjs (``node --test``) reads them with the
page's reader, writes a bag of Fast CDR golden messages with the page's
writer, and reads that back with ``@mcap/core``. Here ``mcap`` and
``mcap-ros2-support`` read the page's bag: the topics, types, counts,
times and decoded values, with its CRCs checked.
"""

import json
from pathlib import Path
import random
import shutil
import subprocess
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import cdr_fastcdr  # noqa: E402, I100
import pytest  # noqa: E402, I100, I202

REPO = Path(__file__).resolve().parents[1]
JS_TEST = REPO / 'tests' / 'js' / 'test_mcap_page.mjs'
# the golden vectors the page's bag carries, per topic (decoded by mcap-ros2-support)
PLAYED_TYPES = ('cdr_test_msgs/msg/Primitives', 'cdr_test_msgs/msg/Inner',
                'cdr_test_msgs/msg/Defaults')
QOS_CASES = [
    [],
    [{'history': 'keep_last', 'depth': 7, 'reliability': 'best_effort',
      'durability': 'transient_local', 'deadlineMs': 0, 'lifespanMs': 1500.5,
      'liveliness': 'automatic', 'leaseMs': 0}],
    [{'history': 'keep_all', 'depth': 0, 'reliability': 'reliable', 'durability': 'volatile',
      'deadlineMs': 100, 'lifespanMs': 0, 'liveliness': 'manual_by_topic', 'leaseMs': 2000},
     {'depth': 10}],
]
PLAYER_QOS_TEXTS = [
    '',
    'not: [yaml',
    '- history: 1\n  depth: 5\n  reliability: 1\n  durability: 1\n'
    '  lifespan: {sec: 2, nsec: 500}\n',
    '- {history: keep_last, depth: 3, reliability: best_effort, durability: volatile}\n'
    '- {history: keep_last, depth: 9, reliability: reliable, durability: volatile}\n',
    '- history: 3\n  depth: 0\n  reliability: 2\n  durability: 2\n',
]


def _schemas(types):
    from colcon_wasm.ros2msg import Ros2MsgSchemas
    return Ros2MsgSchemas.from_documents([types])


def _python_bag(path, types):
    """Write /a and /b with the mcap writer, small chunks, log times not in file order."""
    from mcap.writer import CompressionType, Writer
    schemas = _schemas(types)
    rng = random.Random(41)
    expected = []
    with open(path, 'wb') as f:
        writer = Writer(f, chunk_size=200, compression=CompressionType.NONE)
        writer.start(profile='ros2', library='test')
        channels = {}
        for topic, type_name in (('/a', 'cdr_test_msgs/msg/Inner'),
                                 ('/b', 'cdr_test_msgs/msg/Primitives')):
            schema = writer.register_schema(type_name, 'ros2msg',
                                            schemas.full_text(type_name).encode())
            channels[topic] = writer.register_channel(
                topic, 'cdr', schema, {'offered_qos_profiles': ''})
        for i in range(60):
            topic = '/a' if i % 3 else '/b'
            jitter = rng.randrange(-25, 25) * 1_000_000
            log_time = 1_700_000_000_000_000_000 + i * 10_000_000 + jitter
            data = bytes([0, 1, 0, 0]) + i.to_bytes(4, 'little') + bytes(rng.randrange(0, 40))
            writer.add_message(channels[topic], log_time, data, log_time - 5)
            expected.append({'topic': topic, 'logTime': str(log_time), 'hex': data.hex()})
        writer.finish()
    expected.sort(key=lambda m: int(m['logTime']))  # stable: file order among equal times
    return expected


def _zstd_bag(path, types):
    from mcap.writer import CompressionType, Writer
    with open(path, 'wb') as f:
        writer = Writer(f, compression=CompressionType.ZSTD)
        writer.start(profile='ros2', library='test')
        schema = writer.register_schema('cdr_test_msgs/msg/Inner', 'ros2msg', b'uint8 tag\n')
        channel = writer.register_channel('/z', 'cdr', schema)
        for i in range(5):
            writer.add_message(channel, i, bytes([0, 1, 0, 0, i]), i)
        writer.finish()


def _serve_recorder_bag(path, types):
    """Write a bag as serve's recorder (and colcon-wasm record) write it: BagWriter."""
    from colcon_wasm.record.bag_writer import BagWriter
    writer = BagWriter(path, _schemas(types), compression='none')
    channel = writer.add_topic('/rec', 'cdr_test_msgs/msg/Inner',
                               [{'reliability': 'reliable', 'durability': 'transient_local',
                                 'depth': 4}])
    expected = []
    for i in range(8):
        data = bytes([0, 1, 0, 0, i, 0, 0, 0])
        writer.write(channel, 1_000_000_000 * (i + 1), 1_000_000_000 * (i + 1), data)
        expected.append({'topic': '/rec', 'logTime': str(1_000_000_000 * (i + 1)),
                         'hex': data.hex()})
    writer.close()
    return expected


@pytest.fixture(scope='module')
def page_run(tmp_path_factory):
    """Write the inputs and expectations, run the node tests; their output and the page's bag."""
    from colcon_wasm.record.qos import player_qos, to_rosbag2
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    folder = tmp_path_factory.mktemp('mcap_page')
    types = cdr_fastcdr.load_types()
    schemas = _schemas(types)
    (folder / 'types.json').write_text(json.dumps(types), encoding='utf-8')
    vectors = [case for document in cdr_fastcdr.load_vectors().values()
               for case in document['vectors'] if case['type'] in PLAYED_TYPES]
    fixtures = {
        'types': str(folder / 'types.json'),
        'texts': {name: schemas.full_text(name) for name in schemas.names()},
        'qos': [{'profiles': case, 'yaml': to_rosbag2(case)} for case in QOS_CASES],
        'playerQos': [{'text': text, 'qos': player_qos(text)} for text in PLAYER_QOS_TEXTS],
        'pythonBag': str(folder / 'python.mcap'),
        'pythonExpected': _python_bag(folder / 'python.mcap', types),
        'recorderBag': str(folder / 'recorder.mcap'),
        'recorderExpected': _serve_recorder_bag(folder / 'recorder.mcap', types),
        'zstdBag': str(folder / 'zstd.mcap'),
        'vectors': [{'name': v['name'], 'type': v['type'], 'hex': v['hex']} for v in vectors],
        'out': str(folder / 'page.mcap'),
    }
    _zstd_bag(folder / 'zstd.mcap', types)
    (folder / 'fixtures.json').write_text(json.dumps(fixtures), encoding='utf-8')
    result = subprocess.run(
        [node, '--test', '--test-reporter=tap', str(JS_TEST)],
        env={'MCAP_FIXTURES': str(folder / 'fixtures.json'), 'PATH': '/usr/bin:/bin'},
        capture_output=True, text=True, timeout=300)
    return {'result': result, 'out': Path(fixtures['out']), 'vectors': fixtures['vectors']}


def test_the_node_tests_pass(page_run):
    result = page_run['result']
    failures = [line for line in result.stdout.splitlines() if line.startswith('not ok')]
    assert result.returncode == 0, '\n'.join(failures) + '\n' + result.stdout[-8000:] + \
        result.stderr[-3000:]
    assert '# fail 0' in result.stdout
    assert '# pass 0' not in result.stdout


def _values(cases):
    by_name = {name: value for name, _, value in cdr_fastcdr.all_cases(cdr_fastcdr.load_vectors())}
    return [by_name[v['name']] for v in cases]


def _same(decoded, value, where):
    """Compare a mcap-ros2-support message with a golden vector's JSON value."""
    if isinstance(value, dict):
        for key, item in value.items():
            _same(getattr(decoded, key), item, f'{where}.{key}')
    elif isinstance(value, list):
        assert len(decoded) == len(value), where
        for i, (a, b) in enumerate(zip(decoded, value)):
            _same(a, b, f'{where}[{i}]')
    elif isinstance(value, float) or value in ('NaN', 'Infinity', '-Infinity'):
        value = float(value)  # the vectors name non-finite values
        assert decoded == pytest.approx(value, rel=1e-6, nan_ok=True), where
    elif isinstance(value, str) and isinstance(decoded, int):
        assert decoded == int(value), where  # 64-bit integers are strings in the vectors
    elif isinstance(value, bool):
        assert bool(decoded) is value, where
    elif where.endswith('char_value'):
        assert decoded & 0xff == value, where  # mcap-ros2-support reads a char as int8
    else:
        assert decoded == value, where


def test_the_page_bag_is_read_by_mcap_and_mcap_ros2_support(page_run):
    assert page_run['result'].returncode == 0, page_run['result'].stdout[-4000:]
    from mcap.reader import make_reader
    from mcap.stream_reader import StreamReader
    from mcap_ros2.decoder import DecoderFactory
    path = page_run['out']
    cases = page_run['vectors']
    with open(path, 'rb') as f:
        reader = make_reader(f, validate_crcs=True, decoder_factories=[DecoderFactory()])
        header = reader.get_header()
        assert (header.profile, header.library) == ('ros2', 'colcon-wasm page')
        summary = reader.get_summary()
        assert summary.statistics.message_count == len(cases)
        assert len(summary.chunk_indexes) >= 2  # the node test writes more than a chunk
        assert {c.topic for c in summary.channels.values()} == \
            {'/' + t.split('/')[-1].lower() for t in PLAYED_TYPES}
        for channel in summary.channels.values():
            schema = summary.schemas[channel.schema_id]
            assert channel.message_encoding == 'cdr' and schema.encoding == 'ros2msg'
            assert channel.metadata['offered_qos_profiles'].startswith('- history: 1\n')
        decoded = list(reader.iter_decoded_messages(log_time_order=True))
    assert len(decoded) == len(cases)
    times = [m.log_time for _, _, m, _ in decoded]
    assert times == sorted(times)
    for (schema, channel, message, value), case, expected in zip(decoded, cases, _values(cases)):
        assert schema.name == case['type']
        assert channel.topic == '/' + case['type'].split('/')[-1].lower()
        assert message.data.hex() == case['hex']
        _same(value, expected, case['name'])
    # the stream reader checks every CRC (the chunks', the data section's, the summary's)
    with open(path, 'rb') as f:
        records = list(StreamReader(f, validate_crcs=True).records)
    assert type(records[-1]).__name__ == 'Footer'
