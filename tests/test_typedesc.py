# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Tests of colcon_wasm.typedesc: the .msg/.srv/.action grammar as JSON."""

import importlib.util
import json
import os
from pathlib import Path
import tarfile

from colcon_wasm import typedesc
from colcon_wasm.typedesc import TypeDescriptionError
import pytest

REPO = Path(__file__).resolve().parents[1]


def _fields(text, package='pkg'):
    return typedesc.parse_message(package, 'T', text)['fields']


def test_primitive_fields_and_comments():
    fields = _fields(
        '# file comment\n'
        'bool a  # trailing comment\n'
        '\tbyte b\n'
        'char c\n'
        'float32 d\nfloat64 e\nint8 f\nuint8 g\nint16 h\nuint16 i\n'
        'int32 j\nuint32 k\nint64 l\nuint64 m\nstring n\nwstring o\n')
    assert [f['name'] for f in fields] == list('abcdefghijklmno')
    assert [f['type'] for f in fields] == list(typedesc.PRIMITIVE_TYPES)
    assert all(set(f) == {'name', 'type'} for f in fields)


def test_arrays_sequences_and_bounded_strings():
    fields = _fields(
        'int32[3] fixed\n'
        'int32[] unbounded\n'
        'int32[<=4] bounded\n'
        'string<=5 short\n'
        'wstring<=6 wide\n'
        'string<=7[2] short_array\n'
        'string<=8[<=9] short_sequence\n')
    assert fields == [
        {'name': 'fixed', 'type': 'int32', 'array_size': 3},
        {'name': 'unbounded', 'type': 'int32', 'sequence': True},
        {'name': 'bounded', 'type': 'int32', 'sequence': True, 'sequence_bound': 4},
        {'name': 'short', 'type': 'string', 'string_bound': 5},
        {'name': 'wide', 'type': 'wstring', 'string_bound': 6},
        {'name': 'short_array', 'type': 'string', 'string_bound': 7, 'array_size': 2},
        {'name': 'short_sequence', 'type': 'string', 'string_bound': 8,
         'sequence': True, 'sequence_bound': 9},
    ]


def test_nested_types_with_implicit_and_explicit_package():
    fields = _fields(
        'Inner inner\n'
        'other_pkg/Point[] points\n'
        'geometry_msgs/msg/Pose pose\n', package='my_pkg')
    assert fields == [
        {'name': 'inner', 'type': 'my_pkg/msg/Inner'},
        {'name': 'points', 'type': 'other_pkg/msg/Point', 'sequence': True},
        {'name': 'pose', 'type': 'geometry_msgs/msg/Pose'},
    ]


def test_constants():
    constants = typedesc.parse_message('pkg', 'T', (
        'int32 MAX=7\n'
        'int64 BIG = -9223372036854775808\n'
        'uint64 HUGE=18446744073709551615\n'
        'bool FLAG=True\n'
        'float64 PI=3.25\n'
        "string GREETING='hello world'  # a comment\n"
        'byte HEX=0x1f\n'))['constants']
    assert constants == [
        {'name': 'MAX', 'type': 'int32', 'value': 7},
        {'name': 'BIG', 'type': 'int64', 'value': '-9223372036854775808'},
        {'name': 'HUGE', 'type': 'uint64', 'value': '18446744073709551615'},
        {'name': 'FLAG', 'type': 'bool', 'value': True},
        {'name': 'PI', 'type': 'float64', 'value': 3.25},
        {'name': 'GREETING', 'type': 'string', 'value': 'hello world'},
        {'name': 'HEX', 'type': 'byte', 'value': 31},
    ]


def test_defaults():
    fields = _fields(
        'int8 a -5\n'
        'float32 b nan\n'
        'float64 c -inf\n'
        'string d "with \\"quotes\\""\n'
        "string e 'single'\n"
        'int32[3] f [1, 2, 3]\n'
        'float64[<=3] g [1.5]\n'
        'string[] h ["a,b", \'c\', d]\n'
        'bool[2] i [true, 0]\n'
        'uint64 j 18446744073709551615\n')
    assert [f['default'] for f in fields] == [
        -5, 'NaN', '-Infinity', 'with "quotes"', 'single', [1, 2, 3], [1.5],
        ['a,b', 'c', 'd'], [True, False], '18446744073709551615']


