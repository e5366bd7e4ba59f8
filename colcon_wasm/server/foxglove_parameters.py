# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The ``parameters`` and ``parametersSubscribe`` capabilities of ``serve --foxglove``.

The pages advertise their nodes' rcl parameter services to serve's relay
and publish ``/parameter_events`` to it (bridges/rosbridge/client.mjs), so
this server calls the nodes' real services through the relay, in JSON
(rcl_interfaces' ``get_parameters``, ``set_parameters``,
``list_parameters`` of ``/<node>/...``), and hears the changes on
``/parameter_events``; it keeps no parameter store of its own. As
foxglove_bridge and the Node.js server of ``run``/``launch --foxglove``
(bridges/foxglove/parameters.mjs) do it:

* a parameter name is ``<node>.<parameter>`` (``/talker.rate``);
* ``getParameters`` without names gives every parameter of every node that
  has parameter services; with names, those (a name the node does not have
  is left out); the request ``id`` comes back with the values;
* ``setParameters`` sets them, and with an ``id`` answers with the values
  the nodes have then; a value left out (null) deletes the parameter;
* values are JSON: integers and strings as they are, doubles with ``type:
  float64``, ``float64_array``, ``byte_array`` (base64);
* ``subscribeParameterUpdates`` / ``unsubscribeParameterUpdates``: the
  changes of those names, as ``parameterValues`` without an id.

A node that does not exist on the relay's graph, a node that refuses a
value, a name without a node, a value that is no parameter value: an error
status naming it, with the request's id; the connection stays up.
"""

import base64
import threading

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.server import foxglove_wire as wire
from colcon_wasm.server.foxglove_link import CallError

logger = colcon_logger.getChild(__name__)

EVENTS_TOPIC = '/parameter_events'
EVENTS_TYPE = 'rcl_interfaces/msg/ParameterEvent'
PARAMETER_TIMEOUT = 5.0

# rcl_interfaces/msg/ParameterType
(NOT_SET, BOOL, INTEGER, DOUBLE, STRING, BYTE_ARRAY, BOOL_ARRAY, INTEGER_ARRAY, DOUBLE_ARRAY,
 STRING_ARRAY) = range(10)
"""The field of rcl_interfaces/msg/ParameterValue that holds each type's value."""
VALUE_FIELDS = {BOOL: 'bool_value', INTEGER: 'integer_value', DOUBLE: 'double_value',
                STRING: 'string_value', BYTE_ARRAY: 'byte_array_value',
                BOOL_ARRAY: 'bool_array_value', INTEGER_ARRAY: 'integer_array_value',
                DOUBLE_ARRAY: 'double_array_value', STRING_ARRAY: 'string_array_value'}


class ParameterError(ColconWasmError):
    """A parameter request that cannot be made: the text names what is wrong."""


def split_name(name):
    """
    Split ``/node.param`` at the first dot after the node name.

    :returns: ``(node, parameter)``, the node fully qualified
    :raises ParameterError: when the name has no ``.``
    """
    if not isinstance(name, str):
        raise ParameterError(f'parameter name {name!r} is not a string')
    full = name if name.startswith('/') else f'/{name}'
    dot = full.find('.', full.rfind('/'))
    if dot < 0 or dot == len(full) - 1 or full[dot - 1] == '/':
        raise ParameterError(f"parameter name '{name}' is not <node>.<parameter> "
                             '(e.g. /talker.rate)')
    return full[:dot], full[dot + 1:]


def _is_int(value):
    return isinstance(value, int) and not isinstance(value, bool)


def from_rcl(name, value):
    """
    Return the Foxglove parameter of an rcl_interfaces/msg/ParameterValue (rosbridge JSON).

    :returns: ``{name, value[, type]}``, or None for NOT_SET (or a value
      JSON cannot carry: a NaN double)
    """
    if not isinstance(value, dict):
        return None
    kind = value.get('type')
    field = VALUE_FIELDS.get(kind)
    if field is None or value.get(field) is None:
        return None
    v = value[field]
    if kind == DOUBLE:
        return {'name': name, 'value': v, 'type': 'float64'}
    if kind == DOUBLE_ARRAY:
        return {'name': name, 'value': v, 'type': 'float64_array'}
    if kind == BYTE_ARRAY:
        data = base64.b64decode(v) if isinstance(v, str) else bytes(v)
        return {'name': name, 'value': base64.b64encode(data).decode('ascii'),
                'type': 'byte_array'}
    return {'name': name, 'value': v}


