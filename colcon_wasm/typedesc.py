# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

r"""Type descriptions: ROS interface definitions as JSON, for CDR in JS.

An interface package installs its definitions as ``share/<pkg>/msg/*.msg``,
``share/<pkg>/srv/*.srv`` and ``share/<pkg>/action/*.action``.  This module
parses them with the grammar of ``rosidl_adapter`` (Humble) and writes one
``share/<pkg>/colcon_wasm/types.json`` per package.  The launcher page and
``colcon-wasm launch --echo`` read these files to encode and decode CDR
(``packages/wasm_js/src/cdr.mjs``).

The JSON format (``schema`` 1)::

    {"schema": 1, "package": "demo_interfaces",
     "messages": {"demo_interfaces/msg/Num": {
         "fields": [{"name": "num", "type": "int64"},
                    {"name": "xs", "type": "float64", "sequence": true,
                     "sequence_bound": 4},
                    {"name": "name", "type": "string", "string_bound": 8,
                     "default": "abc"},
                    {"name": "stamp", "type": "builtin_interfaces/msg/Time"},
                    {"name": "rgb", "type": "uint8", "array_size": 3}],
         "constants": [{"name": "MAX", "type": "int32", "value": 7}],
         "definition": "int64 num\n..."}},
     "services": {"demo_interfaces/srv/AddTwoInts": {
         "request": "demo_interfaces/srv/AddTwoInts_Request",
         "response": "demo_interfaces/srv/AddTwoInts_Response",
         "definition": "int64 a\nint64 b\n---\nint64 sum\n"}},
     "actions": {"pkg/action/Fib": {
         "goal": "pkg/action/Fib_Goal", "result": "pkg/action/Fib_Result",
         "feedback": "pkg/action/Fib_Feedback",
         "send_goal": {"request": "...", "response": "..."},
         "get_result": {"request": "...", "response": "..."},
         "feedback_message": "pkg/action/Fib_FeedbackMessage"}}}

Each message keeps its ``definition``: the text of its ``.msg`` file (or of
its part of the ``.srv``/``.action``), comments included, from which
:mod:`colcon_wasm.ros2msg` assembles the schemas rosbag2 and Foxglove use;
services and actions keep the text of their whole file.

Service requests and responses and the messages an action implies (the
``_SendGoal``/``_GetResult`` services and the ``_FeedbackMessage``, as
``rosidl_parser`` defines them) are ordinary entries of ``messages``.  A
structure without fields gets the member ``uint8
structure_needs_at_least_one_member``, as rosidl generates it, because it is on
the wire.  64-bit integers are written as decimal strings and non-finite
floats as ``"NaN"``, ``"Infinity"``, ``"-Infinity"``, since JSON numbers cannot
hold them.
"""

import json
import math
import os
from pathlib import Path
import re

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError

logger = colcon_logger.getChild(__name__)

SCHEMA_VERSION = 1

PRIMITIVE_TYPES = (
    'bool', 'byte', 'char', 'float32', 'float64',
    'int8', 'uint8', 'int16', 'uint16', 'int32', 'uint32', 'int64', 'uint64',
    'string', 'wstring',
)
_INTEGER_RANGES = {
    'byte': (0, 255),
    'char': (0, 255),
    'int8': (-2 ** 7, 2 ** 7 - 1),
    'uint8': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1),
    'uint16': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1),
    'uint32': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1),
    'uint64': (0, 2 ** 64 - 1),
}
EMPTY_STRUCTURE_MEMBER = 'structure_needs_at_least_one_member'

_PACKAGE_NAME = re.compile(r'^(?!.*__)(?!.*_$)[a-z][a-z0-9_]*$')
_FIELD_NAME = _PACKAGE_NAME
_TYPE_NAME = re.compile(r'^[A-Z][A-Za-z0-9]*$')
_CONSTANT_NAME = re.compile(r'^[A-Z]([A-Z0-9_]?[A-Z0-9]+)*$')

_KINDS = (('msg', '.msg'), ('srv', '.srv'), ('action', '.action'))


class TypeDescriptionError(ColconWasmError, ValueError):
    """An interface definition that cannot be described; names file and line."""

    def __init__(self, message, *, path=None, line=None):
        """Record where the problem is and format ``path:line: message``."""
        self.path = path
        self.line = line
        location = ''
        if path is not None:
            location = str(path) + (f':{line}' if line else '') + ': '
        super().__init__(location + message)


