# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The numbers wasm_cpp and wasm_js share agree.

The C++ side (packages/wasm_cpp headers, qos_to_wire, Event::take) and the
JS side (packages/wasm_js/src/abi/bus_abi.mjs, and the tables of
src/abi/library_wasm_bus.js) write the same status codes, kinds, modes,
event types, QoS words and struct layouts. The checks parse the C++ text,
import the JS module with Node.js, and name each number that differs. The
last tests run the same checks on deliberately altered copies, to show that
they fail.
"""

import json
from pathlib import Path
import re
import shutil
import subprocess

import pytest

REPO = Path(__file__).resolve().parents[1]
CPP = REPO / 'packages' / 'wasm_cpp'
ABI_JS = REPO / 'packages' / 'wasm_js' / 'src' / 'abi' / 'bus_abi.mjs'
LIBRARY_JS = REPO / 'packages' / 'wasm_js' / 'src' / 'abi' / 'library_wasm_bus.js'

# C++ sources, by the short name the checks use
CPP_FILES = {
    'bus_abi.hpp': CPP / 'src' / 'bus_abi.hpp',
    'bus_abi.cpp': CPP / 'src' / 'bus_abi.cpp',
    'events.cpp': CPP / 'src' / 'events.cpp',
    'status.hpp': CPP / 'include' / 'wasm_cpp' / 'status.hpp',
    'graph.hpp': CPP / 'include' / 'wasm_cpp' / 'graph.hpp',
    'events.hpp': CPP / 'include' / 'wasm_cpp' / 'events.hpp',
    'wait_set.hpp': CPP / 'include' / 'wasm_cpp' / 'wait_set.hpp',
    'qos.hpp': CPP / 'include' / 'wasm_cpp' / 'qos.hpp',
}

# (JS table, C++ file, C++ enum, prefix of the C++ names, C++-only names)
ENUMS = [
    ('Code', 'status.hpp', 'Code', '', ()),
    ('EndpointKind', 'graph.hpp', 'EndpointKind', '', ()),
    ('EndpointKind', 'bus_abi.hpp', 'BusKind', 'Bus', ()),
    ('TakeMode', 'bus_abi.hpp', 'BusTakeMode', 'Take', ()),
    ('WaitKind', 'wait_set.hpp', 'Kind', '', ()),
    ('EventType', 'events.hpp', 'EventType', '', ('INVALID',)),
    ('History', 'qos.hpp', 'History', '', ('UNKNOWN',)),
    ('Reliability', 'qos.hpp', 'Reliability', '', ('UNKNOWN',)),
    ('Durability', 'qos.hpp', 'Durability', '', ('UNKNOWN',)),
    ('Liveliness', 'qos.hpp', 'Liveliness', '', ('UNKNOWN',)),
    ('PolicyKind', 'qos.hpp', 'QosPolicyKind', '', ('AVOID_ROS_NAMESPACE_CONVENTIONS',)),
]

# QoS fields of qos_to_wire -> the JS QOS word of their first word
QOS_FIELDS = {
    'history': 'HISTORY', 'depth': 'DEPTH', 'reliability': 'RELIABILITY',
    'durability': 'DURABILITY', 'liveliness': 'LIVELINESS',
    'avoid_ros_namespace_conventions': 'FLAGS', 'deadline': 'DEADLINE_LO',
    'lifespan': 'LIFESPAN_LO', 'liveliness_lease_duration': 'LEASE_LO',
}

# wasm_cpp::EventStatus fields Event::take reads -> EVENT_STATUS words
EVENT_FIELDS = {
    'total_count': 'TOTAL', 'total_count_change': 'CHANGE', 'alive_count': 'ALIVE',
    'not_alive_count': 'NOT_ALIVE', 'alive_count_change': 'ALIVE_CHANGE',
    'not_alive_count_change': 'NOT_ALIVE_CHANGE', 'last_policy_kind': 'POLICY',
}

C_SIZES = {'double': 8, 'int64_t': 8, 'uint64_t': 8, 'int32_t': 4, 'uint32_t': 4, 'float': 4}


def strip_comments(text):
    """Remove C++ comments."""
    return re.sub(r'//[^\n]*|/\*.*?\*/', '', text, flags=re.DOTALL)


def upper_snake(camel):
    """Turn ``LivelinessChanged`` into ``LIVELINESS_CHANGED``."""
    return re.sub(r'(?<=[a-z0-9])(?=[A-Z])', '_', camel).upper()


def int_value(expression, where):
    """Evaluate an enum value: a number or ``1 << n``."""
    m = re.fullmatch(r'\s*(\d+)\s*(?:<<\s*(\d+))?\s*', expression)
    if not m:
        raise ValueError(f'{where}: cannot read the value {expression!r}')
    return int(m.group(1)) << int(m.group(2) or 0)


def cpp_enum(text, name, prefix, where):
    """Read ``enum [class] name : type {kX = n, ...}`` as {'X': n} (prefix dropped)."""
    m = re.search(r'enum\s+(?:class\s+)?' + name + r'\s*:\s*\w+\s*\{(.*?)\}', strip_comments(text),
                  re.DOTALL)
    if not m:
        raise ValueError(f'{where}: enum {name} not found')
    values = {}
    for entry in m.group(1).split(','):
        if not entry.strip():
            continue
        key, _, value = entry.partition('=')
        key = key.strip()
        if not key.startswith('k' + prefix):
            raise ValueError(f'{where}: enum {name}: {key} does not start with k{prefix}')
        values[upper_snake(key[1 + len(prefix):])] = int_value(value, f'{where}: {name}::{key}')
    return values


def cpp_take_info(text, where):
    """Get the word offsets of struct wasm_bus_take_info (doubles: NAME_F64) and WORDS."""
    m = re.search(r'struct\s+wasm_bus_take_info\s*\{(.*?)\};', strip_comments(text), re.DOTALL)
    if not m:
        raise ValueError(f'{where}: struct wasm_bus_take_info not found')
    offset = 0
    words = {}
    for field in m.group(1).split(';'):
        field = field.strip()
        if not field:
            continue
        fm = re.fullmatch(r'(\w+)\s+(\w+)(?:\[(\d+)\])?', field)
        if not fm or fm.group(1) not in C_SIZES:
            raise ValueError(f'{where}: wasm_bus_take_info: cannot read the field {field!r}')
        size = C_SIZES[fm.group(1)]
        offset = (offset + size - 1) // size * size
        key = fm.group(2).upper() + ('_F64' if fm.group(1) == 'double' else '')
        words[key] = offset // 4
        offset += size * int(fm.group(3) or 1)
    words['WORDS'] = (offset + 7) // 8 * 8 // 4
    return words


def cpp_qos_words(text, where):
    """Get the first wire word of each QoS field that qos_to_wire writes."""
    m = re.search(r'void\s+qos_to_wire\s*\([^)]*\)\s*\{(.*?)\n\}', text, re.DOTALL)
    if not m:
        raise ValueError(f'{where}: qos_to_wire not found')
    words = {}
    for index, field in re.findall(r'w\[(\d+)\]\s*(?:=|,)[^;]*?\bqos\.(\w+)', m.group(1)):
        if field not in QOS_FIELDS:
            raise ValueError(f'{where}: qos_to_wire writes an unknown field qos.{field}')
        words[QOS_FIELDS[field]] = int(index)
    return words


def cpp_event_status(text, where):
    """Get the status words Event::take reads, and WORDS."""
    m = re.search(r'Status\s+Event::take\s*\(.*?\n\}', text, re.DOTALL)
    if not m:
        raise ValueError(f'{where}: Event::take not found')
    body = m.group(0)
    words = {}
    for field, index in re.findall(r'status->(\w+)\s*=\s*(?:[^;]*?\b)?s\[(\d+)\]', body):
        words[EVENT_FIELDS.get(field, field)] = int(index)
    taken = re.search(r'\*taken\s*=\s*s\[(\d+)\]', body)
    size = re.search(r'int32_t\s+s\[(\d+)\]', body)
    if not taken or not size:
        raise ValueError(f'{where}: Event::take: the changed flag or the status size not found')
    words['CHANGED'] = int(taken.group(1))
    words['WORDS'] = int(size.group(1))
    return words


def js_tables(module=ABI_JS):
    """Import the JS ABI module with Node.js and return its exports."""
    node = shutil.which('node')
    assert node, 'Node.js 20 is needed (apt-get install nodejs)'
    script = ('import(process.argv[1]).then((m) => '
              'process.stdout.write(JSON.stringify(m)))')
    result = subprocess.run(
        [node, '--input-type=module', '-e', script, Path(module).as_uri()],
        capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, f'cannot import {module}: {result.stderr[-2000:]}'
    return json.loads(result.stdout)


def library_table(text, name):
    """Read the ``NAME: {KEY: n, ...}`` table of library_wasm_bus.js' $WasmBus."""
    m = re.search(r'\b' + name + r'\s*:\s*\{([^}]*)\}', text)
    if not m:
        raise ValueError(f'library_wasm_bus.js: the table {name} not found')
    return {k: int(v) for k, v in re.findall(r'(\w+)\s*:\s*(\d+)', m.group(1))}


