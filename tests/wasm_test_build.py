# Copyright 2026 The colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""
The test build of issue 15: tests cross-compiled with `--wasm-tests`, cached.

One `colcon build --wasm` of the Humble snapshot up to
test_rmw_implementation (the rmw conformance suite), rcl (its own tests),
the fixture package wasm_test_cases and rmw_wasm_cpp_fault_tests, with
their tests and with fault
injection (`--wasm-fault-injection`: every package compiled with
RCUTILS_ENABLE_FAULT_INJECTION, as rcutils' own test build makes its users
do). The test tooling comes from the corpus snapshot at Humble's versions:
ament/googletest (gtest_vendor, gmock_vendor), osrf_testing_tools_cpp and
rmw_dds_common.

Why not an overlay on the cached rclcpp build (tests/rclcpp_build.py):
fault injection is compiled into rcutils, rmw and rcl themselves, and the
underlay's CMake configs name its own static libraries by path, so an
overlay cannot replace them. This build stops below rclcpp, which is most of
the rclcpp build's time. It is cached by tests/humble_build.py under
``$COLCON_WASM_CACHE``, keyed by its inputs.

    from wasm_test_build import wasm_test_build, colcon_test
    build = wasm_test_build()       # skips when a snapshot is absent
"""

import os
from pathlib import Path
import subprocess
import sys

from humble_build import humble_build
from humble_build import REPO
from rclcpp_build import ExistingBuild

"""Packages of this repository added to the workspace (name: folder)."""
EXTRA = {
    'wasm_test_cases': REPO / 'tests' / 'ros_fixtures' / 'wasm_test_cases',
    'rmw_wasm_cpp_fault_tests': REPO / 'tests' / 'rmw' / 'rmw_wasm_cpp_fault_tests',
}

"""The packages whose tests are built and run."""
TESTED = ('test_rmw_implementation', 'rcl', *EXTRA)

"""Repositories of the corpus snapshot: the test tooling at Humble's versions."""
CORPUS = ('ament/googletest', 'osrf/osrf_testing_tools_cpp', 'ros2/rmw_dds_common')

"""Link tests at -O1 (CI budget), as tests/rclcpp_build.py does."""
COLCON_ARGS = ('--wasm-link-opt-level', '1', '--wasm-fault-injection',
               '--wasm-tests', *TESTED)


def wasm_test_build():
    """
    Build (or reuse) the test build; skips when a snapshot is absent.

    A developer can set COLCON_WASM_TEST_WORKSPACE to a workspace built with
    the same command (see COLCON_ARGS); CI never sets it.
    """
    workspace = os.environ.get('COLCON_WASM_TEST_WORKSPACE')
    if workspace:
        return ExistingBuild(workspace)
    return humble_build(up_to=TESTED, skip=(), extra=EXTRA, colcon_args=COLCON_ARGS,
                        corpus=CORPUS)


def colcon_test(build, *packages, extra=(), timeout=1800):
    """
    Run `colcon test --wasm` on packages of the build, then read the results.

    :returns: (the completed `colcon test`, the completed
      `colcon test-result --wasm --all --verbose`)
    """
    colcon = str(Path(sys.executable).parent / 'colcon')
    env = dict(os.environ, COLCON_HOME=str(build.workspace / '.colcon_home'))
    tested = subprocess.run(
        [colcon, 'test', '--wasm', '--packages-select', *packages,
         '--event-handlers', 'console_direct-', *extra],
        cwd=build.workspace, env=env, stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT, text=True, timeout=timeout)
    base = build.build / packages[0] if len(packages) == 1 else build.build
    shown = subprocess.run(
        [colcon, 'test-result', '--wasm', '--all', '--verbose',
         '--test-result-base', str(base)],
        cwd=build.workspace, env=env, stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT, text=True, timeout=300)
    return tested, shown
