# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Launch plans for ``colcon-wasm launch`` and ``run``.

A plan is a list of processes (an executable of the install space and its
argv with ``--ros-args -r ... -p ...``), read from an XML or YAML launch file
(``load_launch_file``) or from ``PKG/EXE`` items (``plan_items``), and the
composable nodes to load into containers (``composable``).
"""

from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.launch_plan import LaunchPlan
from colcon_wasm.launch.launch_plan import NodeProcess
from colcon_wasm.launch.loader import load_launch_file

__all__ = ['LaunchError', 'LaunchPlan', 'NodeProcess', 'load_launch_file', 'plan_items',
           'split_launch_arguments']


def split_launch_arguments(values):
    """
    Split ``name:=value`` launch arguments from the other values.

    :returns: ``(others, {name: value})``
    :raises LaunchError: for an argument with an empty name
    """
    others = []
    arguments = {}
    for value in values:
        name, separator, text = value.partition(':=')
        if separator and '/' not in name:
            if not name:
                raise LaunchError(f"launch argument {value!r} has no name before ':='")
            arguments[name] = text
        else:
            others.append(value)
    return others, arguments


def plan_items(items):
    """
    Make a plan of ``PKG/EXE`` items, one process each, with no arguments.

    :raises LaunchError: for an item that is not ``PKG/EXE``
    """
    processes = []
    for item in items:
        package, separator, executable = item.partition('/')
        if not separator or not package or not executable or '/' in executable:
            raise LaunchError(
                f"'{item}' is neither a launch file nor a PKG/EXE item (e.g. demo_nodes/talker)")
        processes.append(NodeProcess(package, executable))
    return LaunchPlan(processes)
