# Copyright 2026 colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""Composable nodes in a container, as the composition demo's launch file starts them."""

from launch import LaunchDescription
from launch.actions import TimerAction
from launch_ros.actions import ComposableNodeContainer
from launch_ros.actions import LoadComposableNodes
from launch_ros.descriptions import ComposableNode


def generate_launch_description():
    return LaunchDescription([
        ComposableNodeContainer(
            name='my_container', namespace='', package='rclcpp_components',
            executable='component_container',
            composable_node_descriptions=[
                ComposableNode(package='composition_cases', plugin='composition_cases::Talker',
                               name='talker', parameters=[{'use_sim_time': False}]),
            ]),
        TimerAction(period=1.0, actions=[LoadComposableNodes(
            target_container='/my_container',
            composable_node_descriptions=[
                ComposableNode(package='composition_cases',
                               plugin='composition_cases::Listener', name='listener',
                               extra_arguments=[{'use_intra_process_comms': True}]),
                ComposableNode(package='composition_cases', plugin='composition_cases::Nope',
                               name='nope'),
            ])]),
    ])
