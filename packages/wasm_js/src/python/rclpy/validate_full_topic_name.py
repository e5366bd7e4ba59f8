# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.validate_full_topic_name, with rmw's rules (rclpy/_names.py)."""

from rclpy._names import full_topic_name_error
from rclpy.exceptions import InvalidServiceNameException
from rclpy.exceptions import InvalidTopicNameException


def validate_full_topic_name(name, *, is_service=False):
    """
    Validate an absolute topic (or service) name.

    :returns: True when it is valid
    :raises InvalidTopicNameException: (InvalidServiceNameException) when it is not
    """
    error = full_topic_name_error(name)  # rmw's text says 'topic name' for services too
    if error is None:
        return True
    raise (InvalidServiceNameException if is_service else InvalidTopicNameException)(name, *error)