def _error(message, source, line_number):
    return TypeDescriptionError(message, path=source, line=line_number)


def _full_name(package, kind, name):
    return f'{package}/{kind}/{name}'


def _parse_int(text):
    try:
        return int(text)
    except ValueError:
        return int(text, 0)


def _json_number(primitive, value):
    """Represent a parsed primitive value the way types.json stores it."""
    if primitive in ('int64', 'uint64'):
        return str(value)
    if primitive in ('float32', 'float64') and not math.isfinite(value):
        return 'NaN' if math.isnan(value) else (
            'Infinity' if value > 0 else '-Infinity')
    return value


def parse_primitive_value(primitive, text, *, string_bound=None):
    """
    Parse the text of a constant or default value of a primitive type.

    Follows ``rosidl_adapter.parser.parse_primitive_value_string``.

    :param primitive: the primitive type name, e.g. ``'int32'``
    :param text: the value as written in the definition
    :param string_bound: the upper bound of a bounded string type
    :returns: the value as stored in types.json
    :raises ValueError: with a message saying what is accepted
    """
    if primitive == 'bool':
        if text.lower() in ('true', '1'):
            return True
        if text.lower() in ('false', '0'):
            return False
        raise ValueError(
            f"value '{text}' is not a bool: use true/1 or false/0")
    if primitive in _INTEGER_RANGES:
        low, high = _INTEGER_RANGES[primitive]
        try:
            value = _parse_int(text)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise ValueError(
                f"value '{text}' is not a valid {primitive}: use an integer from {low} to {high}")
        return _json_number(primitive, value)
    if primitive in ('float32', 'float64'):
        try:
            return _json_number(primitive, float(text))
        except ValueError:
            raise ValueError(
                f"value '{text}' is not a valid {primitive}: use a number with '.' as the "
                'decimal separator') from None
    # string and wstring: outer quotes allow leading and trailing spaces
    for quote in ('"', "'"):
        if len(text) >= 2 and text.startswith(quote) and text.endswith(quote):
            text = text[1:-1]
            if re.search(rf'(?<!\\){quote}', text):
                raise ValueError(
                    f'string value {text!r} has an inner {quote} that is not escaped '
                    'with a backslash')
            text = text.replace('\\' + quote, quote)
            break
    if string_bound is not None and len(text) > string_bound:
        raise ValueError(
            f'string value {text!r} is longer than the bound of {string_bound} characters')
    return text


def _split_string_array(text):
    """Split the elements of a string array default (quotes may hold ',')."""
    values = []
    rest = text.strip()
    while rest:
        if rest[0] in '"\'':
            quote = rest[0]
            index = 1
            while index < len(rest):
                if rest[index] == '\\':
                    index += 2
                    continue
                if rest[index] == quote:
                    break
                index += 1
            else:
                raise ValueError(f'string array element {rest} has no closing {quote}')
            values.append(rest[1:index].replace('\\' + quote, quote))
            rest = rest[index + 1:].lstrip()
            if rest and rest[0] != ',':
                raise ValueError(
                    f"expected ',' after a quoted string, found {rest!r}")
            rest = rest[1:].lstrip()
        else:
            element, _, rest = rest.partition(',')
            values.append(element.strip())
            rest = rest.lstrip()
    return values


def parse_default_value(field, text):
    """
    Parse the default value text of a field description.

    :param field: the field description (``type``, ``array_size`` ...)
    :param text: the default value as written after the field name
    :returns: the value as stored in types.json
    :raises ValueError: when the value does not fit the field
    """
    primitive = field['type']
    if primitive not in PRIMITIVE_TYPES:
        raise ValueError(
            f"field of type '{primitive}' cannot have a default value: only primitive "
            'types and arrays of them can')
    bound = field.get('string_bound')
    if 'array_size' not in field and not field.get('sequence'):
        return parse_primitive_value(primitive, text, string_bound=bound)
    if not (text.startswith('[') and text.endswith(']')):
        raise ValueError(
            f"array default value '{text}' must start with '[' and end with ']'")
    inner = text[1:-1]
    if primitive in ('string', 'wstring'):
        elements = _split_string_array(inner)
    else:
        elements = [e.strip() for e in inner.split(',')] if inner.strip() else []
    size = field.get('array_size')
    if size is not None and len(elements) != size:
        raise ValueError(f'array default value has {len(elements)} elements, the array has {size}')
    limit = field.get('sequence_bound')
    if limit is not None and len(elements) > limit:
        raise ValueError(
            f'sequence default value has {len(elements)} elements, more than the bound {limit}')
    return [parse_primitive_value(primitive, e, string_bound=bound)
            for e in elements]


