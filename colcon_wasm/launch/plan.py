# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""A launch plan: the processes to start, each with its ROS arguments."""

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
        if self.name is not None and not _NAME.match(self.name):
            raise LaunchError(
                "node name '{}' is not valid: use letters, digits and '_', not starting "
                'with a digit'.format(self.name), *self.where)
        if self.namespace is not None and self.namespace != '/':
            tokens = self.namespace.strip('/').split('/')
            if not all(_NAMESPACE_TOKEN.match(t) for t in tokens):
                raise LaunchError(
                    "namespace '{}' is not valid: use '/'-separated names of letters, "
                    "digits and '_'".format(self.namespace), *self.where)

    def ros_argv(self):
        """Return the arguments after ``--ros-args`` that launch_ros would give."""
        argv = list(self.ros_arguments)
        if self.name is not None:
            argv += ['-r', '__node:={}'.format(self.name)]
        if self.namespace is not None:
            argv += ['-r', '__ns:={}'.format(self.namespace)]
        for name, value, node in self.parameters:
            argv += ['-p', '{}{}:={}'.format(node + ':' if node else '', name, value)]
        for source, target in self.remappings:
            argv += ['-r', '{}:={}'.format(source, target)]
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

    def __init__(self, processes=(), arguments=None):
        """Keep the processes and label them ``exe-N`` with one counter, as launch does."""
        self.processes = list(processes)
        self.arguments = dict(arguments or {})
        for index, process in enumerate(self.processes, start=1):
            process.label = '{}-{}'.format(process.exec_name, index)
