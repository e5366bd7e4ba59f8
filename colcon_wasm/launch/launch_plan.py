# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""A launch plan: the processes to start, each with its ROS arguments.

It also holds the composable nodes to load into containers
(``colcon_wasm.launch.composable``), which the host loads once the processes
have started.
"""

import re

from colcon_wasm.launch.errors import LaunchError
import yaml

_NAME = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')
_NAMESPACE_TOKEN = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


def yaml_value(value):
    """Render a parameter value as the YAML text rcl parses after ``:=``."""
    text = yaml.safe_dump(value, default_flow_style=True, width=1 << 20).strip()
    if text.endswith('\n...'):
        text = text[:-4]
    return text.strip()


def absolute_namespace(base, namespace):
    """Combine a pushed namespace with a node's namespace, as launch_ros does."""
    if namespace is None:
        combined = base
    elif namespace.startswith('/') or not base:
        combined = namespace
    else:
        combined = base.rstrip('/') + '/' + namespace
    if combined is None:
        return None
    if not combined.startswith('/'):
        combined = '/' + combined
    if len(combined) > 1:
        combined = combined.rstrip('/')
    return combined


def validate_node_name(name, namespace, where, what='node'):
    """
    Check a node name and namespace as rcl would, before anything runs.

    :raises LaunchError: naming the file and line of the tag
    """
    if name is not None and not _NAME.match(name):
        raise LaunchError(
            f"{what} name '{name}' is not valid: use letters, digits and '_', not starting "
            'with a digit', *where)
    if namespace is not None and namespace != '/':
        tokens = namespace.strip('/').split('/')
        if not all(_NAMESPACE_TOKEN.match(t) for t in tokens):
            raise LaunchError(
                f"namespace '{namespace}' is not valid: use '/'-separated names of letters, "
                "digits and '_'", *where)


def fully_qualified_name(namespace, name):
    """Return ``/ns/name`` of a node (namespace None or ``/`` for the root)."""
    if not namespace or namespace == '/':
        return '/' + name
    return namespace.rstrip('/') + '/' + name


class NodeProcess:
    """One process of a launch: an executable with its arguments."""

    def __init__(self, package, executable, *, name=None, namespace=None, arguments=(),
                 ros_arguments=(), remappings=(), parameters=(), env=None,
                 exec_name=None, where=(None, None)):
        """
        Describe a process.

        :param parameters: ``[(name, yaml_text, node_name_or_None)]``
        :param where: ``(file, line)`` of the tag, for errors
        """
        self.package = package
        self.executable = executable
        self.name = name
        self.namespace = namespace
        self.arguments = list(arguments)
        self.ros_arguments = list(ros_arguments)
        self.remappings = list(remappings)
        self.parameters = list(parameters)
        self.env = dict(env or {})
        self.exec_name = exec_name or executable
        self.where = where
        self.label = self.exec_name
        self._validate()

    def _validate(self):
        validate_node_name(self.name, self.namespace, self.where)

    @property
    def node_name(self):
        """Return the node's fully qualified name, or None when the launch file names none."""
        if self.name is None:
            return None
        return fully_qualified_name(self.namespace, self.name)

    def ros_argv(self):
        """Return the arguments after ``--ros-args`` that launch_ros would give."""
        argv = list(self.ros_arguments)
        if self.name is not None:
            argv += ['-r', f'__node:={self.name}']
        if self.namespace is not None:
            argv += ['-r', f'__ns:={self.namespace}']
        for name, value, node in self.parameters:
            argv += ['-p', f"{node + ':' if node else ''}{name}:={value}"]
        for source, target in self.remappings:
            argv += ['-r', f'{source}:={target}']
        return argv

    def argv(self):
        """Return the full argument list (without the program name)."""
        ros = self.ros_argv()
        return self.arguments + (['--ros-args'] + ros if ros else [])

    def to_json(self):
        """Describe the process for the JS host (paths filled in by the caller)."""
        return {
            'label': self.label,
            'package': self.package,
            'executable': self.executable,
            'args': self.argv(),
            'env': self.env,
        }


class LaunchPlan:
    """The processes of one launch, labelled ``exe-N`` like ``ros2 launch``."""

    def __init__(self, processes=(), arguments=None, loads=()):
        """
        Keep the processes and label them ``exe-N`` with one counter, as launch does.

        :param loads: ``LoadComposableNodes`` in the order of the launch file
        """
        self.processes = list(processes)
        self.arguments = dict(arguments or {})
        self.loads = list(loads)
        for index, process in enumerate(self.processes, start=1):
            process.label = f'{process.exec_name}-{index}'
