# Copyright 2026 colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""A talker on `topic`, and the YAML file of its listener (Python includes YAML)."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import AnyLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    topic = LaunchConfiguration('topic')
    return LaunchDescription([
        DeclareLaunchArgument('topic', default_value='chatter'),
        Node(package='demo_nodes_cpp', executable='talker', remappings=[('chatter', topic)]),
        IncludeLaunchDescription(
            AnyLaunchDescriptionSource(PathJoinSubstitution(
                [FindPackageShare('launch_cases'), 'launch', 'listener.launch.yaml'])),
            launch_arguments={'topic': topic}.items()),
    ])