def test_empty_message_gets_the_member_rosidl_adds():
    description = typedesc.parse_message('pkg', 'Empty', '# nothing\n\nint32 C=1\n')
    assert description['fields'] == [
        {'name': 'structure_needs_at_least_one_member', 'type': 'uint8'}]
    assert description['constants'] == [{'name': 'C', 'type': 'int32', 'value': 1}]


@pytest.mark.parametrize('text,expected', [
    ('int32\n', "'int32' is not a field or constant"),
    ('int33 x\n', "'int33' in type 'int33' is not a valid message name"),
    ('Bad_Name x\n', "'Bad_Name' in type 'Bad_Name' is not a valid message name"),
    ('BadPkg/T x\n', "'BadPkg' in type 'BadPkg/T' is not a valid package name"),
    ('int32 X\n', "'X' is not a valid field name"),
    ('int32 bad__name\n', "'bad__name' is not a valid field name"),
    ('int32 lower=1\n', "'lower' is not a valid constant name"),
    ('int32[0] x\n', 'must be an integer > 0'),
    ('int32[<=x] x\n', 'must be an integer > 0'),
    ('string<=0 x\n', "the bound of string type 'string<=0' must be an integer > 0"),
    ('int32] x\n', "ends with ']' but has no '['"),
    ('uint8 x 256\n', "value '256' is not a valid uint8: use an integer from 0 to 255"),
    ('int8 X=-129\n', "constant X: value '-129' is not a valid int8"),
    ('bool x yes\n', "value 'yes' is not a bool"),
    ('float32 x 1,5\n', "value '1,5' is not a valid float32"),
    ('string<=3 x "long"\n', 'longer than the bound of 3 characters'),
    ('int32[2] x [1]\n', 'array default value has 1 elements, the array has 2'),
    ('int32[<=1] x [1, 2]\n', 'more than the bound 1'),
    ('int32[] x 1\n', "must start with '[' and end with ']'"),
    ('Inner x 1\n', "field of type 'pkg/msg/Inner' cannot have a default value"),
    ('pkg/Point X=1\n', 'constants must have a primitive type'),
    ('time stamp\n', "'time' is a ROS 1 type: use builtin_interfaces/Time"),
    ('int32 x\nint32 x\n', "'x' is defined twice (first on line 2)"),
    ('string s "a"b"\n', 'inner " that is not escaped'),
])
def test_errors_name_the_file_the_line_and_the_problem(text, expected):
    source = Path('/ws/share/pkg/msg/T.msg')
    with pytest.raises(TypeDescriptionError) as info:
        typedesc.parse_message('pkg', 'T', '# header\n' + text, source=source)
    message = str(info.value)
    assert expected in message
    # the error is on the last line; line 1 is the header comment
    line = 1 + text.count('\n')
    assert message.startswith(f'/ws/share/pkg/msg/T.msg:{line}: ')


def test_service_sections_and_line_numbers():
    messages, services = typedesc.describe_service(
        'pkg', 'AddTwoInts', 'int64 a\nint64 b\n---\nint64 sum\n')
    assert services == {'pkg/srv/AddTwoInts': {
        'request': 'pkg/srv/AddTwoInts_Request',
        'response': 'pkg/srv/AddTwoInts_Response',
        'definition': 'int64 a\nint64 b\n---\nint64 sum\n'}}
    assert messages['pkg/srv/AddTwoInts_Request']['definition'] == 'int64 a\nint64 b'
    assert messages['pkg/srv/AddTwoInts_Response']['definition'] == 'int64 sum'
    assert [f['name'] for f in messages['pkg/srv/AddTwoInts_Request']['fields']] == ['a', 'b']
    assert [f['name'] for f in messages['pkg/srv/AddTwoInts_Response']['fields']] == ['sum']

    with pytest.raises(TypeDescriptionError, match=r'^S\.srv:4: .*int99'):
        typedesc.describe_service('pkg', 'S', 'int32 a\n---\n# c\nint99 b\n', source='S.srv')
    with pytest.raises(TypeDescriptionError, match="exactly 1 '---' separator"):
        typedesc.describe_service('pkg', 'S', 'int32 a\n', source='S.srv')


