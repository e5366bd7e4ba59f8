# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Real Humble repositories of the corpus snapshot, built as an overlay.

The corpus (../shared/corpus, $COLCON_WASM_CORPUS) holds geometry2, urdf,
urdfdom, kdl_parser, orocos KDL, robot_state_publisher, message_filters,
diagnostics and angles, unmodified at their Humble versions. They are built
with `colcon build --wasm --wasm-underlay` on the cached rclcpp build
(tests/rclcpp_build.py): a real overlay, cached like it, keyed by its
inputs. TinyXML 1 comes from Debian's source package (recipe `system`),
Eigen from the host. Bullet (tf2_bullet) takes minutes: it is built by
`bench/corpus`, whose table is docs/ecosystem.md, not here.

    from corpus_build import corpus_build
    build = corpus_build()
"""

from humble_build import humble_build
from humble_build import REPO
from rclcpp_build import rclcpp_build

"""Repositories of the corpus the overlay takes (folders of its src/)."""
CORPUS_REPOSITORIES = (
    'ros2/geometry2', 'ros/robot_state_publisher', 'ros2/urdf', 'ros/urdfdom',
    'ros/urdfdom_headers', 'ros/kdl_parser', 'ros2/orocos_kdl_vendor',
    'orocos/orocos_kinematics_dynamics', 'ros2/eigen3_cmake_module',
    'ros2/message_filters', 'ros2/tinyxml_vendor', 'ros/diagnostics', 'ros/angles')

"""What the tests run, and every C/C++ package of those repositories that
needs no hardware, no GUI and no Bullet."""
CORPUS_UP_TO = (
    'robot_state_publisher', 'diagnostic_aggregator', 'diagnostic_updater', 'self_test',
    'message_filters', 'tf2', 'tf2_ros', 'tf2_msgs', 'tf2_eigen', 'tf2_eigen_kdl',
    'tf2_geometry_msgs', 'tf2_kdl', 'tf2_sensor_msgs', 'kdl_parser', 'urdf', 'angles',
    'corpus_probe')

EXTRA = {'corpus_probe': REPO / 'tests' / 'ros_fixtures' / 'corpus_probe'}


def corpus_build():
    """Build (or reuse) the corpus overlay on the rclcpp build."""
    underlay = rclcpp_build()
    return humble_build(
        up_to=CORPUS_UP_TO, skip=(), extra=EXTRA, colcon_args=('--wasm-link-opt-level', '1'),
        corpus=CORPUS_REPOSITORIES, underlay=underlay, snapshot=False)
