# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rosapi's parameter services on serve's rosbridge relay.

roslibjs' ``Param`` (get, set, delete) and ``getParams``, and roslibpy's
``Param``, call rosapi's ``get_param``, ``set_param``, ``delete_param``,
``has_param`` and ``get_param_names``. ROS 2 has no parameter server: rosapi
calls the nodes' rcl parameter services. So does the relay: the pages
advertise their nodes' ``/<node>/get_parameters``, ``set_parameters`` and
``list_parameters`` to it (bridges/rosbridge/client.mjs), and the relay
calls them as it routes any call, in rosbridge JSON. As rosapi:

* a parameter is named ``<node>:<parameter>`` (``/talker:greeting``);
* values travel as JSON text: ``get_param`` answers ``json.dumps`` of the
  value, ``set_param`` types the JSON it is given as ``ros2 param set``
  does (``5`` an integer, ``5.0`` a double, ``"5"`` a string, a list an
  array of one of these);
* ``get_param`` of a parameter or node that is not there answers the
  request's ``default_value`` when it has one;
* ``get_param_names`` lists the parameters of every node that has a
  ``list_parameters`` service; a node that does not answer is left out.

The answers carry rosapi_msgs' ``successful`` and ``reason`` (roslibjs 2
calls its failure callback with the reason): a name with no ``:``, a node
with no parameter services on the graph, a value that is not JSON or no
parameter value, a value the node refuses (a declared type, a read-only
parameter) name what is wrong. The Node.js server's rosapi.mjs answers
the same.
"""

import base64
import json

from colcon_wasm.server.foxglove_parameters import BYTE_ARRAY
from colcon_wasm.server.foxglove_parameters import NOT_SET
from colcon_wasm.server.foxglove_parameters import ParameterError
from colcon_wasm.server.foxglove_parameters import to_rcl
from colcon_wasm.server.foxglove_parameters import VALUE_FIELDS

"""Seconds a node's parameter service has to answer the relay."""
PARAMETER_TIMEOUT = 5.0


def split_name(name):
    """
    Split rosapi's ``<node>:<parameter>``.

    :returns: ``(node, parameter)``, the node fully qualified
    :raises ParameterError: naming the name when it has no node or no parameter
    """
    i = name.rfind(':') if isinstance(name, str) else -1
    if i <= 0 or i == len(name) - 1:
        raise ParameterError(f'malformed parameter name {name!r}: expected '
                             '<node_name>:<param_name>, e.g. /talker:greeting')
    node = name[:i]
    return (node if node.startswith('/') else f'/{node}'), name[i + 1:]


def plain_value(value):
    """
    Return the plain value of an rcl_interfaces/msg/ParameterValue (rosbridge JSON).

    :returns: ``(True, value)``, or ``(False, None)`` for NOT_SET or no value
    """
    if not isinstance(value, dict):
        return False, None
    kind = value.get('type')
    field = VALUE_FIELDS.get(kind) if isinstance(kind, int) else None
    if field is None:
        return False, None
    v = value.get(field)
    if kind == BYTE_ARRAY and isinstance(v, str):
        v = list(base64.b64decode(v))
    return True, v


class _Answer:
    """The relay's own caller of a node's service: hands the reply to a function."""

    def __init__(self, done):
        self.done = done

    def send(self, out):
        """Take the relay's service_response: ``done(values, None)`` or ``done(None, why)``."""
        values = out.get('values')
        if not out.get('result'):
            self.done(None, str(values))
        elif not isinstance(values, dict):
            self.done(None, f'the answer is no JSON object: {json.dumps(values)[:60]}')
        else:
            self.done(values, None)

    def status(self, level, text, rid=None):
        """Say nothing: a failure's text comes with its service_response."""