def compare(table, cpp, cpp_where, js, js_where, cpp_only=()):
    """List the differences of one table between C++ and JS."""
    problems = []
    for key in sorted(set(cpp) | set(js)):
        if key in cpp_only and key not in js:
            continue
        c, j = cpp.get(key), js.get(key)
        if c != j:
            problems.append(f'{table}.{key}: {cpp_where} says {c}, {js_where} says {j}')
    return problems


def abi_mismatches(cpp_texts, js, library_text):
    """
    List every number that C++ and JS do not agree on, as readable lines.

    :param cpp_texts: short file name (CPP_FILES) -> text
    :param js: the exports of src/abi/bus_abi.mjs
    :param library_text: the text of library_wasm_bus.js
    """
    problems = []
    for table, file, enum, prefix, cpp_only in ENUMS:
        cpp = cpp_enum(cpp_texts[file], enum, prefix, file)
        problems += compare(table, cpp, f'{file} ({enum})', js[table], 'bus_abi.mjs', cpp_only)
    qos = cpp_qos_words(cpp_texts['bus_abi.cpp'], 'bus_abi.cpp')
    qos['WORDS'] = int(re.search(r'kQosWords\s*=\s*(\d+)', cpp_texts['bus_abi.hpp']).group(1))
    js_qos = {k: v for k, v in js['QOS'].items() if not k.endswith('_HI')}
    problems += compare('QOS', qos, 'qos_to_wire/kQosWords', js_qos, 'bus_abi.mjs')
    for lo, hi in (('DEADLINE_LO', 'DEADLINE_HI'), ('LIFESPAN_LO', 'LIFESPAN_HI'),
                   ('LEASE_LO', 'LEASE_HI')):
        if js['QOS'][hi] != js['QOS'][lo] + 1:
            problems.append(f'QOS.{hi}: bus_abi.mjs says {js["QOS"][hi]}, '
                            f'a duration takes QOS.{lo} + 1 = {js["QOS"][lo] + 1}')
    take_info = cpp_take_info(cpp_texts['bus_abi.hpp'], 'bus_abi.hpp')
    problems += compare('TAKE_INFO', take_info, 'bus_abi.hpp (wasm_bus_take_info)',
                        js['TAKE_INFO'], 'bus_abi.mjs')
    problems += compare('TAKE_INFO', take_info, 'bus_abi.hpp (wasm_bus_take_info)',
                        library_table(library_text, 'TAKE_INFO'), 'library_wasm_bus.js')
    status = cpp_event_status(cpp_texts['events.cpp'], 'events.cpp')
    problems += compare('EVENT_STATUS', status, 'events.cpp (Event::take)',
                        js['EVENT_STATUS'], 'bus_abi.mjs')
    problems += compare('EVENT_STATUS', status, 'events.cpp (Event::take)',
                        library_table(library_text, 'EVENT_STATUS'), 'library_wasm_bus.js')
    return problems


