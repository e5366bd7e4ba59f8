# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.duration: a span of time in nanoseconds, as rclpy's Duration."""

from rclpy import _messages

_NS = 10 ** 9


class Duration:
    """A span of time (nanoseconds, may be negative)."""

    def __init__(self, *, seconds=0, nanoseconds=0):
        """Create ``seconds`` (int or float) plus ``nanoseconds``."""
        total = int(seconds * _NS) + int(nanoseconds)
        # rcl_duration_value_t is an int64
        if not -2 ** 63 <= total < 2 ** 63:
            raise OverflowError(f'Total nanoseconds value is too large to store in C duration: '
                                f'{total}')
        self._nanoseconds = total

    @property
    def nanoseconds(self):
        """Return the span in nanoseconds."""
        return self._nanoseconds

    def __repr__(self):  # noqa: D105
        return f'Duration(nanoseconds={self._nanoseconds})'

    def __str__(self):  # noqa: D105
        return f'{self._nanoseconds} nanoseconds'

    def _other(self, other):
        if not isinstance(other, Duration):
            raise TypeError(f"Can't compare duration with object of type: {type(other)}")
        return other._nanoseconds

    def __eq__(self, other):  # noqa: D105
        if isinstance(other, Duration):
            return self._nanoseconds == other._nanoseconds
        raise TypeError(f"Can't compare duration with object of type: {type(other)}")

    def __ne__(self, other):  # noqa: D105
        return not self.__eq__(other)

    def __lt__(self, other):  # noqa: D105
        return self._nanoseconds < self._other(other)

    def __le__(self, other):  # noqa: D105
        return self._nanoseconds <= self._other(other)

    def __gt__(self, other):  # noqa: D105
        return self._nanoseconds > self._other(other)

    def __ge__(self, other):  # noqa: D105
        return self._nanoseconds >= self._other(other)

    def __hash__(self):  # noqa: D105
        return hash(self._nanoseconds)

    def to_msg(self):
        """Return a builtin_interfaces/msg/Duration (nanosec in [0, 1e9), sec floored)."""
        sec, nanosec = divmod(self._nanoseconds, _NS)
        return _messages.message_class('builtin_interfaces/msg/Duration')(
            sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg):
        """Make a Duration from a builtin_interfaces/msg/Duration."""
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)
