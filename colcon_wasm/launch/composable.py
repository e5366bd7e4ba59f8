# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Composable nodes: the LoadNode requests of node_container and load_composable_node.

launch_ros (Humble) loads each composable node with one call of its
container's ``<container>/_container/load_node`` service
(``composition_interfaces/srv/LoadNode``).  This module builds those requests
as ``get_composable_node_load_request`` does: remap rules ``from:=to``,
parameters and extra arguments as ``rcl_interfaces/msg/Parameter`` typed as
rclpy types the launch values, parameter files narrowed to the ``**`` and
``ns/name`` sections.  The Node host (``launch/composable.mjs``) makes the
calls; any container that serves the service works.
"""

import math

from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.launch_plan import yaml_value
import yaml

LOAD_NODE_TYPE = 'composition_interfaces/srv/LoadNode'

# rcl_interfaces/msg/ParameterType
_BOOL, _INTEGER, _DOUBLE, _STRING, _BYTE_ARRAY = 1, 2, 3, 4, 5
_BOOL_ARRAY, _INTEGER_ARRAY, _DOUBLE_ARRAY, _STRING_ARRAY = 6, 7, 8, 9
_INT64 = (-2 ** 63, 2 ** 63 - 1)
_VALUE_HINT = 'a bool, an integer, a float, a string, or a list of one of them'


def _json_double(value):
    """Return a double for the plan's JSON ('NaN' and 'Infinity' as cdr.mjs reads them)."""
    if math.isnan(value):
        return 'NaN'
    if math.isinf(value):
        return 'Infinity' if value > 0 else '-Infinity'
    return value


def _json_integer(name, value, where):
    if not _INT64[0] <= value <= _INT64[1]:
        raise LaunchError(f"parameter '{name}': {value} does not fit a 64-bit integer", *where)
    return str(value)  # int64 as a decimal string: exact in JSON and in JS


def parameter_message(name, value, where):
    """
    Make an ``rcl_interfaces/msg/Parameter`` of a launch value, as rclpy types it.

    A bool is BOOL, an int INTEGER, a float DOUBLE, a str STRING; a list is
    an array of its items' type, and an empty list a BYTE_ARRAY (the first
    type rclpy's ``Parameter.Type.check`` accepts it as).

    :returns: the message as JSON (int64 as decimal strings)
    :raises LaunchError: for None, mappings, mixed lists, out-of-range ints
    """
    def fail(why):
        return LaunchError(f"parameter '{name}': {why} ({_VALUE_HINT})", *where)

    if isinstance(value, bool):
        typed = {'type': _BOOL, 'bool_value': value}
    elif isinstance(value, int):
        typed = {'type': _INTEGER, 'integer_value': _json_integer(name, value, where)}
    elif isinstance(value, float):
        typed = {'type': _DOUBLE, 'double_value': _json_double(value)}
    elif isinstance(value, str):
        typed = {'type': _STRING, 'string_value': value}
    elif isinstance(value, (list, tuple)):
        items = list(value)
        if not items:
            typed = {'type': _BYTE_ARRAY, 'byte_array_value': []}
        elif all(isinstance(v, bool) for v in items):
            typed = {'type': _BOOL_ARRAY, 'bool_array_value': items}
        elif all(isinstance(v, int) and not isinstance(v, bool) for v in items):
            typed = {'type': _INTEGER_ARRAY,
                     'integer_array_value': [_json_integer(name, v, where) for v in items]}
        elif all(isinstance(v, float) for v in items):
            typed = {'type': _DOUBLE_ARRAY, 'double_array_value': [_json_double(v) for v in items]}
        elif all(isinstance(v, str) for v in items):
            typed = {'type': _STRING_ARRAY, 'string_array_value': items}
        else:
            raise fail(f'{items!r} mixes types; write every item alike (e.g. 1.0 for a float)')
    elif value is None:
        raise fail('it has no value')
    else:
        raise fail(f'{value!r} is not a parameter value')
    return {'name': name, 'value': typed}


def extra_argument_value(text, name, where):
    """
    Evaluate an ``extra_arg`` value as launch_ros does: the text read as YAML.

    A non-empty list must hold items of one type; an empty text is ``''``.

    :raises LaunchError: for a mapping, null or a mixed list
    """
    try:
        value = yaml.safe_load(text) if text else ''
    except yaml.YAMLError:
        raise LaunchError(f"extra argument '{name}': {text!r} is not valid YAML; quote a string "
                          "(value=\"'text'\")", *where) from None
    if isinstance(value, list):
        if not value or type(value[0]) not in (bool, int, float, str) or not all(
                isinstance(v, type(value[0])) for v in value):
            raise LaunchError(
                f"extra argument '{name}': {value!r} is not a non-empty list of items of one type "
                '(bool, int, float or str)', *where)
    elif not isinstance(value, (bool, int, float, str)):
        raise LaunchError(f"extra argument '{name}': {text!r} is not {_VALUE_HINT}", *where)
    return value


def _file_value(name, value, path, where):
    """Normalize a value of a parameters file as launch_ros' normalize_parameter_dict."""
    if not isinstance(value, list):
        return value
    kinds = {type(v) for v in value}
    if kinds == {int}:
        return value
    if kinds in ({float}, {int, float}):
        return [float(v) for v in value]
    if kinds in ({bool}, {str}):
        return value
    raise LaunchError(
        f"parameter '{name}' in {path}: {value!r} is not a non-empty list of items of one type "
        '(ints and floats together become floats)', *where)