@pytest.fixture(scope='module')
def sources():
    """Read the C++ texts, the JS module's exports and the library text."""
    cpp = {name: path.read_text(encoding='utf-8') for name, path in CPP_FILES.items()}
    return cpp, js_tables(), LIBRARY_JS.read_text(encoding='utf-8')


def test_cpp_and_js_agree(sources):
    cpp, js, library = sources
    problems = abi_mismatches(cpp, js, library)
    assert not problems, (
        'wasm_cpp and wasm_js disagree on the bus ABI; change both sides together:\n  '
        + '\n  '.join(problems))


def test_every_table_is_read(sources):
    cpp, js, library = sources
    # the parsers found what they compare (an empty parse would agree with nothing)
    assert cpp_enum(cpp['events.hpp'], 'EventType', '', 'events.hpp')['MESSAGE_LOST'] == 3
    assert len(cpp_qos_words(cpp['bus_abi.cpp'], 'bus_abi.cpp')) == len(QOS_FIELDS)
    assert cpp_take_info(cpp['bus_abi.hpp'], 'bus_abi.hpp')['WORDS'] == js['TAKE_INFO']['WORDS']
    status = cpp_event_status(cpp['events.cpp'], 'events.cpp')
    assert len(status) == js['EVENT_STATUS']['WORDS'] + 1
    assert library_table(library, 'TAKE_INFO') == js['TAKE_INFO']


