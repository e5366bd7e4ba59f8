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

    While simulated time is active (the node's ``use_sim_time`` is true,
    rclpy/time_source.py), ``now()`` is the time of the last ``/clock``
    message (zero before the first one, as rclpy's); otherwise the system
    time.
    """

    def __init__(self):
        """Create a ROS_TIME clock."""
        super().__init__(clock_type=ClockType.ROS_TIME)
        self._ros_time_is_active = False
        self._ros_time_ns = 0

    @property
    def ros_time_is_active(self):
        """Return whether simulated time (``/clock``) is in use."""
        return self._ros_time_is_active

    def _set_ros_time_is_active(self, active):
        self._ros_time_is_active = bool(active)

    def _set_ros_time(self, nanoseconds):
        self._ros_time_ns = int(nanoseconds)

    def now(self):
        """Return the simulated time while it is active, else the system time."""
        if self._ros_time_is_active:
            from rclpy.time import Time
            return Time(nanoseconds=self._ros_time_ns, clock_type=ClockType.ROS_TIME)
        return super().now()
