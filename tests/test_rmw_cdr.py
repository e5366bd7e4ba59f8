# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
rmw_wasm_cpp's CDR, checked in Node.js on the real wasm build.

* Round trips of every message type of common_interfaces, rcl_interfaces,
  test_msgs and example_interfaces (services and actions included), in the C
  and the C++ layout: both layouts give the same bytes, the bytes come back
  unchanged, every strict prefix is refused, malformed and over-bound input
  gets a clear error (tests/rmw/rmw_wasm_cpp_cdr_tests/src/cdr_roundtrip.cpp).
* The golden vectors of tests/data/cdr, produced by real Fast CDR the way
  rmw_fastrtps_cpp drives it, are read and written back byte for byte, and
  decode to the vectors' values.
"""

import json
import math

from colcon_helpers import node
from humble_build import REPO
from humble_build import unpacked_source
import pytest
from rclcpp_build import executable
from rclcpp_build import rclcpp_build

VECTORS = REPO / 'tests' / 'data' / 'cdr'

"""Interface packages whose every message type is round-tripped: (package, folders)."""
ROUND_TRIP_PACKAGES = {
    'action_msgs': ['rcl_interfaces/action_msgs'],
    'builtin_interfaces': ['rcl_interfaces/builtin_interfaces'],
    'composition_interfaces': ['rcl_interfaces/composition_interfaces'],
    'lifecycle_msgs': ['rcl_interfaces/lifecycle_msgs'],
    'rcl_interfaces': ['rcl_interfaces/rcl_interfaces'],
    'rosgraph_msgs': ['rcl_interfaces/rosgraph_msgs'],
    'statistics_msgs': ['rcl_interfaces/statistics_msgs'],
    'test_msgs': ['rcl_interfaces/test_msgs', 'test_interface_files'],
    'actionlib_msgs': ['common_interfaces/actionlib_msgs'],
    'diagnostic_msgs': ['common_interfaces/diagnostic_msgs'],
    'geometry_msgs': ['common_interfaces/geometry_msgs'],
    'nav_msgs': ['common_interfaces/nav_msgs'],
    'sensor_msgs': ['common_interfaces/sensor_msgs'],
    'shape_msgs': ['common_interfaces/shape_msgs'],
    'std_msgs': ['common_interfaces/std_msgs'],
    'std_srvs': ['common_interfaces/std_srvs'],
    'stereo_msgs': ['common_interfaces/stereo_msgs'],
    'trajectory_msgs': ['common_interfaces/trajectory_msgs'],
    'visualization_msgs': ['common_interfaces/visualization_msgs'],
    'unique_identifier_msgs': ['unique_identifier_msgs'],
    'example_interfaces': ['example_interfaces'],
}

ACTION_PARTS = ('Goal', 'Result', 'Feedback', 'FeedbackMessage', 'SendGoal_Request',
                'SendGoal_Response', 'GetResult_Request', 'GetResult_Response')


@pytest.fixture(scope='module')
def build():
    """Get the (cached) Humble build up to rclcpp with the rmw test packages."""
    return rclcpp_build()


def expected_types():
    """Every message type of the round-trip packages, from their source interface files."""
    source = unpacked_source() / 'ros2'
    names = set()
    for package, folders in ROUND_TRIP_PACKAGES.items():
        for folder in folders:
            for path in (source / folder).glob('msg/*.msg'):
                names.add(f'{package}/msg/{path.stem}')
            for path in (source / folder).glob('srv/*.srv'):
                names.update(f'{package}/srv/{path.stem}_{p}' for p in ('Request', 'Response'))
            for path in (source / folder).glob('action/*.action'):
                names.update(f'{package}/action/{path.stem}_{p}' for p in ACTION_PARTS)
    return names


def test_round_trip_of_every_message_type(build):
    result = node(executable(build, 'rmw_wasm_cpp_cdr_tests', 'cdr_roundtrip'), timeout=300)
    lines = result.stdout.splitlines()
    failures = [line for line in lines if line.startswith('FAIL')]
    assert not failures, '\n'.join(failures)
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    passed = {line.split()[1] for line in lines if line.startswith('PASS ') and '/' in line}
    missing = expected_types() - passed
    assert not missing, f'message types not round-tripped: {sorted(missing)}'
    for check in ('malformed/count over bound', 'malformed/huge count',
                  'malformed/string longer than the stream', 'malformed/not plain CDR',
                  'malformed/no header', 'overbound/int32_values',
                  'overbound/bounded_string_value', 'malformed/big endian read'):
        assert f'PASS {check}' in lines, check
    assert lines[-1].startswith('SUMMARY') and lines[-1].endswith(' 0 failures')


def golden_vectors():
    """Every vector of tests/data/cdr/*.json."""
    vectors = []
    for path in sorted(VECTORS.glob('*.json')):
        vectors += json.loads(path.read_text(encoding='utf-8'))['vectors']
    return vectors


def same_value(expected, got, path='value'):
    """Compare a vector value with a decoded one (floats to float32 precision)."""
    if isinstance(expected, dict):
        assert isinstance(got, dict) and list(expected) == list(got), f'{path}: {got!r}'
        for key in expected:
            same_value(expected[key], got[key], f'{path}.{key}')
    elif isinstance(expected, list):
        assert isinstance(got, list) and len(expected) == len(got), f'{path}: {got!r}'
        for index, (e, g) in enumerate(zip(expected, got)):
            same_value(e, g, f'{path}[{index}]')
    elif isinstance(expected, float) or isinstance(got, float):
        assert math.isclose(float(expected), float(got), rel_tol=1e-7, abs_tol=1e-38), \
            f'{path}: expected {expected!r}, got {got!r}'
    else:
        assert expected == got, f'{path}: expected {expected!r}, got {got!r}'


def test_fast_cdr_golden_vectors(build):
    vectors = golden_vectors()
    if not vectors:
        pytest.skip(f'no golden vectors in {VECTORS}')
    result = node(
        executable(build, 'rmw_wasm_cpp_cdr_tests', 'cdr_golden'),
        *[f"{v['type']}={v['hex']}" for v in vectors], timeout=120)
    lines = result.stdout.splitlines()
    assert len(lines) == len(vectors), result.stdout + result.stderr
    for vector, line in zip(vectors, lines):
        assert line.startswith('OK '), f"{vector['name']}: {line}"
        same_value(vector['value'], json.loads(line.split(' ', 2)[2]))
    assert result.returncode == 0


def test_golden_vectors_cover_the_fast_cdr_rules():
    """The vectors exercise each rule the issue names (alignment, strings, wstrings, ...)."""
    vectors = golden_vectors()
    if not vectors:
        pytest.skip(f'no golden vectors in {VECTORS}')
    types = {v['type'].split('/')[-1] for v in vectors}
    assert {'Primitives', 'Arrays', 'Sequences', 'BoundedSequences', 'Strings',
            'Nested', 'Empty', 'Defaults'} <= types
    assert any(v['type'].endswith('_Request') for v in vectors)
    assert all(v['hex'].startswith('00010000') for v in vectors)