@pytest.mark.parametrize('file,old,new,expected', [
    ('bus_abi.hpp', 'kTakeResponse = 2', 'kTakeResponse = 3', 'TakeMode.RESPONSE'),
    ('events.hpp', 'kMessageLost = 3', 'kMessageLost = 9', 'EventType.MESSAGE_LOST'),
    ('status.hpp', 'kTimeout = 2', 'kTimeout = 4', 'Code.TIMEOUT'),
    ('wait_set.hpp', 'kEvent = 4', 'kEvent = 5', 'WaitKind.EVENT'),
    ('qos.hpp', 'kKeepAll = 2', 'kKeepAll = 7', 'History.KEEP_ALL'),
    ('qos.hpp', 'kDepth = 1 << 7', 'kDepth = 1 << 6', 'PolicyKind.DEPTH'),
    ('bus_abi.cpp', 'w[4] = static_cast<int32_t>(qos.liveliness)',
     'w[5] = static_cast<int32_t>(qos.liveliness)', 'QOS.LIVELINESS'),
    ('bus_abi.hpp', '  uint32_t pub_seq_lo;\n', '  uint32_t pub_seq_lo;\n  uint32_t extra;\n',
     'TAKE_INFO.PUB_SEQ_HI'),
    ('events.cpp', 'status->alive_count = s[3];', 'status->alive_count = s[4];',
     'EVENT_STATUS.ALIVE'),
])
def test_an_altered_cpp_copy_fails(sources, file, old, new, expected):
    cpp, js, library = sources
    assert old in cpp[file], f'{file} no longer contains {old!r}: update this test'
    altered = dict(cpp, **{file: cpp[file].replace(old, new, 1)})
    problems = abi_mismatches(altered, js, library)
    assert any(p.startswith(expected + ':') for p in problems), problems


def test_an_altered_js_copy_fails(sources, tmp_path):
    cpp, _, library = sources
    copy = tmp_path / 'bus_abi.mjs'
    text = ABI_JS.read_text(encoding='utf-8')
    assert 'CLIENT: 4' in text
    copy.write_text(text.replace('CLIENT: 4', 'CLIENT: 5', 1), encoding='utf-8')
    problems = abi_mismatches(cpp, js_tables(copy), library)
    assert any(p.startswith('EndpointKind.CLIENT:') for p in problems), problems


def test_an_altered_library_copy_fails(sources):
    cpp, js, library = sources
    assert 'LENGTH: 15' in library
    problems = abi_mismatches(cpp, js, library.replace('LENGTH: 15', 'LENGTH: 16', 1))
    assert problems == ['TAKE_INFO.LENGTH: bus_abi.hpp (wasm_bus_take_info) says 15, '
                        'library_wasm_bus.js says 16'], problems
