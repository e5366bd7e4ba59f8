# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Humble's last launch and launch_ros, xacro and the launch fixtures, built as an overlay.

Python launch files run with the install space's own launch and launch_ros
(colcon_wasm/launch/python_launch/). The control-stack snapshot
(../shared/corpus-control, $COLCON_WASM_CORPUS_CONTROL) holds Humble's last
releases of them (launch 1.0.14, launch_ros 0.19.14) and xacro; they are
built with `colcon build --wasm --wasm-underlay` on the corpus overlay
(robot_state_publisher), cached like it, keyed by its inputs, with the
fixtures `demo_nodes_cpp` (the talker and listener the upstream example
launch files start) and `launch_cases` (tests/ros_fixtures).

    from launch_build import launch_build
    build = launch_build()
"""

from corpus_build import corpus_build
from humble_build import control_snapshot
from humble_build import humble_build
from humble_build import REPO

"""Repositories of the control-stack snapshot the overlay takes."""
CONTROL_REPOSITORIES = ('ros2/launch', 'ros2/launch_ros', 'ros/xacro')

LAUNCH_UP_TO = ('launch', 'launch_xml', 'launch_yaml', 'launch_ros', 'xacro',
                'demo_nodes_cpp', 'launch_cases')

EXTRA = {name: REPO / 'tests' / 'ros_fixtures' / name
         for name in ('demo_nodes_cpp', 'launch_cases')}


def launch_build():
    """Build (or reuse) the launch overlay on the corpus build."""
    underlay = corpus_build()
    return humble_build(
        up_to=LAUNCH_UP_TO, skip=(), extra=EXTRA, colcon_args=('--wasm-link-opt-level', '1'),
        control=CONTROL_REPOSITORIES, underlay=underlay, snapshot=False)


def upstream_examples():
    """Return the folder of ros2launch's example launch files, unmodified, in the snapshot."""
    from humble_build import unpacked_source
    return unpacked_source(control_snapshot(), 'humble-control-src') / 'ros2' / 'launch_ros' / \
        'ros2launch' / 'examples'


"""The robot demo of the docs (demo/robot/demo_robot: an arm, its motion, an .rviz file)."""
ROBOT_DEMO = {'demo_robot': REPO / 'demo' / 'robot' / 'demo_robot'}


def robot_demo_build():
    """Build (or reuse) demo/robot on the launch overlay (robot_state_publisher, launch_ros)."""
    underlay = launch_build()
    return humble_build(
        up_to=('demo_robot',), skip=(), extra=ROBOT_DEMO,
        colcon_args=('--wasm-link-opt-level', '1'), underlay=underlay, snapshot=False)
