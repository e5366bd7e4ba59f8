# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.utilities: the context helpers and ``remove_ros_args``, as rclpy's.

``remove_ros_args(sys.argv)`` gives a script its own arguments, without
the ROS ones (``--ros-args ... [--]``), for its own argument parser: the
arguments of ``colcon-wasm run --python 'FILE ARGS'`` arrive in
``sys.argv`` as natively.
"""

import sys

from rclpy import context as _context


def get_default_context(*, shutting_down=False):
    """Return the process' default context."""
    return _context.default_context()


def remove_ros_args(args=None):
    """Return ``args`` (default: sys.argv) without the ROS arguments."""
    return _context.remove_ros_args(sys.argv if args is None else args)


def ok(*, context=None):
    """Return True between rclpy.init and rclpy.shutdown."""
    return (context or _context.default_context()).ok()


def shutdown(*, context=None):
    """Shut down rclpy (rclpy.shutdown)."""
    import rclpy
    rclpy.shutdown(context=context)


def try_shutdown(*, context=None):
    """Shut down rclpy unless it is shut down already."""
    import rclpy
    rclpy.try_shutdown(context=context)


def timeout_sec_to_nsec(timeout_sec):
    """Return a timeout in seconds in nanoseconds: -1 (forever) for None or negative."""
    if timeout_sec is None or timeout_sec < 0:
        return -1
    return int(float(timeout_sec) * 1e9)
