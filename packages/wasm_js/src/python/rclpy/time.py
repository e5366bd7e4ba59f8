# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.time: a point in time of one clock type, as rclpy's Time."""

from rclpy import _messages
from rclpy.clock import ClockType
from rclpy.duration import Duration

_NS = 10 ** 9


class Time:
    """A point in time (nanoseconds since the clock's epoch) of a clock type."""

    def __init__(self, *, seconds=0, nanoseconds=0, clock_type=ClockType.SYSTEM_TIME):
        """Create a time; neither part may be negative."""
        if not isinstance(clock_type, ClockType):
            raise TypeError('Clock type must be a ClockType enum')
        if seconds < 0:
            raise ValueError('Seconds value must not be negative')
        if nanoseconds < 0:
            raise ValueError('Nanoseconds value must not be negative')
        total = int(seconds * _NS) + int(nanoseconds)
        if total >= 2 ** 63:
            raise OverflowError(f'Total nanoseconds value is too large to store in C time point: '
                                f'{total}')
        self._nanoseconds = total
        self._clock_type = clock_type

    @property
    def nanoseconds(self):
        """Return the time in nanoseconds."""
        return self._nanoseconds

    @property
    def clock_type(self):
        """Return the clock type."""
        return self._clock_type

    def seconds_nanoseconds(self):
        """Return ``(seconds, nanoseconds)``, nanoseconds in [0, 1e9)."""
        return divmod(self._nanoseconds, _NS)

    def __repr__(self):  # noqa: D105
        return f'Time(nanoseconds={self._nanoseconds}, clock_type={self._clock_type.name})'

    def __add__(self, other):  # noqa: D105
        if isinstance(other, Duration):
            return Time(nanoseconds=self._nanoseconds + other.nanoseconds,
                        clock_type=self._clock_type)
        return NotImplemented

    def __radd__(self, other):  # noqa: D105
        return self.__add__(other)

    def __sub__(self, other):  # noqa: D105
        if isinstance(other, Time):
            if other._clock_type != self._clock_type:
                raise TypeError("Can't subtract times with different clock types")
            return Duration(nanoseconds=self._nanoseconds - other._nanoseconds)
        if isinstance(other, Duration):
            return Time(nanoseconds=self._nanoseconds - other.nanoseconds,
                        clock_type=self._clock_type)
        return NotImplemented

    def _other(self, other):
        if not isinstance(other, Time):
            raise TypeError(f"Can't compare time with object of type: {type(other)}")
        if other._clock_type != self._clock_type:
            raise TypeError("Can't compare times with different clock types")
        return other._nanoseconds

    def __eq__(self, other):  # noqa: D105
        return self._nanoseconds == self._other(other)

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
        return hash((self._nanoseconds, self._clock_type))

    def to_msg(self):
        """Return a builtin_interfaces/msg/Time."""
        sec, nanosec = self.seconds_nanoseconds()
        return _messages.message_class('builtin_interfaces/msg/Time')(sec=sec, nanosec=nanosec)

    @classmethod
    def from_msg(cls, msg, clock_type=ClockType.ROS_TIME):
        """Make a Time from a builtin_interfaces/msg/Time."""
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec, clock_type=clock_type)