class RosapiParameters:
    """The parameter services of rosapi, over one relay's graph."""

    SERVICES = ('get_param', 'has_param', 'set_param', 'delete_param', 'get_param_names')

    def __init__(self, relay):
        """Call the nodes' parameter services through ``relay``."""
        self.relay = relay

    def call(self, service, args, answer):
        """
        Answer one rosapi request once the nodes answered (under the relay's lock).

        :param service: one of :attr:`SERVICES`
        :param args: the request (rosapi_msgs)
        :param answer: called once with the response values
        """
        args = args if isinstance(args, dict) else {}
        if service == 'get_param_names':
            self._names(answer)
            return
        try:
            node, param = split_name(args.get('name'))
        except ParameterError as e:
            answer(_failed(service, str(e), args))
            return
        getattr(self, f'_{service}')(node, param, args, answer)

    def _ask(self, node, service, request, done):
        """Call ``<node>/<service>``: ``done(values, None)``, or ``done(None, why)``."""
        name = f'{node}/{service}'
        if name not in self.relay.services:
            done(None, f'no node {node} with parameter services is on the graph of the pages '
                       f'(nobody serves {name})')
            return
        self.relay.request(name, request, PARAMETER_TIMEOUT, _Answer(done))

    def _value(self, node, param, done):
        """Get one parameter: ``done(found, value, why)``."""
        def got(values, error):
            if values is None:
                done(False, None, error)
                return
            found, value = plain_value(_first(values, 'values'))
            done(found, value, None if found else f'{node} has no parameter {param!r}')
        self._ask(node, 'get_parameters', {'names': [param]}, got)

    def _get_param(self, node, param, args, answer):
        def got(found, value, why):
            if found:
                answer({'value': json.dumps(value), 'successful': True, 'reason': ''})
            elif args.get('default_value'):
                answer({'value': _default(args), 'successful': True, 'reason': ''})
            else:
                answer({'value': 'null', 'successful': False, 'reason': why})
        self._value(node, param, got)

    def _has_param(self, node, param, args, answer):
        self._value(node, param, lambda found, value, why: answer({'exists': found}))

    def _set_param(self, node, param, args, answer):
        text = args.get('value')
        try:
            value = json.loads(text) if isinstance(text, str) else None
        except ValueError:
            value = None
        if not isinstance(text, str) or (value is None and text.strip() != 'null'):
            answer(_failed('set_param', 'the value of set_param must be JSON text '
                           f'(e.g. 5, 2.5, "text", [1, 2]), got {text!r}'))
            return
        try:
            # rosapi sets an empty string for null
            rcl = to_rcl({'name': f'{node}:{param}', 'value': '' if value is None else value})
        except ParameterError as e:
            answer(_failed('set_param', str(e)))
            return
        self._set(node, param, rcl, answer, 'setting')

    def _set(self, node, param, rcl, answer, doing):
        def done(values, error):
            result = _first(values, 'results')
            result = result if isinstance(result, dict) else {}
            if values is None:
                answer(_failed('set_param', f'cannot set {node}:{param}: {error}'))
            elif not result.get('successful'):
                why = result.get('reason') or 'refused by the node'
                answer(_failed('set_param', f'{doing} {node}:{param} failed: {why}'))
            else:
                answer({'successful': True, 'reason': ''})
        self._ask(node, 'set_parameters', {'parameters': [{'name': param, 'value': rcl}]}, done)

    def _delete_param(self, node, param, args, answer):
        def got(found, value, why):
            if found:
                self._set(node, param, {'type': NOT_SET}, answer, 'deleting')
            else:
                answer(_failed('delete_param', f'cannot delete {node}:{param}: {why}'))
        self._value(node, param, got)

    def _names(self, answer):
        suffix = '/list_parameters'
        nodes = sorted(s[:-len(suffix)] for s in self.relay.services if s.endswith(suffix))
        listed = {}

        def one(node):
            def done(values, error):
                result = (values or {}).get('result')
                names = result.get('names') if isinstance(result, dict) else None
                names = names if isinstance(names, list) else []
                listed[node] = [f'{node}:{n}' for n in names if isinstance(n, str)]
                if len(listed) == len(nodes):
                    answer({'names': [name for each in nodes for name in listed[each]]})
            return done

        if not nodes:
            answer({'names': []})
        for node in nodes:
            self._ask(node, 'list_parameters', {'prefixes': [], 'depth': 0}, one(node))


def _first(values, key):
    """Return the first item of the list ``values[key]``, or None."""
    items = values.get(key) if isinstance(values, dict) else None
    return items[0] if isinstance(items, list) and items else None


def _failed(service, reason, args=None):
    """Return the answer of a request that failed: rosapi_msgs' successful and reason."""
    out = {'successful': False, 'reason': reason}
    if service == 'get_param':
        out['value'] = _default(args or {})
    elif service == 'has_param':
        out = {'exists': False}
    return out


def _default(args):
    """Return rosapi's answer for a missing parameter: the default, as JSON text."""
    default = args.get('default_value')
    if not isinstance(default, str) or default == '':
        return 'null'
    try:
        return json.dumps(json.loads(default))
    except ValueError:
        return json.dumps(default)
