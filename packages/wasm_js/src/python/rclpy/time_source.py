# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.time_source: ``use_sim_time`` and ``/clock``, as rclpy's TimeSource.

Every node declares ``use_sim_time`` (false unless overridden, ``-p
use_sim_time:=true``). While it is true, the node subscribes to ``/clock``
(rosgraph_msgs/msg/Clock, depth 1, best effort, as rclpy) and its ROS
clock reads the last time received; setting it false goes back to the
system time. The messages arrive while the node spins, like any others;
a sleep on the clock (``Clock.sleep_until``, ``Rate.sleep``) outside of a
spin takes them itself, as rclpy's executor thread would.
"""

from rclpy.clock import ROSClock
from rclpy.parameter import SetParametersResult
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy

CLOCK_TOPIC = '/clock'
USE_SIM_TIME = 'use_sim_time'


class TimeSource:
    """Drives a node's ROS clock from ``/clock`` while ``use_sim_time`` is true."""

    def __init__(self, node):
        """Declare ``use_sim_time`` on the node and follow it."""
        self._node = node
        self._subscription = None
        self._clock = node.get_clock()
        if not isinstance(self._clock, ROSClock):
            raise TypeError('the time source drives a ROSClock')
        self._clock._clock_waiter = self._wait_for_clock
        node.add_on_set_parameters_callback(self._on_parameters)
        # the callback refuses an override that is no boolean (declare_parameter raises)
        self._follow(node.declare_parameter(USE_SIM_TIME, False).value)

    def _on_parameters(self, parameters):
        for parameter in parameters:
            if parameter.name != USE_SIM_TIME:
                continue
            if not isinstance(parameter.value, bool):
                return SetParametersResult(successful=False,
                                           reason='use_sim_time parameter must be a boolean')
            self._follow(parameter.value)
        return SetParametersResult(successful=True)

    def _follow(self, active):
        if active and self._subscription is None:
            from rosgraph_msgs.msg import Clock
            self._subscription = self._node.create_subscription(
                Clock, CLOCK_TOPIC, self._on_clock,
                QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT))
        elif not active and self._subscription is not None:
            self._node.destroy_subscription(self._subscription)
            self._subscription = None
        self._clock._set_ros_time_is_active(active)

    def _on_clock(self, msg):
        self._clock._set_ros_time(msg.clock.sec * 10 ** 9 + msg.clock.nanosec)

    def _wait_for_clock(self):
        """Wait (at most 0.1 s) for ``/clock`` messages and apply them."""
        from rclpy import executors
        subscription = self._subscription
        if executors.sleep_spins() or subscription is None or subscription._handle is None:
            # a MultiThreadedExecutor's callback: its spin takes /clock with the rest
            executors.wait_a_while(0.1)
            return
        executors.wait_for(subscription, 0.1)
        msg = subscription._take()
        while msg is not None:
            self._on_clock(msg)
            msg = subscription._take()
