# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Humble's core up to rclcpp, built with `colcon build --wasm`.

One build per CI run serves every Humble test: the issue-5 package set of
tests/rclcpp_build.py. It is cached (see tests/humble_build.py); a fresh
machine builds it once. The probe package (tests/fixtures/humble_probe) links rcutils,
rcpputils, rcl_yaml_param_parser and rcl_interfaces' introspection type
support, and runs in Node.js.
"""

import json

from colcon_helpers import node
from humble_build import source_digest
import pytest
from rclcpp_build import rclcpp_build


@pytest.fixture(scope='module')
def build():
    """Get the (cached) Humble build."""
    return rclcpp_build()


def test_packages_built(build):
    for name in ('ament_cmake', 'rcutils', 'rcpputils', 'rmw', 'yaml',
                 'libyaml_vendor', 'rcl_yaml_param_parser',
                 'rosidl_typesupport_introspection_cpp', 'builtin_interfaces',
                 'rcl_interfaces', 'ament_package', 'humble_probe',
                 'rmw_wasm_cpp', 'rmw_implementation', 'rcl', 'rclcpp',
                 'rclcpp_action', 'rclcpp_components', 'rclcpp_lifecycle'):
        assert name in build.packages, name
    # left out: Python bindings, DDS, linters (pure Python)
    for name in ('rosidl_generator_py', 'rclpy', 'rmw_fastrtps_cpp',
                 'rcl_logging_spdlog', 'ament_flake8'):
        assert name not in build.packages, name


def test_probe_runs_in_node(build):
    probe = build.install / 'humble_probe' / 'lib' / 'humble_probe' / \
        'probe.js'
    result = node(probe)
    assert result.returncode == 0, result.stderr[-3000:]
    assert result.stdout.splitlines() == [
        'strerror: No such file or directory',
        'split: 3',
        'yaml: ok 10.5',
        "introspection: ParameterDescriptor has 8 fields, first 'name'",
    ]
    manifest = json.loads(
        (build.install / 'humble_probe' / 'share' / 'humble_probe' /
         'colcon_wasm' / 'manifest.json').read_text())
    assert manifest['package_version'] == '0.1.0'
    assert [e['js'] for e in manifest['executables']] == [
        'lib/humble_probe/probe.js']


def test_rcutils_built_from_patched_copy(build):
    copy = build.build / '.colcon_wasm' / 'source' / 'rcutils'
    assert '!defined(__EMSCRIPTEN__)' in \
        (copy / 'src' / 'strerror.c').read_text()
    assert '__EMSCRIPTEN__' not in \
        (build.workspace / 'src' / 'ros2' / 'rcutils' / 'src' /
         'strerror.c').read_text()


def test_libyaml_vendor_built_offline(build):
    prefix = build.install / 'libyaml_vendor'
    assert (prefix / 'lib' / 'libyaml.a').is_file()
    assert (prefix / 'include' / 'libyaml_vendor' / 'yaml.h').is_file()
    cache = (build.build / 'libyaml_vendor' / 'CMakeCache.txt').read_text()
    assert 'CMAKE_PROJECT_libyaml_vendor_INCLUDE' in cache
    assert not list((build.build / 'libyaml_vendor').glob('libyaml-0.2.5*'))


def test_static_libraries_only(build):
    assert list(build.install.rglob('*.a'))
    assert not list(build.install.rglob('*.so'))


def test_src_untouched(build):
    expected = (build.workspace / 'src_digest.txt').read_text()
    assert source_digest(build.workspace / 'src') == expected