def parse_field_type(type_text, package):
    """
    Parse a field type such as ``string<=5[<=3]`` or ``geometry_msgs/Point[]``.

    :param type_text: the type as written in the definition
    :param package: the package of the definition (for unqualified types)
    :returns: a field description without name
    :raises ValueError: when the type is malformed
    """
    field = {}
    base = type_text
    if base.endswith(']'):
        index = base.rfind('[')
        if index < 0:
            raise ValueError(f"type '{type_text}' ends with ']' but has no '['")
        size_text = base[index + 1:-1]
        base = base[:index]
        if size_text == '':
            field['sequence'] = True
        else:
            upper = size_text.startswith('<=')
            if upper:
                size_text = size_text[2:]
            try:
                size = int(size_text)
            except ValueError:
                size = 0
            if size <= 0:
                raise ValueError(
                    f"the size of array type '{type_text}' must be an integer > 0, "
                    "optionally prefixed with '<=' for an upper bound")
            if upper:
                field['sequence'] = True
                field['sequence_bound'] = size
            else:
                field['array_size'] = size
    if base in PRIMITIVE_TYPES:
        field_type = base
    elif base.startswith(('string<=', 'wstring<=')):
        field_type, _, bound_text = base.partition('<=')
        try:
            bound = int(bound_text)
        except ValueError:
            bound = 0
        if bound <= 0:
            raise ValueError(
                f"the bound of string type '{base}' must be an integer > 0")
        field['string_bound'] = bound
    elif base in ('time', 'duration'):
        raise ValueError(
            f"'{base}' is a ROS 1 type: use builtin_interfaces/{base.capitalize()}")
    else:
        parts = base.split('/')
        if len(parts) == 1:
            type_package, name = package, parts[0]
        elif len(parts) == 2:
            type_package, name = parts
        elif len(parts) == 3 and parts[1] == 'msg':
            type_package, name = parts[0], parts[2]
        else:
            raise ValueError(
                f"type '{base}' is not a primitive type nor 'package/Message'")
        if not _PACKAGE_NAME.match(type_package):
            raise ValueError(f"'{type_package}' in type '{base}' is not a valid package name")
        if not _TYPE_NAME.match(name):
            raise ValueError(
                f"'{name}' in type '{base}' is not a valid message name (CamelCase, "
                'starting with an upper-case letter)')
        field_type = _full_name(type_package, 'msg', name)
    return dict({'type': field_type}, **field)


