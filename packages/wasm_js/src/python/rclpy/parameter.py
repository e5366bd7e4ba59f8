# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Parameters of a node (rclpy.parameter.Parameter); parameter_service.py serves them."""

import array
import enum


class Parameter:
    """A named value with its type."""

    class Type(enum.IntEnum):
        """Parameter types, with rcl_interfaces' values."""

        NOT_SET = 0
        BOOL = 1
        INTEGER = 2
        DOUBLE = 3
        STRING = 4
        BYTE_ARRAY = 5
        BOOL_ARRAY = 6
        INTEGER_ARRAY = 7
        DOUBLE_ARRAY = 8
        STRING_ARRAY = 9

        @classmethod
        def from_parameter_value(cls, value):
            """Return the type of a Python value, as rclpy does."""
            if value is None:
                return cls.NOT_SET
            if isinstance(value, bool):
                return cls.BOOL
            if isinstance(value, int):
                return cls.INTEGER
            if isinstance(value, float):
                return cls.DOUBLE
            if isinstance(value, str):
                return cls.STRING
            if isinstance(value, (bytes, bytearray)):
                return cls.BYTE_ARRAY
            if isinstance(value, (list, tuple)):
                if all(isinstance(v, bool) for v in value):
                    return cls.BOOL_ARRAY
                if all(isinstance(v, int) for v in value):
                    return cls.INTEGER_ARRAY
                if all(isinstance(v, float) for v in value):
                    return cls.DOUBLE_ARRAY
                if all(isinstance(v, str) for v in value):
                    return cls.STRING_ARRAY
            raise TypeError(f"The given value is not one of the allowed types '{value}'.")

        def check(self, parameter_value):
            """Tell whether a Python value is of this type, as rclpy's ``Type.check``."""
            arrays = (list, tuple, array.array)
            checks = {
                Parameter.Type.NOT_SET: lambda v: v is None,
                Parameter.Type.BOOL: lambda v: isinstance(v, bool),
                Parameter.Type.INTEGER: lambda v: isinstance(v, int),
                Parameter.Type.DOUBLE: lambda v: isinstance(v, float),
                Parameter.Type.STRING: lambda v: isinstance(v, str),
                Parameter.Type.BYTE_ARRAY: lambda v: isinstance(v, (list, tuple)) and all(
                    isinstance(x, bytes) and len(x) == 1 for x in v),
                Parameter.Type.BOOL_ARRAY: lambda v: isinstance(v, (list, tuple)) and all(
                    isinstance(x, bool) for x in v),
                Parameter.Type.INTEGER_ARRAY: lambda v: isinstance(v, arrays) and all(
                    isinstance(x, int) for x in v),
                Parameter.Type.DOUBLE_ARRAY: lambda v: isinstance(v, arrays) and all(
                    isinstance(x, float) for x in v),
                Parameter.Type.STRING_ARRAY: lambda v: isinstance(v, (list, tuple)) and all(
                    isinstance(x, str) for x in v),
            }
            return checks[self](parameter_value)

    def __init__(self, name, type_=None, value=None):
        """Create a parameter; ``type_`` defaults to the value's."""
        if type_ is None:
            type_ = Parameter.Type.from_parameter_value(value)
        self._name = name
        self._type = Parameter.Type(type_)
        self._value = value

    @property
    def name(self):
        """Return the name."""
        return self._name

    @property
    def type_(self):
        """Return the type."""
        return self._type

    @property
    def value(self):
        """Return the value."""
        return self._value

    def __repr__(self):
        """Show name, type and value."""
        return f'Parameter({self._name!r}, {self._type.name}, {self._value!r})'

    def get_parameter_value(self):
        """Return the value as an rcl_interfaces/msg/ParameterValue."""
        from rclpy.parameter_service import to_value_msg
        return to_value_msg(self)

    def to_parameter_msg(self):
        """Return the parameter as an rcl_interfaces/msg/Parameter."""
        from rclpy import _messages
        cls = _messages.message_class('rcl_interfaces/msg/Parameter')
        return cls(name=self.name, value=self.get_parameter_value())


class SetParametersResult:
    """What a parameter callback says (rcl_interfaces/msg/SetParametersResult)."""

    def __init__(self, successful=False, reason=''):
        """Create a result."""
        self.successful = successful
        self.reason = reason


def parse_value(text):
    """Parse the value of ``-p name:=value`` (the scalars YAML gives: bool, int, float, str)."""
    lowered = text.strip().lower()
    if lowered in ('true', 'yes', 'on'):
        return True
    if lowered in ('false', 'no', 'off'):
        return False
    for convert in (int, float):
        try:
            return convert(text)
        except ValueError:
            pass
    if len(text) >= 2 and text[0] == text[-1] and text[0] in '\'"':
        return text[1:-1]
    return text
