# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.clock: the clock types and clocks, as rclpy's."""

import enum
import time as _time


class ClockType(enum.IntEnum):
    """rcl_clock_type_t."""

    UNINITIALIZED = 0
    ROS_TIME = 1
    SYSTEM_TIME = 2
    STEADY_TIME = 3


class Clock:
    """A clock of one type: ``now()`` reads it."""

    def __init__(self, *, clock_type=ClockType.SYSTEM_TIME):
        """Create a clock (ROS_TIME, SYSTEM_TIME or STEADY_TIME)."""
        if not isinstance(clock_type, ClockType):
            raise TypeError('Clock type must be a ClockType enum')
        if clock_type == ClockType.UNINITIALIZED:
            raise ValueError('Clock type must not be UNINITIALIZED')
        self._clock_type = clock_type

    @property
    def clock_type(self):
        """Return the clock's type."""
        return self._clock_type

    def __repr__(self):  # noqa: D105
        return f'Clock(clock_type={self._clock_type.name})'

    def now(self):
        """Return the current time of this clock (an rclpy.time.Time)."""
        from rclpy.time import Time
        if self._clock_type == ClockType.STEADY_TIME:
            ns = _time.monotonic_ns()
        else:
            ns = _time.time_ns()
        return Time(nanoseconds=ns, clock_type=self._clock_type)


class ROSClock(Clock):
    """
    The ROS time clock of a node.

    Simulated time (``use_sim_time`` and ``/clock``) is not followed yet:
    ``ros_time_is_active`` is False and ``now()`` is the system time, as in
    rclpy while no /clock has been received.
    """

    def __init__(self):
        """Create a ROS_TIME clock."""
        super().__init__(clock_type=ClockType.ROS_TIME)

    @property
    def ros_time_is_active(self):
        """Return whether simulated time is in use (never, yet)."""
        return False