def test_empty_service_request_and_response():
    messages, _ = typedesc.describe_service('pkg', 'Trigger', '---\n')
    for suffix in ('_Request', '_Response'):
        assert messages['pkg/srv/Trigger' + suffix]['fields'] == [
            {'name': 'structure_needs_at_least_one_member', 'type': 'uint8'}]


def test_action_and_the_messages_rosidl_derives():
    messages, actions = typedesc.describe_action(
        'pkg', 'Fib', 'int32 order\n---\nint32[] sequence\n---\nint32[] partial\n')
    full = 'pkg/action/Fib'
    assert actions[full]['send_goal'] == {
        'request': full + '_SendGoal_Request', 'response': full + '_SendGoal_Response'}
    assert actions[full]['feedback_message'] == full + '_FeedbackMessage'
    assert messages[full + '_Goal']['fields'] == [{'name': 'order', 'type': 'int32'}]
    assert messages[full + '_SendGoal_Request']['fields'] == [
        {'name': 'goal_id', 'type': 'unique_identifier_msgs/msg/UUID'},
        {'name': 'goal', 'type': full + '_Goal'}]
    assert messages[full + '_SendGoal_Response']['fields'] == [
        {'name': 'accepted', 'type': 'bool'},
        {'name': 'stamp', 'type': 'builtin_interfaces/msg/Time'}]
    assert messages[full + '_GetResult_Response']['fields'] == [
        {'name': 'status', 'type': 'int8'}, {'name': 'result', 'type': full + '_Result'}]
    assert messages[full + '_FeedbackMessage']['fields'][1] == {
        'name': 'feedback', 'type': full + '_Feedback'}
    assert actions[full]['definition'].startswith('int32 order\n---\n')
    # the derived messages' texts name their fields in order
    for name, message in messages.items():
        lines = [line.split() for line in message['definition'].splitlines()]
        assert [n for _, n in lines] == [f['name'] for f in message['fields']], name
    assert messages[full + '_FeedbackMessage']['definition'] == \
        'unique_identifier_msgs/UUID goal_id\npkg/Fib_Feedback feedback\n'
    with pytest.raises(TypeDescriptionError, match="exactly 2 '---'"):
        typedesc.describe_action('pkg', 'Fib', 'int32 a\n---\n', source='Fib.action')


def test_write_type_descriptions(tmp_path):
    share = tmp_path / 'share' / 'my_msgs'
    (share / 'msg').mkdir(parents=True)
    (share / 'srv').mkdir()
    (share / 'msg' / 'Num.msg').write_text('int64 num\nfloat64 X_NAN=nan\n')
    (share / 'msg' / 'README.txt').write_text('not a definition')
    (share / 'srv' / 'Add.srv').write_text('int64 a\n---\nint64 sum\n')
    path = typedesc.write_type_descriptions(tmp_path, 'my_msgs')
    assert path == share / 'colcon_wasm' / 'types.json'
    text = path.read_text()
    assert 'NaN"' in text  # stored as a string: valid JSON
    document = json.loads(text)
    assert document['schema'] == 1
    assert document['package'] == 'my_msgs'
    assert sorted(document['messages']) == [
        'my_msgs/msg/Num', 'my_msgs/srv/Add_Request', 'my_msgs/srv/Add_Response']
    assert document['actions'] == {}
    assert not list(path.parent.glob('*.tmp'))


def test_write_type_descriptions_without_interfaces(tmp_path):
    (tmp_path / 'share' / 'plain').mkdir(parents=True)
    assert typedesc.write_type_descriptions(tmp_path, 'plain') is None
    assert not (tmp_path / 'share' / 'plain' / 'colcon_wasm').exists()


def test_write_type_descriptions_reports_the_bad_file(tmp_path):
    (tmp_path / 'share' / 'p' / 'msg').mkdir(parents=True)
    bad = tmp_path / 'share' / 'p' / 'msg' / 'Bad.msg'
    bad.write_text('int32 ok\nfloat33 nope\n')
    with pytest.raises(TypeDescriptionError) as info:
        typedesc.write_type_descriptions(tmp_path, 'p')
    assert str(info.value).startswith(f'{bad}:2: field nope:')


