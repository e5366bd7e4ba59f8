# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
Composition without dlopen (docs/composition.md), in Node.js and Chromium.

tests/rmw/rmw_wasm_cpp_node_tests registers two components (Talker and
Listener) from a static library, generates `talker_component` with
rclcpp_components_register_node(... EXECUTABLE ...), and builds
`static_container`, a component container hosting them, with
rclcpp_components_static_container(). The ros2/examples composition and
wait_set_subscriber executables are covered by tests/test_humble_examples.py.
"""

import json

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


def load(platform, name, package, plugin):
    """Get a step that asks the container to load a component."""
    return {'spawn': name, 'exe': platform.exe(TESTS, 'probe'),
            'args': ['load_component', '/ComponentManager', package, plugin]}


def test_register_node_executable(platform):
    report = platform.run([
        {'spawn': 'talker', 'exe': platform.exe(TESTS, 'talker_component'),
         'args': ['--ros-args', '-r', '__node:=renamed_talker']},
        {'spawn': 'listener', 'exe': platform.exe(TESTS, 'probe'), 'args': ['listener']},
        {'wait': 'listener', 'text': 'HEARD component says ', 'count': 3},
        {'graph': 'running'},
    ])
    assert report['ok'], explain(report)
    # the generated main() passes --ros-args to the component
    assert 'renamed_talker' in [n['name'] for n in report['graphs']['running']['nodes']]


def test_static_container_loads_components_through_its_service(platform):
    report = platform.run([
        {'spawn': 'container', 'exe': platform.exe(TESTS, 'static_container')},
        {'graphWait': {'node': '/ComponentManager', 'present': True}},
        load(platform, 'load_talker', TESTS, 'rmw_wasm_cpp_node_tests::Talker'),
        {'exit': 'load_talker'},
        load(platform, 'load_listener', TESTS, 'rmw_wasm_cpp_node_tests::Listener'),
        {'exit': 'load_listener'},
        {'wait': 'container', 'text': 'component heard: component says ', 'count': 3},
        {'graph': 'loaded'},
    ])
    assert report['ok'], explain(report)
    assert 'LOADED /component_talker id 1' in ' '.join(lines(report, 'load_talker'))
    assert 'LOADED /component_listener id 2' in ' '.join(lines(report, 'load_listener'))
    nodes = {n['name'] for n in report['graphs']['loaded']['nodes']}
    assert {'ComponentManager', 'component_talker', 'component_listener'} <= nodes
    services = {s['name'] for s in report['graphs']['loaded']['services']}
    assert {'/ComponentManager/_container/load_node', '/ComponentManager/_container/list_nodes',
            '/ComponentManager/_container/unload_node'} <= services


def test_static_container_refuses_components_not_linked_in(platform):
    report = platform.run([
        {'spawn': 'container', 'exe': platform.exe(TESTS, 'static_container')},
        {'graphWait': {'node': '/ComponentManager', 'present': True}},
        load(platform, 'load', 'composition', 'composition::Talker'),
        {'exit': 'load'},
    ])
    assert report['ok'], explain(report)
    failure = ' '.join(lines(report, 'load'))
    assert "LOAD FAILED no component of package 'composition' is linked into this container" \
        in failure, json.dumps(report['logs'][-5:])
    assert f'{TESTS}/rmw_wasm_cpp_node_tests::Talker' in failure
