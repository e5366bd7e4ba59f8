# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The context of rclpy.init: command-line ROS arguments, the domain, shutdown."""

import os
import sys


class Context:
    """What rclpy.init sets up and rclpy.shutdown ends."""

    def __init__(self):
        """Create an uninitialised context."""
        self._ok = False
        self._args = []
        self._nodes = []
        self.domain_id = 0

    def init(self, args=None, domain_id=None):
        """Initialise from ``args`` (default: sys.argv)."""
        if self._ok:
            raise RuntimeError('Context.init() must only be called once')
        self._args = list(sys.argv if args is None else args)
        if domain_id is None:
            domain_id = int(os.environ.get('ROS_DOMAIN_ID', '0') or 0)
        self.domain_id = domain_id
        self._ok = True

    def ok(self):
        """Return True between init and shutdown."""
        return self._ok

    def shutdown(self):
        """Destroy the nodes and end the context."""
        if not self._ok:
            raise RuntimeError('Context must be initialized before it can be shutdown')
        for node in list(self._nodes):
            node.destroy_node()
        self._ok = False

    def try_shutdown(self):
        """Shut down unless already shut down."""
        if self._ok:
            self.shutdown()

    def _check_ok(self, what):
        if not self._ok:
            raise RuntimeError(f'cannot {what}: call rclpy.init() first (or the context was '
                               'shut down)')

    def _ros_rules(self, flags, cli_args):
        """Yield the ``from:=to`` pairs after each of ``flags`` inside ``--ros-args``."""
        for args in (self._args, cli_args or []):
            inside = False
            it = iter(args)
            for arg in it:
                if arg == '--ros-args':
                    inside = True
                elif arg == '--':
                    inside = False
                elif inside and arg in flags:
                    rule = next(it, '')
                    if ':=' in rule:
                        yield rule.split(':=', 1)

    def parameter_overrides(self, node_name, cli_args=None):
        """Return the ``-p [node:]name:=value`` values of the ROS arguments for a node."""
        from rclpy.parameter import parse_value
        values = {}
        for name, value in self._ros_rules(('-p', '--param'), cli_args):
            if ':' in name:
                node, name = name.split(':', 1)
                if node != node_name:
                    continue
            values[name] = parse_value(value)
        return values

    def remappings(self, cli_args=None):
        """Return the ``-r from:=to`` rules of the ROS arguments (``--ros-args``)."""
        return dict(self._ros_rules(('-r', '--remap'), cli_args))


_default = Context()


def default_context():
    """Return the process' default context."""
    return _default


def remove_ros_args(args):
    """Return ``args`` without the ROS arguments."""
    out = []
    inside = False
    for arg in args:
        if arg == '--ros-args':
            inside = True
        elif arg == '--' and inside:
            inside = False
        elif not inside:
            out.append(arg)
    return out
