# Copyright 2026 colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""A robot description package's launch file, as real ones are written."""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.actions import LogInfo
from launch.actions import RegisterEventHandler
from launch.actions import TimerAction
from launch.conditions import IfCondition
from launch.event_handlers import OnProcessExit
from launch.substitutions import Command
from launch.substitutions import FindExecutable
from launch.substitutions import LaunchConfiguration
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare
import yaml


def generate_launch_description():
    # a share file read at load time, as many launch files read their configuration
    with open(os.path.join(get_package_share_directory('launch_cases'), 'config',
                           'robot.yaml')) as f:
        config = yaml.safe_load(f)
    robot_description = Command([
        PathJoinSubstitution([FindExecutable(name='xacro')]), ' ',
        PathJoinSubstitution([FindPackageShare('launch_cases'), 'urdf', 'robot.urdf.xacro']),
        ' arm_length:=', LaunchConfiguration('arm_length')])
    first = Node(package='launch_cases', executable='exit_after', name='first',
                 parameters=[{'count': config['ticks'], 'word': 'first'}])
    return LaunchDescription([
        DeclareLaunchArgument('gui', default_value='false', description='Start the GUI'),
        DeclareLaunchArgument('arm_length', default_value='0.5',
                              description='Length of the arm link (m)'),
        LogInfo(msg=['robot name from the config: ', config['robot_name']]),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': ParameterValue(robot_description,
                                                              value_type=str)}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui',
             condition=IfCondition(LaunchConfiguration('gui'))),
        first,
        RegisterEventHandler(OnProcessExit(target_action=first, on_exit=[
            LogInfo(msg='first has exited: starting second'),
            Node(package='launch_cases', executable='exit_after', name='second',
                 parameters=[{'count': 1, 'word': 'second'}]),
        ])),
        TimerAction(period=1.5, actions=[LogInfo(msg='the timer fired after 1.5 s')]),
        Node(package='launch_cases', executable='exit_after', name='phoenix',
             parameters=[{'count': 1, 'code': 3, 'word': 'phoenix'}],
             respawn=True, respawn_delay=0.5),
    ])
