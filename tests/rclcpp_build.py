# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
Humble up to rclcpp and its examples, built once by `colcon build --wasm`.

The package set of issue 5: everything up to rclcpp, rclcpp_action,
rclcpp_components and rclcpp_lifecycle, every rclcpp package of
ros2/examples, and the rmw_wasm_cpp test packages of tests/rmw (plus the
cdr_test_msgs types of the Fast CDR golden vectors). The build is cached by
tests/humble_build.py under ``$COLCON_WASM_CACHE``, keyed by its inputs; a
fresh machine builds it once.

    from rclcpp_build import rclcpp_build
    build = rclcpp_build()      # skips when the Humble snapshot is absent
"""

import os
from pathlib import Path

from humble_build import humble_build
from humble_build import refresh_runtime
from humble_build import REPO

"""The rclcpp packages of ros2/examples (all of them)."""
EXAMPLES = (
    'examples_rclcpp_async_client',
    'examples_rclcpp_cbg_executor',
    'examples_rclcpp_minimal_action_client',
    'examples_rclcpp_minimal_action_server',
    'examples_rclcpp_minimal_client',
    'examples_rclcpp_minimal_composition',
    'examples_rclcpp_minimal_publisher',
    'examples_rclcpp_minimal_service',
    'examples_rclcpp_minimal_subscriber',
    'examples_rclcpp_minimal_timer',
    'examples_rclcpp_multithreaded_executor',
    'examples_rclcpp_wait_set',
)

"""Test packages of rmw_wasm_cpp (name: folder), added to the workspace."""
TEST_PACKAGES = {
    'rmw_wasm_cpp_cdr_tests': REPO / 'tests' / 'rmw' / 'rmw_wasm_cpp_cdr_tests',
    'rmw_wasm_cpp_node_tests': REPO / 'tests' / 'rmw' / 'rmw_wasm_cpp_node_tests',
    'cdr_test_msgs': REPO / 'tests' / 'data' / 'cdr' / 'cdr_test_msgs',
    # the toolchain probe of tests/test_humble.py (rcutils, rcpputils, yaml)
    'humble_probe': REPO / 'tests' / 'fixtures' / 'humble_probe',
    # composition and pluginlib as users write them (tests/test_ros_loading.py)
    **{name: REPO / 'tests' / 'ros_fixtures' / name for name in (
        'composition_cases', 'pluginlib_base', 'pluginlib_greeters', 'pluginlib_user')},
}

"""Repositories of the corpus snapshot the fixtures need (pluginlib)."""
CORPUS = ('ros/pluginlib', 'ros2/tinyxml2_vendor', 'leethomason/tinyxml2')

RCLCPP_UP_TO = (
    'rclcpp', 'rclcpp_action', 'rclcpp_components', 'rclcpp_lifecycle',
    # what overlays of real packages need too (tests/corpus_build.py)
    'ament_cmake_auto', 'ros_environment',
    *EXAMPLES, *TEST_PACKAGES)

RCLCPP_SKIP = ()

"""
Link the test workspace's executables at -O1: ~45 rclcpp executables link in
a third of the time (CI budget), with the same behaviour; bench/rclcpp and
docs report sizes of default (-O2) links separately.
"""
RCLCPP_COLCON_ARGS = ('--wasm-link-opt-level', '1')


class ExistingBuild:
    """A workspace built beforehand by the developer (COLCON_WASM_RCLCPP_WORKSPACE)."""

    def __init__(self, workspace):
        """Use `workspace`/install_wasm as it is."""
        self.workspace = Path(workspace)
        self.install = self.workspace / 'install_wasm'
        self.build = self.workspace / 'build_wasm'
        assert self.install.is_dir(), f'no install_wasm in {workspace}'
        refresh_runtime(self.install)  # the repository's JS runtime, as for a cached build
        self.packages = sorted(p.name for p in self.install.iterdir() if p.is_dir())


def rclcpp_build():
    """Build (or reuse) Humble up to rclcpp, the examples and the rmw tests.

    A developer iterating on one package can set COLCON_WASM_RCLCPP_WORKSPACE
    to a workspace they built with `colcon build --wasm` themselves; CI never
    sets it.
    """
    workspace = os.environ.get('COLCON_WASM_RCLCPP_WORKSPACE')
    if workspace:
        return ExistingBuild(workspace)
    return humble_build(up_to=RCLCPP_UP_TO, skip=RCLCPP_SKIP,
                        extra=TEST_PACKAGES, colcon_args=RCLCPP_COLCON_ARGS,
                        corpus=CORPUS)


def executable(build, package, name):
    """Get the path of an installed executable's .js."""
    path = build.install / package / 'lib' / package / f'{name}.js'
    assert path.is_file(), f'{package}/{name} was not installed at {path}'
    return path
