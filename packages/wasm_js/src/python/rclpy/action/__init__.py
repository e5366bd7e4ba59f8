# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.action: action servers and clients (rcl_action's protocol, on the bus).

An action of a node is found in the graph by its hidden topics and
services, as rcl_action finds it: ``<action>/_action/feedback`` gives the
action names and types, ``send_goal`` servers and clients the nodes.
"""

from rclpy.action.client import ActionClient
from rclpy.action.client import ClientGoalHandle
from rclpy.action.server import ActionServer
from rclpy.action.server import CancelResponse
from rclpy.action.server import GoalResponse
from rclpy.action.server import ServerGoalHandle

__all__ = ['ActionClient', 'ActionServer', 'CancelResponse', 'ClientGoalHandle', 'GoalResponse',
           'ServerGoalHandle', 'get_action_names_and_types',
           'get_action_server_names_and_types_by_node',
           'get_action_client_names_and_types_by_node']

_FEEDBACK = '/_action/feedback'
_SEND_GOAL = '/_action/send_goal'


def _strip(names_and_types, suffix, type_suffix):
    found = []
    for name, types in names_and_types:
        if name.endswith(suffix):
            found.append((name[:-len(suffix)],
                          [t[:-len(type_suffix)] if t.endswith(type_suffix) else t
                           for t in types]))
    return sorted(found)


def get_action_names_and_types(node):
    """Return ``[(action name, [types])]`` of the graph."""
    return _strip(node.get_topic_names_and_types(), _FEEDBACK, '_FeedbackMessage')


def get_action_server_names_and_types_by_node(node, remote_node_name, remote_node_namespace):
    """Return the actions a node serves, ``[(name, [types])]``."""
    return _strip(node.get_service_names_and_types_by_node(
        remote_node_name, remote_node_namespace), _SEND_GOAL, '_SendGoal')


def get_action_client_names_and_types_by_node(node, remote_node_name, remote_node_namespace):
    """Return the actions a node is a client of, ``[(name, [types])]``."""
    return _strip(node.get_client_names_and_types_by_node(
        remote_node_name, remote_node_namespace), _SEND_GOAL, '_SendGoal')