def to_rcl(parameter):
    """
    Return the rcl_interfaces/msg/ParameterValue (rosbridge JSON) of a Foxglove parameter.

    :raises ParameterError: naming the parameter when its value is none of ROS 2's
    """
    name, value, kind = parameter.get('name'), parameter.get('value'), parameter.get('type')
    if value is None:
        return {'type': NOT_SET}
    if kind == 'byte_array':
        try:
            data = base64.b64decode(value, validate=True) if isinstance(value, str) else None
        except ValueError:
            data = None
        if data is None:
            raise ParameterError(f"parameter '{name}': a byte_array value must be base64 text")
        return {'type': BYTE_ARRAY, 'byte_array_value': list(data)}
    numbers = (int, float)
    if kind == 'float64' and isinstance(value, numbers) and not isinstance(value, bool):
        return {'type': DOUBLE, 'double_value': float(value)}
    if kind == 'float64_array' and isinstance(value, list) and all(
            isinstance(v, numbers) and not isinstance(v, bool) for v in value):
        return {'type': DOUBLE_ARRAY, 'double_array_value': [float(v) for v in value]}
    if isinstance(value, bool):
        return {'type': BOOL, 'bool_value': value}
    if _is_int(value):
        return {'type': INTEGER, 'integer_value': value}
    if isinstance(value, float):
        return {'type': DOUBLE, 'double_value': value}
    if isinstance(value, str):
        return {'type': STRING, 'string_value': value}
    if isinstance(value, list):
        if all(isinstance(v, bool) for v in value):
            return {'type': BOOL_ARRAY, 'bool_array_value': value}
        if all(_is_int(v) for v in value):
            return {'type': INTEGER_ARRAY, 'integer_array_value': value}
        if all(isinstance(v, numbers) and not isinstance(v, bool) for v in value):
            return {'type': DOUBLE_ARRAY, 'double_array_value': [float(v) for v in value]}
        if all(isinstance(v, str) for v in value):
            return {'type': STRING_ARRAY, 'string_array_value': value}
    raise ParameterError(f"parameter '{name}': {value!r} is no ROS 2 parameter value (a bool, "
                         'number, string, or an array of only one of these)')


def _names(msg, key, what):
    value = msg.get(key)
    if not isinstance(value, list):
        raise ParameterError(f"{msg.get('op')} needs '{key}': an array of {what}")
    return value


