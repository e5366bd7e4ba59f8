# Copyright 2026 colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""A launch file that raises while it is loaded."""

from launch import LaunchDescription


def generate_launch_description():
    names = {'talker': 'demo_nodes_cpp'}
    return LaunchDescription([names['listener']])