# --- against rosidl_adapter's own parser, on every definition in Humble ---

def _humble_archive():
    root = Path(os.environ.get('COLCON_WASM_HUMBLE', REPO.parent / 'shared' / 'humble'))
    archive = root / 'src.tar.xz'
    if not archive.is_file():
        pytest.skip(f'Humble snapshot not found at {root} (set COLCON_WASM_HUMBLE)')
    return archive


@pytest.fixture(scope='module')
def humble_interfaces(tmp_path_factory):
    """Extract rosidl_adapter's parser and every interface definition of Humble."""
    archive = _humble_archive()
    target = tmp_path_factory.mktemp('humble')
    definitions = []
    with tarfile.open(archive) as tar:
        for member in tar:
            parts = member.name.split('/')
            wanted = member.name.endswith('rosidl_adapter/rosidl_adapter/parser.py')
            if len(parts) >= 3 and member.isfile() and parts[-2] in ('msg', 'srv', 'action') \
                    and parts[-1].endswith('.' + parts[-2]):
                wanted = True
                definitions.append(member.name)
            if wanted:
                tar.extract(member, target, filter='data')
    parser_file = next(target.rglob('rosidl_adapter/parser.py'))
    spec = importlib.util.spec_from_file_location('humble_rosidl_parser', parser_file)
    parser = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(parser)
    return parser, [target / name for name in definitions]


def _reference_field(field, package):
    """Describe a rosidl_adapter Field the way types.json does."""
    t = field.type
    if t.is_primitive_type():
        entry = {'type': t.type}
        if t.string_upper_bound:
            entry['string_bound'] = t.string_upper_bound
    else:
        entry = {'type': f'{t.pkg_name}/msg/{t.type}'}
    if t.is_array:
        if t.is_fixed_size_array():
            entry['array_size'] = t.array_size
        else:
            entry['sequence'] = True
            if t.array_size:
                entry['sequence_bound'] = t.array_size
    return dict({'name': field.name}, **entry)


def _reference_value(primitive, value):
    if isinstance(value, list):
        return [_reference_value(primitive, v) for v in value]
    return typedesc._json_number(primitive, value)


def _compare(ours, spec, package):
    fields = [dict(f) for f in ours['fields']]
    reference = [_reference_field(f, package) for f in spec.fields]
    for mine, field in zip(fields, spec.fields):
        default = mine.pop('default', None)
        if field.default_value is None:
            assert default is None
        else:
            assert default == _reference_value(field.type.type, field.default_value)
    if not spec.fields:
        reference = [{'name': typedesc.EMPTY_STRUCTURE_MEMBER, 'type': 'uint8'}]
    assert fields == reference
    assert ours['constants'] == [
        {'name': c.name, 'type': c.type, 'value': _reference_value(c.type, c.value)}
        for c in spec.constants]


def test_every_humble_definition_matches_rosidl_adapter(humble_interfaces, capsys):
    parser, paths = humble_interfaces
    assert len(paths) > 200, 'the snapshot should hold all Humble interfaces'
    for path in paths:
        package, kind, name = path.parent.parent.name, path.parent.name, path.stem
        text = path.read_text(encoding='utf-8')
        if kind == 'msg':
            ours = typedesc.describe_message(package, name, text, source=path)
            _compare(ours[f'{package}/msg/{name}'],
                     parser.parse_message_string(package, name, text), package)
        elif kind == 'srv':
            ours, _ = typedesc.describe_service(package, name, text, source=path)
            spec = parser.parse_service_string(package, name, text)
            _compare(ours[f'{package}/srv/{name}_Request'], spec.request, package)
            _compare(ours[f'{package}/srv/{name}_Response'], spec.response, package)
        else:
            ours, _ = typedesc.describe_action(package, name, text, source=path)
            spec = parser.parse_action_string(package, name, text)
            for part in ('goal', 'result', 'feedback'):
                _compare(ours[f'{package}/action/{name}_{part.capitalize()}'],
                         getattr(spec, part), package)
