# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The robot demo as a ROS 2 launch file: robot_state_publisher with the URDF, arm_motion, rviz2."""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('demo_robot')
    with open(os.path.join(share, 'urdf', 'demo_arm.urdf')) as f:
        robot_description = f.read()
    return LaunchDescription([
        DeclareLaunchArgument('rate', default_value='30.0',
                              description='joint states per second'),
        DeclareLaunchArgument('rviz', default_value='true', description='start rviz2'),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': robot_description}], output='screen'),
        Node(package='demo_robot', executable='arm_motion',
             parameters=[{'rate': LaunchConfiguration('rate')}], output='screen'),
        Node(package='rviz2', executable='rviz2',
             condition=IfCondition(LaunchConfiguration('rviz')),
             arguments=['-d', os.path.join(share, 'rviz', 'demo.rviz')]),
    ])
