# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.exceptions: the exceptions this rclpy raises, with rclpy's names and texts."""


class NotInitializedException(Exception):
    """rclpy was used before ``rclpy.init()`` (or after its shutdown)."""

    def __init__(self, *args):
        """Say that init has not been called."""
        super().__init__('rclpy.init() has not been called', *args)


class ROSInterruptException(Exception):
    """An operation (a Rate's sleep) ended by rclpy's shutdown."""

    def __init__(self, *args):
        """Say that shutdown has been called."""
        super().__init__('rclpy.shutdown() has been called', *args)


class ParameterException(Exception):
    """A parameter operation refused."""

    def __init__(self, error_msg, parameters, *args):
        """Give the reason and the parameter(s)."""
        super().__init__(f'{error_msg}: {parameters}', *args)


class ParameterNotDeclaredException(ParameterException):
    """A parameter that was not declared (and undeclared ones are not allowed)."""

    def __init__(self, parameters, *args):
        """Name the parameter(s)."""
        Exception.__init__(self, 'Invalid access to undeclared parameter(s)', parameters, *args)


class ParameterAlreadyDeclaredException(ParameterException):
    """A parameter declared twice."""

    def __init__(self, parameters, *args):
        """Name the parameter(s)."""
        Exception.__init__(self, 'Parameter(s) already declared', parameters, *args)


class InvalidParameterValueException(ParameterException):
    """A parameter value that a set-parameters callback refused."""

    def __init__(self, parameter, value, reason, *args):
        """Name the parameter, the value and the reason."""
        Exception.__init__(
            self, f'Invalid parameter value ({value}) for parameter. Reason: {reason}',
            parameter, *args)


class NameValidationException(Exception):
    """Raised when a topic name, node name, or namespace are invalid."""

    def __init__(self, name_type, name, error_msg, invalid_index, *args):
        """Say what is wrong, and point at it as rclpy does."""
        msg = (f'Invalid {name_type}: {error_msg}:\n'
               f"  '{name}'\n"
               f"   {' ' * invalid_index}^")
        Exception.__init__(self, msg)


class InvalidNamespaceException(NameValidationException):
    """Raised when a namespace is invalid."""

    def __init__(self, name, error_msg, invalid_index, *args):  # noqa: D107
        NameValidationException.__init__(self, 'namespace', name, error_msg, invalid_index)


class InvalidNodeNameException(NameValidationException):
    """Raised when a node name is invalid."""

    def __init__(self, name, error_msg, invalid_index, *args):  # noqa: D107
        NameValidationException.__init__(self, 'node name', name, error_msg, invalid_index)


class InvalidTopicNameException(NameValidationException):
    """Raised when a topic name is invalid."""

    def __init__(self, name, error_msg, invalid_index, *args):  # noqa: D107
        NameValidationException.__init__(self, 'topic name', name, error_msg, invalid_index)


class InvalidServiceNameException(NameValidationException):
    """Raised when a service name is invalid."""

    def __init__(self, name, error_msg, invalid_index, *args):  # noqa: D107
        NameValidationException.__init__(self, 'service name', name, error_msg, invalid_index)
