# Copyright 2026 colcon-wasm authors
# Licensed under the Apache License, Version 2.0

"""A lifecycle node driven through its transitions, and Shutdown on a node's exit."""

from launch import LaunchDescription
from launch.actions import EmitEvent
from launch.actions import LogInfo
from launch.actions import RegisterEventHandler
from launch.actions import Shutdown
from launch.events import matches_action
from launch_ros.actions import LifecycleNode
from launch_ros.actions import Node
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState
import lifecycle_msgs.msg


def generate_launch_description():
    talker = LifecycleNode(package='launch_cases', executable='lifecycle_talker',
                           name='lc_talker', namespace='')
    return LaunchDescription([
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker, goal_state='inactive',
            entities=[
                LogInfo(msg="node 'lc_talker' reached the 'inactive' state, 'activating'."),
                EmitEvent(event=ChangeState(
                    lifecycle_node_matcher=matches_action(talker),
                    transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE)),
            ])),
        RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=talker, goal_state='active',
            entities=[
                LogInfo(msg="node 'lc_talker' reached the 'active' state, launching 'listener'."),
                Node(package='demo_nodes_cpp', executable='listener',
                     remappings=[('chatter', 'lifecycle_chatter')]),
                Node(package='launch_cases', executable='exit_after', name='stopper',
                     parameters=[{'count': 6, 'word': 'stopper'}], on_exit=Shutdown()),
            ])),
        talker,
        EmitEvent(event=ChangeState(
            lifecycle_node_matcher=matches_action(talker),
            transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE)),
    ])
