# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Complete definitions in rosbag2's ros2msg form, read by a third-party decoder."""

from colcon_wasm import typedesc
from colcon_wasm.ros2msg import DELIMITER
from colcon_wasm.ros2msg import Ros2MsgSchemas
from colcon_wasm.ros2msg import SchemaError
from mcap_ros2._dynamic import generate_dynamic
from mcap_ros2._dynamic import serialize_dynamic
import pytest

TIME = 'int32 sec\nuint32 nanosec\n'
HEADER = '# Standard metadata\nbuiltin_interfaces/Time stamp\nstring frame_id\n'
POINT = 'float64 x\nfloat64 y\n'
SHAPE = ('# a shape with corners\nstd_msgs/Header header\nuint8 KIND_BOX=1\n'
         'uint8 kind\nPoint[] corners\nPoint center\nbuiltin_interfaces/Time[2] seen\n')
FIX = 'int64 a\n---\nShape shape\n'


def _schemas(tmp_path):
    files = {
        ('builtin_interfaces', 'msg', 'Time'): TIME,
        ('std_msgs', 'msg', 'Header'): HEADER,
        ('shapes', 'msg', 'Point'): POINT,
        ('shapes', 'msg', 'Shape'): SHAPE,
        ('shapes', 'srv', 'Fix'): FIX,
    }
    documents = []
    for package in ('builtin_interfaces', 'std_msgs', 'shapes'):
        share = tmp_path / 'share' / package
        for (owner, kind, name), text in files.items():
            if owner == package:
                (share / kind).mkdir(parents=True, exist_ok=True)
                (share / kind / f'{name}.{kind}').write_text(text)
        documents.append(typedesc.describe_package(share, package))
    return Ros2MsgSchemas.from_documents(documents)


def test_full_text_is_rosbag2s_form(tmp_path):
    text = _schemas(tmp_path).full_text('shapes/msg/Shape')
    # the own text first, then each dependency once, depth first, sorted
    assert text == (
        SHAPE
        + f'\n{DELIMITER}\nMSG: builtin_interfaces/Time\n' + TIME
        + f'\n{DELIMITER}\nMSG: shapes/Point\n' + POINT
        + f'\n{DELIMITER}\nMSG: std_msgs/Header\n' + HEADER)
    assert _schemas(tmp_path).full_text('shapes/Shape') == text


def test_a_third_party_decoder_reads_the_schema(tmp_path):
    text = _schemas(tmp_path).full_text('shapes/msg/Shape')
    encode = serialize_dynamic('shapes/msg/Shape', text)['shapes/msg/Shape']
    decode = generate_dynamic('shapes/msg/Shape', text)['shapes/msg/Shape']
    data = encode({
        'header': {'stamp': {'sec': 3, 'nanosec': 4}, 'frame_id': 'map'},
        'kind': 1, 'corners': [{'x': 1.0, 'y': 2.0}], 'center': {'x': 0.5, 'y': 0.25},
        'seen': [{'sec': 1, 'nanosec': 2}, {'sec': 5, 'nanosec': 6}]})
    message = decode(data)
    assert message.header.frame_id == 'map'
    assert message.header.stamp.nanosec == 4
    assert [(p.x, p.y) for p in message.corners] == [(1.0, 2.0)]
    assert message.seen[1].sec == 5
    assert message.kind == 1


def test_service_parts_have_definitions(tmp_path):
    text = _schemas(tmp_path).full_text('shapes/srv/Fix_Response')
    assert text.startswith('Shape shape' + f'\n{DELIMITER}\nMSG: shapes/Shape\n' + SHAPE)


def test_unknown_types_are_named_with_their_user(tmp_path):
    schemas = _schemas(tmp_path)
    with pytest.raises(SchemaError, match="no type description of 'nope/msg/X'"):
        schemas.full_text('nope/msg/X')
    broken = Ros2MsgSchemas({'a/msg/A': {
        'fields': [{'name': 'b', 'type': 'b/msg/B'}], 'constants': [], 'definition': 'b/B b\n'}})
    with pytest.raises(SchemaError, match="'b/msg/B' \\(used by 'a/msg/A'\\)"):
        broken.full_text('a/msg/A')
    old = Ros2MsgSchemas({'a/msg/A': {'fields': [], 'constants': []}})
    with pytest.raises(SchemaError, match='older colcon-wasm'):
        old.full_text('a/msg/A')