def parse_message(package, name, text, *, source=None, first_line=1):
    """
    Parse the text of a ``.msg`` definition (or one part of a .srv/.action).

    :param package: the package the definition belongs to
    :param name: the name of the message, e.g. ``'Num'`` or ``'Add_Request'``
    :param text: the definition
    :param source: the file, for error messages
    :param first_line: line number of the first line of ``text`` in ``source``
    :returns: ``{'fields': [...], 'constants': [...]}``
    :raises TypeDescriptionError: naming the file and line of the problem
    """
    fields = []
    constants = []
    names = {}
    for offset, raw_line in enumerate(text.splitlines()):
        line_number = first_line + offset
        line = raw_line.replace('\t', ' ')
        index = line.find('#')
        if index >= 0:
            line = line[:index]
        line = line.strip()
        if not line:
            continue
        type_text, _, rest = line.partition(' ')
        rest = rest.strip()
        if not rest:
            raise _error(
                f"'{line}' is not a field or constant: expected 'TYPE NAME', "
                "'TYPE NAME DEFAULT' or 'TYPE NAME=VALUE'",
                source, line_number)
        if '=' in rest:
            constant_name, _, value_text = rest.partition('=')
            constant_name = constant_name.strip()
            value_text = value_text.strip()
            if type_text not in PRIMITIVE_TYPES:
                raise _error(
                    f"constant '{constant_name}' has type '{type_text}': constants must have a "
                    'primitive '
                    'type', source, line_number)
            if not _CONSTANT_NAME.match(constant_name):
                raise _error(
                    f"'{constant_name}' is not a valid constant name (UPPER_CASE)",
                    source, line_number)
            try:
                value = parse_primitive_value(type_text, value_text)
            except ValueError as e:
                raise _error(f'constant {constant_name}: {e}',
                             source, line_number) from None
            entry = {'name': constant_name, 'type': type_text, 'value': value}
            target = constants
            entry_name = constant_name
        else:
            field_name, _, default_text = rest.partition(' ')
            default_text = default_text.strip()
            if not _FIELD_NAME.match(field_name):
                raise _error(
                    f"'{field_name}' is not a valid field name (lower_case, no double or "
                    'trailing underscore)', source, line_number)
            try:
                field = parse_field_type(type_text, package)
            except ValueError as e:
                raise _error(f'field {field_name}: {e}',
                             source, line_number) from None
            entry = dict({'name': field_name}, **field)
            if default_text:
                try:
                    entry['default'] = parse_default_value(field, default_text)
                except ValueError as e:
                    raise _error(f'default of field {field_name}: {e}',
                                 source, line_number) from None
            target = fields
            entry_name = field_name
        if entry_name in names:
            raise _error(
                f"'{entry_name}' is defined twice (first on line {names[entry_name]})",
                source, line_number)
        names[entry_name] = line_number
        target.append(entry)
    if not fields:
        fields.append({'name': EMPTY_STRUCTURE_MEMBER, 'type': 'uint8'})
    return {'fields': fields, 'constants': constants}


def _split_sections(text, count, source, kind):
    """Split a .srv or .action text at its '---' lines, keeping line numbers."""
    lines = text.splitlines()
    separators = [i for i, line in enumerate(lines) if line == '---']
    if len(separators) != count - 1:
        raise _error(
            f"a .{kind} file needs exactly {count - 1} '---' separator line(s), found "
            f'{len(separators)}', source, None)
    bounds = [-1] + separators + [len(lines)]
    return [('\n'.join(lines[bounds[i] + 1:bounds[i + 1]]), bounds[i] + 2)
            for i in range(count)]


def describe_message(package, name, text, *, source=None):
    """Describe a ``.msg`` file: ``{'<pkg>/msg/<name>': description}``."""
    return {_full_name(package, 'msg', name):
            _with_definition(parse_message(package, name, text, source=source), text)}


def _with_definition(description, text):
    """Keep the definition's text (comments and all) beside its description."""
    description['definition'] = text
    return description


def describe_service(package, name, text, *, source=None):
    """
    Describe a ``.srv`` file.

    :returns: ``(messages, services)``: the request and response messages and
      the service entry naming them
    """
    (request, request_line), (response, response_line) = _split_sections(
        text, 2, source, 'srv')
    messages = {}
    full = _full_name(package, 'srv', name)
    for suffix, part, line in (('_Request', request, request_line),
                               ('_Response', response, response_line)):
        messages[full + suffix] = _with_definition(parse_message(
            package, name + suffix, part, source=source, first_line=line), part)
    services = {full: {'request': full + '_Request', 'response': full + '_Response',
                       'definition': text}}
    return messages, services


