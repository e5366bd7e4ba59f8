# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A node's parameter services and ``/parameter_events``, as rclpy's ParameterService.

``~/describe_parameters``, ``~/get_parameters``, ``~/get_parameter_types``,
``~/list_parameters``, ``~/set_parameters`` and
``~/set_parameters_atomically`` (rcl_interfaces), so that the launcher page,
``ros2 param``-style tools and C++ nodes (``rclcpp::AsyncParametersClient``)
read and set a Python node's parameters; each change is published on
``/parameter_events``. They need the rcl_interfaces type descriptions in the
install space; without them the node has none (as a node with
``start_parameter_services=False``).
"""

from rclpy import _messages
from rclpy.parameter import Parameter
from rclpy.qos import qos_profile_services_default

_SERVICES = {
    'describe_parameters': 'DescribeParameters',
    'get_parameters': 'GetParameters',
    'get_parameter_types': 'GetParameterTypes',
    'list_parameters': 'ListParameters',
    'set_parameters': 'SetParameters',
    'set_parameters_atomically': 'SetParametersAtomically',
}

# ParameterValue's field for each Parameter.Type
_FIELDS = {
    Parameter.Type.BOOL: 'bool_value',
    Parameter.Type.INTEGER: 'integer_value',
    Parameter.Type.DOUBLE: 'double_value',
    Parameter.Type.STRING: 'string_value',
    Parameter.Type.BYTE_ARRAY: 'byte_array_value',
    Parameter.Type.BOOL_ARRAY: 'bool_array_value',
    Parameter.Type.INTEGER_ARRAY: 'integer_array_value',
    Parameter.Type.DOUBLE_ARRAY: 'double_array_value',
    Parameter.Type.STRING_ARRAY: 'string_array_value',
}


def available():
    """Return True when the install describes rcl_interfaces' parameter services."""
    try:
        _messages.service_class('rcl_interfaces/srv/GetParameters')
        _messages.message_class('rcl_interfaces/msg/ParameterEvent')
    except ImportError:
        return False
    return True


def to_value_msg(parameter):
    """Return the rcl_interfaces/msg/ParameterValue of a Parameter."""
    cls = _messages.message_class('rcl_interfaces/msg/ParameterValue')
    msg = cls(type=int(parameter.type_))
    field = _FIELDS.get(parameter.type_)
    if field is not None:
        value = parameter.value
        if isinstance(value, (list, tuple, bytes, bytearray)):
            value = list(value)  # bytes: their ints, as byte[] holds them
        setattr(msg, field, value)
    return msg


def from_value_msg(name, msg):
    """Return the Parameter of a name and an rcl_interfaces/msg/ParameterValue."""
    kind = Parameter.Type(msg.type)
    field = _FIELDS.get(kind)
    value = getattr(msg, field) if field else None
    if kind == Parameter.Type.BYTE_ARRAY:
        value = bytes(value)
    elif field is not None and not isinstance(value, (bool, int, float, str)):
        value = list(value)  # a sequence (list or array.array)
    return Parameter(name, kind, value)


class ParameterService:
    """The parameter services and ``/parameter_events`` publisher of one node."""

    def __init__(self, node):
        """Create the six services under the node's name and the events publisher."""
        self.node = node
        for suffix, name in _SERVICES.items():
            srv_type = _messages.service_class(f'rcl_interfaces/srv/{name}')
            node.create_service(srv_type, f'~/{suffix}', getattr(self, f'_{suffix}'),
                                qos_profile=qos_profile_services_default)
        self._event_type = _messages.message_class('rcl_interfaces/msg/ParameterEvent')
        self.events = node.create_publisher(self._event_type, '/parameter_events', 1000)

    def publish_event(self, new=(), changed=(), deleted=()):
        """Publish a ParameterEvent for this node."""
        param = _messages.message_class('rcl_interfaces/msg/Parameter')
        stamp = _messages.message_class('builtin_interfaces/msg/Time')
        sec, nanosec = self.node.get_clock().now().seconds_nanoseconds()
        self.events.publish(self._event_type(
            stamp=stamp(sec=sec, nanosec=nanosec),
            node=self.node.get_fully_qualified_name(),
            new_parameters=[param(name=p.name, value=to_value_msg(p)) for p in new],
            changed_parameters=[param(name=p.name, value=to_value_msg(p)) for p in changed],
            deleted_parameters=[param(name=p.name, value=to_value_msg(p)) for p in deleted]))

    def _get(self, name):
        return self.node._parameters.get(name, Parameter(name))

    def _describe_parameters(self, request, response):
        descriptor = _messages.message_class('rcl_interfaces/msg/ParameterDescriptor')
        response.descriptors = [descriptor(name=n, type=int(self._get(n).type_))
                                for n in request.names]
        return response

    def _get_parameters(self, request, response):
        response.values = [to_value_msg(self._get(n)) for n in request.names]
        return response

    def _get_parameter_types(self, request, response):
        response.types = [int(self._get(n).type_) for n in request.names]
        return response

    def _list_parameters(self, request, response):
        prefixes = list(request.prefixes)
        depth = request.depth
        names = []
        found = set()
        for name in sorted(self.node._parameters):
            if prefixes and not any(name == p or name.startswith(p + '.') for p in prefixes):
                continue
            if depth and name.count('.') >= depth:
                continue
            names.append(name)
            if '.' in name:
                found.add(name.rsplit('.', 1)[0])
        result = _messages.message_class('rcl_interfaces/msg/ListParametersResult')
        response.result = result(names=names, prefixes=sorted(found))
        return response

    def _set_one(self, parameters):
        result = _messages.message_class('rcl_interfaces/msg/SetParametersResult')
        try:
            outcome = self.node.set_parameters(parameters)
        except Exception as e:  # noqa: B902 rclpy answers any refusal with its reason
            return [result(successful=False, reason=str(e))] * len(parameters)
        return [result(successful=r.successful, reason=r.reason) for r in outcome]

    def _set_parameters(self, request, response):
        response.results = [self._set_one([from_value_msg(p.name, p.value)])[0]
                            for p in request.parameters]
        return response

    def _set_parameters_atomically(self, request, response):
        parameters = [from_value_msg(p.name, p.value) for p in request.parameters]
        result = _messages.message_class('rcl_interfaces/msg/SetParametersResult')
        undeclared = [p.name for p in parameters if p.name not in self.node._parameters]
        if undeclared and not self.node._allow_undeclared:
            response.result = result(successful=False,
                                     reason=f'parameter not declared: {undeclared[0]}')
            return response
        verdict = self.node._run_parameter_callbacks(parameters)
        if verdict.successful:
            for p in parameters:
                self.node._parameters[p.name] = p
            self.publish_event(new=[p for p in parameters if p.name in undeclared],
                               changed=[p for p in parameters if p.name not in undeclared])
        response.result = result(successful=verdict.successful, reason=verdict.reason)
        return response
