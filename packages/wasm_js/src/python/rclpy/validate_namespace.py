# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.validate_namespace, with rmw's rules (rclpy/_names.py)."""

from rclpy._names import namespace_error
from rclpy.exceptions import InvalidNamespaceException


def validate_namespace(namespace):
    """
    Validate a namespace: absolute and not empty, as rmw wants it.

    :returns: True when it is valid
    :raises InvalidNamespaceException: when it is not
    """
    error = namespace_error(namespace)
    if error is None:
        return True
    raise InvalidNamespaceException(namespace, *error)
