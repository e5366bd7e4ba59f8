# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.validate_node_name, with rmw's rules (rclpy/_names.py)."""

from rclpy._names import node_name_error
from rclpy.exceptions import InvalidNodeNameException


def validate_node_name(node_name):
    """
    Validate a node name.

    :returns: True when it is valid
    :raises InvalidNodeNameException: when it is not
    """
    error = node_name_error(node_name)
    if error is None:
        return True
    raise InvalidNodeNameException(node_name, *error)
