# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rmw's name validation (rmw/src/validate_*.c of Humble), in Python.

rclpy's ``validate_namespace``, ``validate_node_name`` and
``validate_full_topic_name`` ask rmw through ``_rclpy``; these are the same
rules, with rmw's messages and the index rmw reports. launch_ros validates
every ``Node``'s name and namespace with them on the build host.
"""

#: rmw's RMW_TOPIC_MAX_NAME_LENGTH (255, less 8 reserved for prefixes)
TOPIC_MAX_NAME_LENGTH = 255 - 8
#: rmw's RMW_NAMESPACE_MAX_LENGTH
NAMESPACE_MAX_LENGTH = TOPIC_MAX_NAME_LENGTH - 2
#: rmw's RMW_NODE_NAME_MAX_NAME_LENGTH
NODE_NAME_MAX_LENGTH = 255


def _alnum(c):
    return c.isascii() and c.isalnum()


def full_topic_name_error(name, what='topic name'):
    """Return ``(message, index)`` of what is wrong with an absolute topic name, or None."""
    if not name:
        return f'{what} must not be empty', 0
    if name[0] != '/':
        return f"{what} must be absolute, it must lead with a '/'", 0
    if name[-1] == '/':
        return f"{what} must not end with a '/'", len(name) - 1
    for i, c in enumerate(name):
        if not (_alnum(c) or c in '_/'):
            return f"{what} must not contain characters other than alphanumerics, '_', or '/'", i
    for i in range(len(name) - 1):
        if name[i] == '/':
            if name[i + 1] == '/':
                return f"{what} must not contain repeated '/'", i + 1
            if name[i + 1].isdigit():
                return f'{what} must not have a token that starts with a number', i + 1
    if len(name) > TOPIC_MAX_NAME_LENGTH:
        return f"topic length should not exceed '{TOPIC_MAX_NAME_LENGTH}'", \
            TOPIC_MAX_NAME_LENGTH - 1
    return None


def namespace_error(namespace):
    """Return ``(message, index)`` of what is wrong with a namespace, or None."""
    if namespace == '/':
        return None
    error = full_topic_name_error(namespace, 'namespace')
    if error is not None and not error[0].startswith('topic length'):
        message, index = error
        if message == "namespace must not end with a '/'":
            message = "namespace must not end with a '/', unless only a '/'"
        return message, index
    if len(namespace) > NAMESPACE_MAX_LENGTH:
        return f"namespace should not exceed '{NAMESPACE_MAX_LENGTH}'", NAMESPACE_MAX_LENGTH - 1
    return None


def node_name_error(name):
    """Return ``(message, index)`` of what is wrong with a node name, or None."""
    if not name:
        return 'node name must not be empty', 0
    for i, c in enumerate(name):
        if not (_alnum(c) or c == '_'):
            return "node name must not contain characters other than alphanumerics or '_'", i
    if name[0].isdigit():
        return 'node name must not start with a number', 0
    if len(name) > NODE_NAME_MAX_LENGTH:
        return f"node name length should not exceed '{NODE_NAME_MAX_LENGTH}'", \
            NODE_NAME_MAX_LENGTH - 1
    return None
