# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rmw_zenoh's wire conventions in packages/wasm_js/src/bridges/zenoh/keys.mjs, cross-checked.

Against independent implementations: pamoja-ros2 (a Rust implementation of
rmw_zenoh's key assembly and name mangling, from PyPI), zenoh.ext's
serializer (the attachment), and the QoS texts rmw_zenoh_cpp writes for the
common profiles (rmw_zenoh_cpp 0.1.9, src/detail/liveliness_utils.cpp).
"""

import json
from pathlib import Path
import subprocess

import pytest
import zenoh_peers

KEYS = Path(__file__).resolve().parents[1] / 'packages' / 'wasm_js' / 'src' / 'bridges' / 'zenoh' \
    / 'keys.mjs'

CASES = [
    (0, '/chatter', 'std_msgs/msg/String'),
    (7, '/robot1/camera/image_raw', 'sensor_msgs/msg/Image'),
    (0, '/add_two_ints', 'example_interfaces/srv/AddTwoInts'),
    (232, '/a/b/c', 'demo_interfaces/msg/Chatter'),
]

QOS = [
    ({'reliability': 'reliable', 'durability': 'volatile', 'history': 'keep_last', 'depth': 10},
     '::,10:,:,:,,'),
    ({'durability': 'transient_local', 'depth': 1}, ':1:,1:,:,:,,'),
    ({'reliability': 'best_effort', 'depth': 5}, '2::,5:,:,:,,'),
    ({'history': 'keep_all'}, '::2,:,:,:,,'),
    ({'depth': 10, 'deadlineMs': 1000}, '::,10:1,0:,:,,'),
    ({'depth': 42}, '::,:,:,:,,'),
]


def keys_js(request):
    """Run keys.mjs in Node.js on a request; returns its JSON answer."""
    script = f"""
      import * as k from {json.dumps(KEYS.as_uri())};
      const req = {json.dumps(request)};
      const hex = (b) => Buffer.from(b).toString('hex');
      const out = {{
        keys: req.cases.map(([d, n, t]) => k.dataKey(d, n, t)),
        types: req.cases.map(([, , t]) => k.ddsTypeName(t)),
        back: req.cases.map(([, , t]) => k.rosTypeName(k.ddsTypeName(t))),
        mangled: req.cases.map(([, n]) => k.mangle(n)),
        qos: req.qos.map((q) => k.qosText(q)),
        parsedQos: req.qos.map((q) => k.parseQosText(k.qosText(q))),
        attachment: hex(k.encodeAttachment(req.seq, BigInt(req.stamp),
          Buffer.from(req.gid, 'hex'))),
        decoded: (() => {{
          const a = k.decodeAttachment(Buffer.from(req.foreign, 'hex'));
          return [String(a.sequence), String(a.timestampNs), hex(a.gid)];
        }})(),
        token: k.tokenKey(req.token),
        parsedToken: k.parseToken(k.tokenKey(req.token)),
        errors: req.bad.map((t) => {{
          try {{ k.parseToken(t); return null; }} catch (e) {{ return e.message; }}
        }}),
      }};
      console.log(JSON.stringify(out));
    """
    result = subprocess.run(['node', '--input-type=module', '-e', script], capture_output=True,
                            text=True, timeout=60)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


@pytest.fixture(scope='module')
def answer():
    """keys.mjs' answers for the cases."""
    gid = bytes(range(16))
    return keys_js({
        'cases': CASES, 'qos': [q for q, _ in QOS], 'seq': 5, 'stamp': '1700000000123456789',
        'gid': gid.hex(),
        'foreign': zenoh_peers.attachment(9, bytes(range(16, 32)), 1800000000000000001).hex(),
        'token': {'domain': 0, 'zid': '8d5a3e8b6d5f4f1e9c0b2a1d3e4f5a6b', 'nodeId': 0, 'id': 10,
                  'kind': 'MP', 'enclave': '/', 'namespace': '/robot1', 'node': 'cam',
                  'name': '/robot1/image', 'type': 'sensor_msgs/msg/Image',
                  'qos': {'reliability': 'best_effort', 'depth': 5}},
        'bad': ['@ros2_lv/0/z/1/1/NN/%/%', '@ros2_lv/0/z/1/1/MP/%/%/n/%t/std_msgs/Hash/::,:,:,:,,',
                'other/0/z/1/1/NN/%/%/n'],
    })


def test_data_keys_and_names_match_pamoja(answer):
    ros2 = pytest.importorskip('pamoja.ros2',
                               reason='pamoja-ros2 is missing: pip install -e .[test]')
    hash_text = 'RIHS01_' + '00' * 32
    for (domain, name, ros_type), key, dds, mangled, back in zip(
            CASES, answer['keys'], answer['types'], answer['mangled'], answer['back']):
        theirs = ros2.entity_key(domain, name, ros_type, hash_text)
        assert theirs is not None, (domain, name, ros_type)
        # Humble writes TypeHashNotSupported where later distributions put the RIHS01 hash
        assert key == theirs[:-len(hash_text)] + 'TypeHashNotSupported'
        assert dds == ros2.dds_type_name(ros_type)
        assert mangled == ros2.percent_mangle(name)
        assert back == ros_type
        assert key == zenoh_peers.data_key(name, ros_type, domain)


def test_attachments_match_zenoh_ext_serialization(answer):
    gid = bytes(range(16))
    assert answer['attachment'] == zenoh_peers.attachment(5, gid, 1700000000123456789).hex()
    assert answer['decoded'] == ['9', '1800000000000000001', bytes(range(16, 32)).hex()]


def test_qos_texts_are_those_rmw_zenoh_writes(answer):
    assert answer['qos'] == [text for _, text in QOS]
    parsed = answer['parsedQos']
    assert parsed[1]['durability'] == 'transient_local' and parsed[1]['depth'] == 1
    assert parsed[2]['reliability'] == 'best_effort' and parsed[3]['history'] == 'keep_all'
    assert parsed[4]['deadlineMs'] == 1000
    assert parsed[5]['depth'] == 42


def test_tokens_are_built_and_parsed_as_rmw_zenoh_does(answer):
    assert answer['token'] == ('@ros2_lv/0/8d5a3e8b6d5f4f1e9c0b2a1d3e4f5a6b/0/10/MP/%/%robot1/cam/'
                               '%robot1%image/sensor_msgs::msg::dds_::Image_/'
                               'TypeHashNotSupported/2::,5:,:,:,,')
    token = answer['parsedToken']
    assert (token['namespace'], token['node'], token['name'], token['type']) == \
        ('/robot1', 'cam', '/robot1/image', 'sensor_msgs/msg/Image')
    assert token['qos']['reliability'] == 'best_effort' and token['qos']['depth'] == 5
    short, bad_type, prefix = answer['errors']
    assert 'fewer than 9 fields' in short
    assert "is not rmw_zenoh's pkg::msg::dds_::Type_" in bad_type
    assert 'is not an rmw_zenoh liveliness token' in prefix
