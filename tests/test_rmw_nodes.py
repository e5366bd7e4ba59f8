# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
rclcpp nodes on rmw_wasm_cpp: arguments, environment, time, threads, bad input.

The nodes are the scenarios of tests/rmw/rmw_wasm_cpp_node_tests (one
`probe` executable, `probe <scenario> [--ros-args ...]`) and the
ros2/examples talker, built by `colcon build --wasm` (tests/rclcpp_build.py).
Each test runs in Node.js and in headless Chromium.
"""

import re

import pytest
from rclcpp_build import rclcpp_build
from rmw_scenario import explain
from rmw_scenario import lines
from rmw_scenario import Platform

TESTS = 'rmw_wasm_cpp_node_tests'


@pytest.fixture(scope='module')
def build():
    """Get the (cached) Humble build up to rclcpp with the rmw test packages."""
    return rclcpp_build()


@pytest.fixture(params=['node', 'chromium'])
def platform(request, build):
    """Run on Node.js and on Chromium."""
    return Platform(request.param, build)


def probe(platform, name, scenario, *args, env=None, **extra):
    """Get a spawn step of `probe <scenario> <args...>`."""
    step = {'spawn': name, 'exe': platform.exe(TESTS, 'probe'),
            'args': [scenario, *args], 'env': env or {}}
    step.update(extra)
    return step


def run(platform, steps, **kwargs):
    """Run a scenario and assert it completed."""
    report = platform.run(steps, **kwargs)
    assert report['ok'], explain(report)
    return report


def test_parameter_from_command_line_read_through_parameter_services(platform):
    report = run(platform, [
        probe(platform, 'talker', 'param_talker',
              '--ros-args', '-p', 'greeting:=bonjour', '-p', 'period_ms:=50'),
        {'wait': 'talker', 'text': 'NAME /param_talker'},
        probe(platform, 'reader', 'param_reader', 'param_talker', 'greeting'),
        {'wait': 'reader', 'text': 'PARAM greeting=', 'timeout': 30},
        probe(platform, 'listener', 'listener'),
        {'wait': 'listener', 'text': 'HEARD bonjour ', 'count': 2},
    ])
    assert 'PARAM greeting=bonjour' in lines(report, 'reader')[-1]


def test_parameter_file(platform):
    params = 'param_talker:\n  ros__parameters:\n    greeting: "from a file"\n'
    report = run(platform, [
        probe(platform, 'talker', 'param_talker', '--ros-args', '--params-file', '/params.yaml',
              files={'/params.yaml': params}),
        probe(platform, 'listener', 'listener'),
        {'wait': 'listener', 'text': 'HEARD from a file ', 'count': 2},
    ])
    assert report['ok']


def test_remaps_node_name_and_namespace(platform):
    report = run(platform, [
        probe(platform, 'talker', 'param_talker', '--ros-args', '-r', '__node:=speaker',
              '-r', '__ns:=/robot', '-r', 'chatter:=news'),
        {'wait': 'talker', 'text': 'NAME '},
        probe(platform, 'listener', 'listener', '--ros-args', '-r', '__ns:=/robot',
              '-r', 'chatter:=news'),
        {'wait': 'listener', 'text': 'HEARD hello ', 'count': 2},
        {'graph': 'running'},
    ])
    assert 'NAME /robot/speaker TOPIC /robot/news' in lines(report, 'talker')[-1]
    graph = report['graphs']['running']
    assert any(n['namespace'] == '/robot' and n['name'] == 'speaker' for n in graph['nodes'])
    topic = next(t for t in graph['topics'] if t['name'] == '/robot/news')
    assert topic['types'] == ['std_msgs/msg/String']
    assert [p['node'] for p in topic['publishers']] == ['speaker']


def test_ros_namespace_environment(platform):
    report = run(platform, [
        probe(platform, 'talker', 'param_talker', env={'ROS_NAMESPACE': '/fleet/robot1'}),
        {'wait': 'talker', 'text': 'NAME '},
    ])
    assert 'NAME /fleet/robot1/param_talker TOPIC /fleet/robot1/chatter' in \
        lines(report, 'talker')[-1]


def test_domains_are_isolated(platform):
    report = run(platform, [
        probe(platform, 'talker', 'param_talker', env={'ROS_DOMAIN_ID': '5'}),
        {'wait': 'talker', 'text': 'DOMAIN 5'},
        probe(platform, 'other', 'listener', env={'ROS_DOMAIN_ID': '6'}),
        probe(platform, 'same', 'listener', env={'ROS_DOMAIN_ID': '5'}),
        {'wait': 'same', 'text': 'HEARD hello ', 'count': 3},
        {'quiet': 'other', 'text': 'HEARD', 'seconds': 1},
        {'graph': 'both'},
    ])
    domains = {n['name']: n['domain'] for n in report['graphs']['both']['nodes']}
    assert domains['param_talker'] == 5
    assert sorted(n['domain'] for n in report['graphs']['both']['nodes']
                  if n['name'] == 'probe_listener') == [5, 6]


@pytest.mark.parametrize('level,present,absent', [
    ('warn', ['warn line', 'error line'], ['info line', 'debug line']),
    ('debug', ['debug line', 'info line', 'warn line', 'error line'], []),
])
def test_log_levels_and_severities(platform, level, present, absent):
    report = run(platform, [
        probe(platform, 'talker', 'param_talker', '--ros-args', '--log-level', level),
        {'wait': 'talker', 'text': 'error line'},
    ])
    texts = lines(report, 'talker')
    for text in present:
        assert any(t.endswith(text) for t in texts), (text, texts)
    for text in absent:
        assert not any(t.endswith(text) for t in texts), (text, texts)
    severities = {e['text'].rsplit(': ', 1)[-1]: e['severity']
                  for e in report['logs'] if e['name'] == 'talker'}
    for text in present:
        assert severities[text] == text.split()[0].upper()


def test_sim_time_from_clock(platform):
    report = run(platform, [
        probe(platform, 'clock', 'clock', '1000'),
        probe(platform, 'node', 'sim_time', '--ros-args', '-p', 'use_sim_time:=true'),
        {'exit': 'node', 'timeout': 30},
    ])
    assert 'USE_SIM_TIME true' in ' '.join(lines(report, 'node'))
    sim = [float(m.group(1)) for t in lines(report, 'node')
           for m in [re.search(r'SIM_TIME ([\d.]+)', t)] if m]
    assert sim and 1000.0 <= sim[0] < 1100.0, sim


def test_spin_sleeps_without_burning_cpu(platform):
    """Idle executors (single and multi-threaded) sleep in rmw_wait: no busy polling."""
    report = run(platform, [
        probe(platform, 'single', 'listener'),
        probe(platform, 'multi', 'mt_listener'),
        {'wait': 'multi', 'text': 'SPINNING with 4 threads'},
        {'graphWait': {'node': '/probe_listener', 'present': True}},
        {'cpu': 'idle', 'seconds': 2},
        probe(platform, 'talker', 'param_talker'),
        {'wait': 'multi', 'text': 'HEARD hello ', 'count': 3},
        {'wait': 'single', 'text': 'HEARD hello ', 'count': 3},
    ])
    if platform.name == 'node':
        # two idle nodes (5 threads spinning) use a few percent of one core at most
        assert report['cpu']['idle'] < 0.1, report['cpu']


def test_topic_with_another_type(platform):
    report = run(platform, [
        {'spawn': 'talker', 'exe': platform.exe(
            'examples_rclcpp_minimal_publisher', 'publisher_member_function')},
        {'wait': 'talker', 'text': 'Publishing', 'count': 2},
        probe(platform, 'clash', 'wrong_type', 'topic'),
        {'exit': 'clash', 'timeout': 30},
    ])
    texts = lines(report, 'clash')
    warning = [t for t in lines(report, 'clash', 'WARN') if 'will not match' in t]
    assert warning and "topic '/topic' already has endpoints of type 'std_msgs/msg/String'" \
        in warning[0] and "'std_msgs/msg/Int32'" in warning[0], texts
    assert any('TYPES /topic: std_msgs/msg/Int32, std_msgs/msg/String' in t for t in texts)
    assert any('RECEIVED 0 MATCHED 0' in t for t in texts)


def test_service_call_without_server(platform):
    report = run(platform, [probe(platform, 'client', 'no_server'), {'exit': 'client'}])
    texts = ' '.join(lines(report, 'client'))
    assert 'SERVICE READY no' in texts
    match = re.search(r'RESULT TIMEOUT after (\d+) ms; future pending yes', texts)
    assert match, texts
    assert 450 <= int(match.group(1)) <= 2000
    assert report['exits']['client']['code'] == 0


def test_same_node_name_twice(platform):
    report = run(platform, [
        probe(platform, 'first', 'param_talker'),
        {'wait': 'first', 'text': 'NAME /param_talker'},
        probe(platform, 'second', 'param_talker'),
        {'wait': 'second', 'text': 'NAME /param_talker'},
    ])
    warnings = [t for t in lines(report, 'second', 'WARN') if 'already exists' in t]
    assert warnings and "a node named '/param_talker' already exists in domain 0" in warnings[0]
    assert not [t for t in lines(report, 'first', 'WARN') if 'already exists' in t]


def test_invalid_topic_name(platform):
    report = run(platform, [probe(platform, 'node', 'invalid_topic'), {'exit': 'node'}])
    refused = [t for t in lines(report, 'node') if 'REFUSED' in t]
    assert refused and 'bad topic name!' in refused[0] and 'invalid' in refused[0].lower()
    assert report['exits']['node']['code'] == 0


def test_message_over_the_maximum(platform):
    report = run(platform, [
        probe(platform, 'node', 'oversize', str(2 << 20)),
        probe(platform, 'listener', 'listener', '--ros-args', '-r', 'chatter:=big'),
        {'exit': 'node'},
    ], runtime={'maxMessageBytes': 1 << 20})
    texts = ' '.join(lines(report, 'node'))
    assert re.search(r"REFUSED .*cannot publish on '/big': the serialized std_msgs/msg/String "
                     r'is 2097161 bytes, over the bus maximum of 1048576 bytes', texts), texts
    assert 'SMALL PUBLISH OK' in texts


def test_worker_dies_holding_a_client_request(platform):
    report = run(platform, [
        probe(platform, 'holder', 'hold_server'),
        probe(platform, 'caller', 'caller'),
        {'wait': 'holder', 'text': 'HOLDING request'},
        {'stop': 'holder'},
        {'graphWait': {'node': '/hold_server', 'present': False}},
        {'wait': 'caller', 'text': 'SERVER GONE with the request'},
        probe(platform, 'adder', 'add_server'),
        {'wait': 'caller', 'text': 'RESULT 5', 'timeout': 30},
        {'exit': 'caller'},
    ])
    texts = lines(report, 'caller')
    assert sum('SENT request' in t for t in texts) == 2
    assert 'pruned 1 pending' in ' '.join(texts)
    assert report['exits']['holder']['reason'] == 'stopped'
    assert report['exits']['caller']['code'] == 0