def describe_action(package, name, text, *, source=None):
    """
    Describe an ``.action`` file, with the messages rosidl derives from it.

    :returns: ``(messages, actions)``
    """
    sections = _split_sections(text, 3, source, 'action')
    full = _full_name(package, 'action', name)
    messages = {}
    for suffix, (part, line) in zip(('_Goal', '_Result', '_Feedback'), sections):
        messages[full + suffix] = _with_definition(parse_message(
            package, name + suffix, part, source=source, first_line=line), part)
    uuid = {'name': 'goal_id', 'type': 'unique_identifier_msgs/msg/UUID'}
    messages[full + '_SendGoal_Request'] = {
        'fields': [uuid, {'name': 'goal', 'type': full + '_Goal'}], 'constants': []}
    messages[full + '_SendGoal_Response'] = {
        'fields': [{'name': 'accepted', 'type': 'bool'},
                   {'name': 'stamp', 'type': 'builtin_interfaces/msg/Time'}],
        'constants': []}
    messages[full + '_GetResult_Request'] = {'fields': [uuid], 'constants': []}
    messages[full + '_GetResult_Response'] = {
        'fields': [{'name': 'status', 'type': 'int8'},
                   {'name': 'result', 'type': full + '_Result'}],
        'constants': []}
    messages[full + '_FeedbackMessage'] = {
        'fields': [uuid, {'name': 'feedback', 'type': full + '_Feedback'}],
        'constants': []}
    # the messages rosidl derives get the text of their fields (rosidl writes
    # no file for them)
    uuid_line = 'unique_identifier_msgs/UUID goal_id\n'
    derived = {
        '_SendGoal_Request': uuid_line + f'{package}/{name}_Goal goal\n',
        '_SendGoal_Response': 'bool accepted\nbuiltin_interfaces/Time stamp\n',
        '_GetResult_Request': uuid_line,
        '_GetResult_Response': f'int8 status\n{package}/{name}_Result result\n',
        '_FeedbackMessage': uuid_line + f'{package}/{name}_Feedback feedback\n',
    }
    for suffix, definition in derived.items():
        _with_definition(messages[full + suffix], definition)
    actions = {full: {
        'definition': text,
        'goal': full + '_Goal',
        'result': full + '_Result',
        'feedback': full + '_Feedback',
        'send_goal': {'request': full + '_SendGoal_Request',
                      'response': full + '_SendGoal_Response'},
        'get_result': {'request': full + '_GetResult_Request',
                       'response': full + '_GetResult_Response'},
        'feedback_message': full + '_FeedbackMessage',
    }}
    return messages, actions


def describe_package(share_dir, package):
    """
    Describe every interface definition installed in a package's share dir.

    :param share_dir: ``<prefix>/share/<pkg>``
    :param package: the package name
    :returns: the types.json document, or None when the package installs no
      ``.msg``, ``.srv`` or ``.action`` file
    :raises TypeDescriptionError: for the first definition that does not parse
    """
    share_dir = Path(share_dir)
    document = {'schema': SCHEMA_VERSION, 'package': package,
                'messages': {}, 'services': {}, 'actions': {}}
    found = False
    for kind, suffix in _KINDS:
        directory = share_dir / kind
        if not directory.is_dir():
            continue
        for path in sorted(directory.glob('*' + suffix)):
            found = True
            name = path.stem
            if not _TYPE_NAME.match(name):
                raise TypeDescriptionError(
                    f"'{name}' is not a valid interface name (CamelCase)",
                    path=path)
            try:
                text = path.read_text(encoding='utf-8')
            except (OSError, UnicodeDecodeError) as e:
                raise TypeDescriptionError(f'cannot read: {e}', path=path) from e
            if kind == 'msg':
                document['messages'].update(
                    describe_message(package, name, text, source=path))
            elif kind == 'srv':
                messages, services = describe_service(package, name, text, source=path)
                document['messages'].update(messages)
                document['services'].update(services)
            else:
                messages, actions = describe_action(package, name, text, source=path)
                document['messages'].update(messages)
                document['actions'].update(actions)
    return document if found else None


def type_descriptions_path(prefix, package):
    """Return where the types.json of a package is installed."""
    return Path(prefix) / 'share' / package / 'colcon_wasm' / 'types.json'


def write_type_descriptions(prefix, package):
    """
    Write ``share/<pkg>/colcon_wasm/types.json`` for an installed package.

    Called by the post-processing step after the package is installed.

    :param prefix: the install prefix of the package
    :param package: the package name
    :returns: the path written, or None when the package installs no
      interface definitions
    :raises TypeDescriptionError: naming the definition file and line
    """
    document = describe_package(Path(prefix) / 'share' / package, package)
    if document is None:
        return None
    path = type_descriptions_path(prefix, package)
    path.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(document, indent=1, sort_keys=True, allow_nan=False) + '\n'
    temporary = path.with_name(path.name + '.tmp')
    temporary.write_text(text, encoding='utf-8')
    os.replace(str(temporary), str(path))
    logger.debug(f"Wrote type descriptions of '{package}' to '{path}'")
    return path