def _flatten(prefix, value, out):
    if isinstance(value, dict):
        for key, item in value.items():
            _flatten(f'{prefix}{key}.', item, out)
    else:
        out.append((prefix[:-1], value))


def _node_sections(document, keys, found):
    """Collect ``{'ns/name' or '**': parameters}`` as launch_ros' to_parameters_list."""
    for key, value in document.items():
        if key == 'ros__parameters':
            found['/'.join(keys)] = value
            return
        if isinstance(value, dict):
            _node_sections(value, keys + [str(key).lstrip('/')], found)


def file_parameters(path, node_name, namespace, where):
    """
    Read the parameters of one composable node from a parameters file.

    As launch_ros does for composable nodes: the ``/**`` section, then the
    section of the node's ``ns/name`` (it wins); other sections, and
    wildcards such as ``/**/name``, do not apply.

    :returns: ``[(dotted.name, value)]``
    :raises LaunchError: for a file that cannot be read or values of no type
    """
    try:
        with open(path, 'r', encoding='utf-8') as f:
            document = yaml.safe_load(f)
    except OSError as e:
        raise LaunchError(f'cannot read the parameters file {path}: {e.strerror}',
                          *where) from None
    except yaml.YAMLError as e:
        raise LaunchError(f'the parameters file {path} is not valid YAML: {e}',
                          *where) from None
    sections = {}
    if isinstance(document, dict):
        _node_sections(document, [], sections)
    if not sections:
        raise LaunchError(f'the parameters file {path} has no node section with '
                          "'ros__parameters' (e.g. /**: {ros__parameters: {rate: 5}})",
                          *where)
    key = node_name
    if namespace and namespace != '/':
        key = f"{namespace.strip('/')}/{node_name}"
    merged = dict(sections.get('**') or {})
    merged.update(sections.get(key) or {})
    flat = []
    _flatten('', merged, flat)
    return [(name, _file_value(name, value, path, where)) for name, value in flat]


class ComposableNode:
    """One ``composable_node``: what its LoadNode request carries."""

    def __init__(self, package, plugin, name, *, namespace=None, remappings=(),
                 parameters=(), extra_arguments=(), where=(None, None)):
        """
        Describe a composable node; values are evaluated already.

        :param namespace: the absolute namespace, or None for the node's own
        :param remappings: ``[(from, to)]``
        :param parameters: ``[(name, value, (file, line))]`` in order (a later one wins)
        :param extra_arguments: the same, e.g. use_intra_process_comms
        :raises LaunchError: for a value that is no parameter type, at its line
        """
        self.package = package
        self.plugin = plugin
        self.name = name
        self.namespace = namespace
        self.remappings = list(remappings)
        self.parameters = [parameter_message(*p) for p in parameters]
        self.extra_arguments = [parameter_message(*a) for a in extra_arguments]
        self._values = [(n, v) for n, v, _ in parameters]
        self._extra_values = [(n, v) for n, v, _ in extra_arguments]
        self.where = where

    def request(self):
        """Return the ``composition_interfaces/srv/LoadNode`` request, as JSON."""
        return {
            'package_name': self.package,
            'plugin_name': self.plugin,
            'node_name': self.name,
            'node_namespace': self.namespace or '',
            'log_level': 0,  # launch_ros (Humble) leaves it unset
            'remap_rules': [f'{s}:={t}' for s, t in self.remappings],
            'parameters': self.parameters,
            'extra_arguments': self.extra_arguments,
        }

    def describe(self):
        """Return the node as the arguments a ComponentManager gives it, for --print-plan."""
        words = [self.package, self.plugin, '--ros-args']
        for source, target in self.remappings:
            words += ['-r', f'{source}:={target}']
        words += ['-r', f'__node:={self.name}']
        if self.namespace:
            words += ['-r', f'__ns:={self.namespace}']
        for name, value in self._values:
            words += ['-p', f'{name}:={yaml_value(value)}']
        for name, value in self._extra_values:
            words += ['-e', f'{name}:={yaml_value(value)}']
        return ' '.join(words)


class LoadComposableNodes:
    """Composable nodes to load, in order, into one container."""

    def __init__(self, target, nodes, *, containers=(), kind='load_composable_node',
                 where=(None, None)):
        """
        Describe one ``load_composable_node`` (or the nodes of a ``node_container``).

        :param target: the container's name as written (``/ns/name``; a
          relative name is resolved in ``/``, as launch_ros' own node does)
        :param containers: the NodeProcesses of this launch with that name:
          when they all exit before the service appears, the load fails at once
        :param kind: the tag, for messages
        """
        self.target = target
        self.service = f"{target if target.startswith('/') else '/' + target}/_container/load_node"
        self.nodes = list(nodes)
        self.containers = list(containers)
        self.kind = kind
        self.where = where

    @property
    def container_name(self):
        """Return the container's fully qualified name."""
        return self.service[:-len('/_container/load_node')]

    def to_json(self):
        """Describe the load for the Node host."""
        file, line = self.where
        return {
            'target': self.target,
            'service': self.service,
            'type': LOAD_NODE_TYPE,
            'containers': [p.label for p in self.containers],
            'where': f'<{self.kind}> at {file}:{line}' if file is not None else None,
            'requests': [node.request() for node in self.nodes],
        }
