# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python message classes, made at import time from the type descriptions.

``from std_msgs.msg import String`` works for every interface package whose
``types.json`` the process loaded: a meta path finder (last on
``sys.meta_path``, so real modules win) creates ``<pkg>``, ``<pkg>.msg`` and
``<pkg>.srv`` and ``<pkg>.action``. The classes follow rosidl_generator_py's: ``__slots__``,
keyword constructors, defaults, constants as class attributes, ``__eq__``,
``__repr__`` and type checks with its messages
(``The 'data' field must be of type 'str'``). Numeric sequences are
``array.array``; fixed-size arrays are lists (rclpy uses numpy arrays,
which Pyodide's npm package does not carry).
"""

import array
import importlib.abc
import importlib.machinery
import json
import sys
import types

_INT_RANGES = {
    'byte': (0, 255), 'char': (0, 255), 'octet': (0, 255),
    'int8': (-2 ** 7, 2 ** 7 - 1), 'uint8': (0, 2 ** 8 - 1),
    'int16': (-2 ** 15, 2 ** 15 - 1), 'uint16': (0, 2 ** 16 - 1),
    'int32': (-2 ** 31, 2 ** 31 - 1), 'uint32': (0, 2 ** 32 - 1),
    'int64': (-2 ** 63, 2 ** 63 - 1), 'uint64': (0, 2 ** 64 - 1),
}
_TYPECODES = {
    'int8': 'b', 'uint8': 'B', 'int16': 'h', 'uint16': 'H', 'int32': 'i',
    'uint32': 'I', 'int64': 'q', 'uint64': 'Q', 'float32': 'f', 'float64': 'd',
}
_FLOATS = ('float32', 'float64')

_descriptions = {}
_classes = {}


def load_descriptions(text):
    """Add type descriptions (``{messages, services, actions}`` as JSON text)."""
    doc = json.loads(text)
    for kind in ('messages', 'services', 'actions'):
        _descriptions.setdefault(kind, {}).update(doc.get(kind) or {})


def packages():
    """Return the interface packages described."""
    names = set()
    for kind in ('messages', 'services', 'actions'):
        names.update(name.split('/')[0] for name in _descriptions.get(kind, {}))
    return names


def _normalize(name):
    parts = name.split('/')
    if len(parts) == 2:
        return f'{parts[0]}/msg/{parts[1]}'
    return name


def _check_scalar(field, value, name):
    """Check one element like rosidl_generator_py's setters; returns it unchanged."""
    kind = field['type']
    if kind == 'bool':
        assert isinstance(value, bool), \
            f"The '{name}' field must be of type 'bool'"
    elif kind in ('string', 'wstring'):
        assert isinstance(value, str), \
            f"The '{name}' field must be of type 'str'"
        bound = field.get('string_bound')
        assert bound is None or len(value) <= bound, \
            f"The '{name}' field must be string with length <= {bound}"
    elif kind in _FLOATS:
        assert isinstance(value, float), \
            f"The '{name}' field must be of type 'float'"
    elif kind in _INT_RANGES:
        assert isinstance(value, int) and not isinstance(value, bool), \
            f"The '{name}' field must be of type 'int'"
        low, high = _INT_RANGES[kind]
        what = 'an unsigned' if low == 0 else 'a'
        assert low <= value <= high, \
            f"The '{name}' field must be {what} integer in [{low}, {high}]"
    else:
        cls = message_class(_normalize(kind))
        assert isinstance(value, cls), \
            f"The '{name}' field must be a sub message of type '{cls.__name__}'"
    return value


def _check(field, value):
    name = field['name']
    if 'array_size' not in field and not field.get('sequence'):
        return _check_scalar(field, value, name)
    assert isinstance(value, (list, tuple, array.array)), \
        f"The '{name}' field must be a set or sequence"
    size = field.get('array_size')
    bound = field.get('sequence_bound')
    if size is not None:
        assert len(value) == size, \
            f"The '{name}' field must have exactly {size} elements"
    if bound is not None:
        assert len(value) <= bound, \
            f"The '{name}' field must have at most {bound} elements"
    for element in value:
        _check_scalar(field, element, name)
    code = _TYPECODES.get(field['type'])
    if field.get('sequence') and code:
        return value if isinstance(value, array.array) else array.array(code, value)
    return list(value)


def _zero_scalar(field):
    kind = field['type']
    if kind == 'bool':
        return False
    if kind in ('string', 'wstring'):
        return ''
    if kind in _FLOATS:
        return 0.0
    if kind in _INT_RANGES:
        return 0
    return message_class(_normalize(kind))()


def _default(field):
    if 'default' in field:
        value = field['default']
        if field['type'] in _FLOATS:
            value = [float(v) for v in value] if isinstance(value, list) else float(value)
    elif field.get('array_size') is not None:
        value = [_zero_scalar(field) for _ in range(field['array_size'])]
    elif field.get('sequence'):
        value = []
    else:
        return _zero_scalar(field)
    return _check(field, value) if isinstance(value, list) else value


def _to_plain(field, value):
    """Convert a field value for cdr.mjs (through Pyodide's to_js)."""
    kind = field['type']
    nested = kind not in _INT_RANGES and kind not in _FLOATS and \
        kind not in ('bool', 'string', 'wstring')
    if 'array_size' in field or field.get('sequence'):
        if nested:
            return [v._to_plain() for v in value]
        return list(value)
    return value._to_plain() if nested else value


def _from_plain(field, value):
    kind = field['type']
    nested = kind not in _INT_RANGES and kind not in _FLOATS and \
        kind not in ('bool', 'string', 'wstring')
    cls = message_class(_normalize(kind)) if nested else None
    if 'array_size' in field or field.get('sequence'):
        if isinstance(value, memoryview):
            value = value.tolist()
        if nested:
            return [cls._from_plain(v) for v in value]
        code = _TYPECODES.get(kind)
        if field.get('sequence') and code:
            return array.array(code, value)
        return list(value)
    return cls._from_plain(value) if nested else value


class Message:
    """Base of the generated message classes."""

    __slots__ = ()
    # class data, named so that no field's slot (``_<field>``) can meet them
    _field_specs = ()
    _ros_type = ''

    def __init__(self, **kwargs):
        """Set the fields given, the others to their defaults."""
        names = {f['name'] for f in self._field_specs}
        assert all(k in names for k in kwargs), \
            ('Invalid arguments passed to constructor: '
             f"{', '.join(sorted((k for k in kwargs if k not in names)))}")
        for field in self._field_specs:
            name = field['name']
            if name in kwargs:
                setattr(self, name, kwargs[name])
            else:
                object.__setattr__(self, f'_{name}', _default(field))

    @classmethod
    def get_fields_and_field_types(cls):
        """Return {field name: ROS type} as rosidl_generator_py's classes do."""
        result = {}
        for field in cls._field_specs:
            kind = field['type']
            if field.get('array_size') is not None:
                kind = f"{kind}[{field['array_size']}]"
            elif field.get('sequence'):
                bound = field.get('sequence_bound')
                kind = f"sequence<{kind}{(f', {bound}' if bound else '')}>"
            result[field['name']] = kind
        return result

    def __eq__(self, other):
        """Equal when of the same class with equal fields."""
        if not isinstance(other, self.__class__):
            return False
        return all(getattr(self, f['name']) == getattr(other, f['name'])
                   for f in self._field_specs)

    def __repr__(self):
        """``pkg.msg.Name(field=value, ...)``."""
        module = self.__class__.__module__
        args = ', '.join(f"{f['name']}={getattr(self, f['name'])!r}"
                         for f in self._field_specs)
        return f'{module}.{self.__class__.__name__}({args})'

    def _to_plain(self):
        return {f['name']: _to_plain(f, getattr(self, f"_{f['name']}")) for f in self._field_specs}

    @classmethod
    def _from_plain(cls, plain):
        msg = cls.__new__(cls)
        for field in cls._field_specs:
            object.__setattr__(msg, f"_{field['name']}", _from_plain(field, plain[field['name']]))
        return msg


def _property(field):
    name = field['name']

    def getter(self):
        return getattr(self, f'_{name}')

    def setter(self, value):
        object.__setattr__(self, f'_{name}', _check(field, value))

    return property(getter, setter, doc=f'Message field {name!r}.')


def _compiled_to_plain(fields):
    """
    Message._to_plain written out for one type's fields (it runs once per publish).

    None when a field name is not a Python identifier (Message._to_plain then
    serves).
    """
    parts = []
    for field in fields:
        name, kind = field['name'], field['type']
        if not name.isidentifier():
            return None
        nested = kind not in _INT_RANGES and kind not in _FLOATS and \
            kind not in ('bool', 'string', 'wstring')
        value = f'self._{name}'
        if 'array_size' in field or field.get('sequence'):
            value = f'[v._to_plain() for v in {value}]' if nested else f'list({value})'
        elif nested:
            value = f'{value}._to_plain()'
        parts.append(f'{name!r}: {value}')
    namespace = {}
    exec(f"def _to_plain(self):\n    return {{{', '.join(parts)}}}\n", namespace)  # noqa: S102
    return namespace['_to_plain']


def _make_class(full, description, module):
    pkg, kind, name = full.split('/')
    namespace = {
        '__slots__': tuple(f"_{f['name']}" for f in description['fields']),
        '_field_specs': tuple(description['fields']),
        '_ros_type': full,
        '__module__': module,
        '__doc__': description.get('definition') or f'Message {full}.',
    }
    for field in description['fields']:
        namespace[field['name']] = _property(field)
    to_plain = _compiled_to_plain(description['fields'])
    if to_plain is not None:
        namespace['_to_plain'] = to_plain
    for constant in description.get('constants') or []:
        namespace[constant['name']] = constant['value']
    return type(name, (Message,), namespace)


def message_class(full):
    """Return the class of a message type ``pkg/msg/Name`` (made once)."""
    full = _normalize(full)
    cls = _classes.get(full)
    if cls is None:
        description = _descriptions.get('messages', {}).get(full)
        if description is None:
            pkg = full.split('/')[0]
            hint = (f"package '{pkg}' has type descriptions, but not this message"
                    if pkg in packages() else
                    f"no types.json of package '{pkg}' is loaded: build '{pkg}' with colcon "
                    'build --wasm into this install space')
            raise ImportError(f'unknown message type {full!r}: {hint}')
        pkg, kind, name = full.split('/')
        cls = _make_class(full, description, f'{pkg}.{kind}')
        _classes[full] = cls
    return cls


def service_class(full):
    """Return the class of a service type ``pkg/srv/Name``: its Request and Response."""
    cls = _classes.get(full)
    if cls is None:
        description = _descriptions.get('services', {}).get(full)
        if description is None:
            raise ImportError(f'unknown service type {full!r}: build its package with colcon '
                              'build --wasm into this install space')
        cls = _service(full, description['request'], description['response'],
                       description.get('definition'))
    return cls


def _service(full, request, response, definition=None):
    pkg, kind, name = full.split('/')
    cls = type(name, (), {
        'Request': message_class(request),
        'Response': message_class(response),
        '_ros_type': full,
        '__module__': f'{pkg}.{kind}',
        '__doc__': definition or f'Service {full}.',
    })
    _classes[full] = cls
    return cls


def action_class(full):
    """
    Return the class of an action type ``pkg/action/Name``, as rosidl_generator_py's.

    ``Goal``, ``Result`` and ``Feedback``, and ``Impl``: the services and
    messages rcl_action puts on the wire (``SendGoalService``,
    ``GetResultService``, ``FeedbackMessage``, ``CancelGoalService``,
    ``GoalStatusMessage``).
    """
    cls = _classes.get(full)
    if cls is None:
        description = _descriptions.get('actions', {}).get(full)
        if description is None:
            raise ImportError(f'unknown action type {full!r}: build its package with colcon '
                              'build --wasm into this install space')
        pkg, kind, name = full.split('/')
        send_goal, get_result = description['send_goal'], description['get_result']
        impl = type('Impl', (), {
            'SendGoalService': _service(f'{full}_SendGoal', send_goal['request'],
                                        send_goal['response']),
            'GetResultService': _service(f'{full}_GetResult', get_result['request'],
                                         get_result['response']),
            'FeedbackMessage': message_class(description['feedback_message']),
            'CancelGoalService': service_class('action_msgs/srv/CancelGoal'),
            'GoalStatusMessage': message_class('action_msgs/msg/GoalStatusArray'),
        })
        cls = type(name, (), {
            'Goal': message_class(description['goal']),
            'Result': message_class(description['result']),
            'Feedback': message_class(description['feedback']),
            'Impl': impl,
            '_ros_type': full,
            '__module__': f'{pkg}.{kind}',
            '__doc__': description.get('definition') or f'Action {full}.',
        })
        _classes[full] = cls
    return cls


def type_name(msg_type):
    """Return the ROS type name of a generated message or service class."""
    name = getattr(msg_type, '_ros_type', None)
    if not name:
        raise TypeError(f'{msg_type!r} is not a message or service class of this rclpy (import '
                        'it from <package>.msg or <package>.srv)')
    return name


class _InterfaceFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Creates ``<pkg>`` and ``<pkg>.msg`` modules of the described packages."""

    def find_spec(self, fullname, path=None, target=None):  # noqa: D102
        parts = fullname.split('.')
        if parts[0] not in packages() or len(parts) > 2:
            return None
        if len(parts) == 2 and parts[1] not in ('msg', 'srv', 'action'):
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=len(parts) == 1)

    def create_module(self, spec):  # noqa: D102
        module = types.ModuleType(spec.name)
        parts = spec.name.split('.')
        if len(parts) == 1:
            module.__path__ = []
            return module
        pkg, kind = parts
        prefix = f'{pkg}/{kind}/'
        table = _descriptions.get('messages', {}) if kind in ('msg', 'srv') else {}
        for full in sorted(table):
            if full.startswith(prefix):
                setattr(module, full[len(prefix):], message_class(full))
        if kind == 'srv':
            for full in sorted(_descriptions.get('services', {})):
                if full.startswith(prefix):
                    setattr(module, full[len(prefix):], service_class(full))
        if kind == 'action':
            for full in sorted(_descriptions.get('actions', {})):
                if full.startswith(prefix):
                    setattr(module, full[len(prefix):], action_class(full))
        return module

    def exec_module(self, module):  # noqa: D102
        pass


def install_finder():
    """Put the finder last on sys.meta_path (once)."""
    if not any(isinstance(f, _InterfaceFinder) for f in sys.meta_path):
        sys.meta_path.append(_InterfaceFinder())
