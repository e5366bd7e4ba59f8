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

    def sleep_until(self, until, context=None):
        """
        Sleep until ``until`` (a Time of this clock's type); True when it was reached.

        False when it woke for another reason, as rclpy's: the context
        (default: the default one) was shut down, or simulated time was
        switched on or off (the epoch changed). A ROS clock on simulated
        time sleeps until ``/clock`` reaches ``until``. It waits
        with rclpy.executors.wait_a_while: in a MultiThreadedExecutor's
        callback, the other callbacks run meanwhile.
        """
        from rclpy.context import default_context
        from rclpy.exceptions import NotInitializedException
        context = context or default_context()
        if not context.ok():
            raise NotInitializedException()
        if until.clock_type != self._clock_type:
            raise ValueError("until's clock type does not match this clock's type")
        simulated = self._simulated()
        while True:
            if not context.ok() or self._simulated() != simulated:
                return False
            left = (until - self.now()).nanoseconds / 1e9
            if left <= 0:
                return True
            self._wait(left)

    def sleep_for(self, rel_time, context=None):
        """Sleep for ``rel_time`` (a Duration): ``sleep_until(now() + rel_time, context)``."""
        return self.sleep_until(self.now() + rel_time, context)

    def _simulated(self):
        """Return True while the clock counts simulated time (a ROS clock on /clock)."""
        return False

    def _wait(self, seconds):
        """Wait for time to pass, at most ``seconds`` (sleep_until checks what woke it)."""
        from rclpy.executors import wait_a_while
        wait_a_while(seconds)


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

    def _simulated(self):
        return self._ros_time_is_active

    def _wait(self, seconds):
        """Wait for time to pass; on simulated time, for /clock (its time source)."""
        waiter = getattr(self, '_clock_waiter', None)
        if self._ros_time_is_active and waiter is not None:
            waiter()
        else:
            super()._wait(seconds)

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