class Parameters:
    """The nodes' parameters, through the relay, for the sessions of one server."""

    def __init__(self, server):
        """Use the server's own relay link (``server.control``)."""
        self.server = server
        self.lock = threading.Lock()
        self.watchers = {}        # session -> set of parameter names

    @property
    def link(self):
        """The relay link the calls and /parameter_events go through."""
        return self.server.control

    @property
    def available(self):
        """Whether the install describes the parameter services and events."""
        schemas = self.server.schemas
        return all(schemas.resolve(t) for t in (
            'rcl_interfaces/srv/GetParameters_Request', 'rcl_interfaces/srv/SetParameters_Request',
            'rcl_interfaces/srv/ListParameters_Request', EVENTS_TYPE))

    # ------------------------------------------------------------ calls

    def _each(self, calls):
        """
        Make calls at once: ``{key: (service, args)}``.

        :returns: ``({key: values}, {key: error text})``
        """
        futures = {key: self.link.call(service, args, PARAMETER_TIMEOUT)
                   for key, (service, args) in calls.items()}
        done, failed = {}, {}
        for key, future in futures.items():
            try:
                done[key] = self.link.values(future, PARAMETER_TIMEOUT)
            except CallError as e:
                failed[key] = str(e)
        return done, failed

    def nodes(self):
        """List the nodes that have parameter services on the relay's graph."""
        services = set(self.link.values(self.link.call('/rosapi/services', {})).get(
            'services') or [])
        return sorted(s[:-len('/get_parameters')] for s in services
                      if s.endswith('/get_parameters') and
                      f"{s[:-len('/get_parameters')]}/list_parameters" in services)

    def get(self, names):
        """
        Read parameters; no names: every parameter of every node.

        :returns: ``(parameters, errors)``, the parameters sorted by name
        """
        errors = []
        by_node = {}
        if not names:
            try:
                nodes = self.nodes()
            except CallError as e:
                return [], [f'cannot list the services of the graph: {e}']
            listed, failed = self._each({n: (f'{n}/list_parameters', {'prefixes': [], 'depth': 0})
                                         for n in nodes})
            errors += [f'cannot list the parameters of {n}: {e}' for n, e in failed.items()]
            by_node = {n: list((v.get('result') or {}).get('names') or [])
                       for n, v in listed.items()}
        else:
            for name in names:
                node, param = split_name(name)
                by_node.setdefault(node, []).append(param)
        got, failed = self._each({n: (f'{n}/get_parameters', {'names': ps})
                                  for n, ps in by_node.items() if ps})
        errors += [f'cannot get the parameters of {_node_text(n, e)}' for n, e in failed.items()]
        parameters = []
        for node, values in got.items():
            for param, value in zip(by_node[node], values.get('values') or []):
                p = from_rcl(f'{node}.{param}', value)
                if p is not None:
                    parameters.append(p)
        return sorted(parameters, key=lambda p: p['name']), errors

    def set(self, parameters):
        """
        Set parameters, per node.

        :returns: the errors (a node that refused a value says why)
        :raises ParameterError: for a name or value that is wrong (nothing is set then)
        """
        by_node = {}
        for p in parameters:
            if not isinstance(p, dict):
                raise ParameterError(f'setParameters: {p!r} is not a {{name, value}} object')
            node, param = split_name(p.get('name'))
            by_node.setdefault(node, []).append({'name': param, 'value': to_rcl(p)})
        answers, failed = self._each({n: (f'{n}/set_parameters', {'parameters': ps})
                                      for n, ps in by_node.items()})
        errors = [f'cannot set the parameters of {_node_text(n, e)}' for n, e in failed.items()]
        for node, values in answers.items():
            for p, result in zip(by_node[node], values.get('results') or []):
                if not result.get('successful'):
                    errors.append(f"setting {node}.{p['name']} failed: "
                                  f"{result.get('reason') or 'refused by the node'}")
        return errors

    # ------------------------------------------------------------ Foxglove ops

    def get_parameters(self, session, msg):
        """Answer ``getParameters``: ``parameterValues`` with the request's id."""
        rid = msg.get('id')
        try:
            parameters, errors = self.get(_names(msg, 'parameterNames',
                                                 'parameter names (/node.param)'))
        except ParameterError as e:
            session.status(wire.ERROR, f'getParameters: {e}', rid)
            return
        for e in errors:
            session.status(wire.ERROR, f'getParameters: {e}', rid)
        session.send_json(op='parameterValues', parameters=parameters,
                          **({} if rid is None else {'id': rid}))

    def set_parameters(self, session, msg):
        """Answer ``setParameters``; with an id, the values the nodes have then."""
        rid = msg.get('id')
        try:
            params = _names(msg, 'parameters', '{name, value} objects')
            errors = self.set(params)
        except ParameterError as e:
            session.status(wire.ERROR, f'setParameters: {e}', rid)
            return
        for e in errors:
            session.status(wire.ERROR, f'setParameters: {e}', rid)
        if rid is not None:
            parameters, errors = self.get([p['name'] for p in params])
            session.send_json(op='parameterValues', parameters=parameters, id=rid)

    def follow(self):
        """
        Subscribe to /parameter_events (JSON), when the install describes it.

        From the start, not when a session first watches: the relay tells the
        pages which forms to send when they advertise the topic, so no change
        made after a session subscribed is missed while the relay asks.
        """
        if self.available:
            self.link.send(op='subscribe', id='foxglove-parameters', topic=EVENTS_TOPIC,
                           type=EVENTS_TYPE)

    def subscribe(self, session, msg):
        """``subscribeParameterUpdates``: hear the changes of those names."""
        names = _names(msg, 'parameterNames', 'parameter names (/node.param)')
        with self.lock:
            self.watchers.setdefault(session, set()).update(n for n in names
                                                            if isinstance(n, str))

    def unsubscribe(self, session, msg):
        """``unsubscribeParameterUpdates``: no more changes of those names."""
        names = _names(msg, 'parameterNames', 'parameter names (/node.param)')
        with self.lock:
            self.watchers.get(session, set()).difference_update(names)

    def forget(self, session):
        """Forget a session that ended."""
        with self.lock:
            self.watchers.pop(session, None)

    def event(self, event):
        """One rcl_interfaces/msg/ParameterEvent (JSON): send its changes to who watches them."""
        if not isinstance(event, dict) or not isinstance(event.get('node'), str):
            return
        node = event['node'] if event['node'].startswith('/') else f"/{event['node']}"
        changed = []
        for p in (event.get('new_parameters') or []) + (event.get('changed_parameters') or []):
            value = from_rcl(f"{node}.{p.get('name')}", p.get('value'))
            if value is not None:
                changed.append(value)
        changed += [{'name': f"{node}.{p.get('name')}"}
                    for p in event.get('deleted_parameters') or []]
        with self.lock:
            watchers = [(s, set(names)) for s, names in self.watchers.items()]
        for session, names in watchers:
            mine = [p for p in changed if p['name'] in names]
            if mine:
                session.send_json(op='parameterValues', parameters=mine)


def _node_text(node, error):
    """Say why a node's parameter service failed; a node the graph lacks is named so."""
    if 'does not exist' in error:
        return f'{node}: no node {node} with parameter services is on the graph of the pages'
    return f'{node}: {error}'
