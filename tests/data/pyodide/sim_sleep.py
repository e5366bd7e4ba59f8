"""Sleeps on a clock: Clock.sleep_for / sleep_until and Rate, on the steady and the ROS clock."""

import time

import rclpy
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.duration import Duration
from rclpy.node import Node

rclpy.init(args=['sim_sleep.py', '--ros-args', '-p', 'use_sim_time:=true'])
steady = Clock(clock_type=ClockType.STEADY_TIME)
start = steady.now()
assert steady.sleep_for(Duration(seconds=0.3))
assert steady.now() - start >= Duration(seconds=0.3)
try:
    steady.sleep_until(Clock().now())
except ValueError as e:
    assert "until's clock type does not match" in str(e), e
else:
    raise SystemExit('a Time of another clock type must be refused')

node = Node('sleeper')
clock = node.get_clock()
assert clock.ros_time_is_active
# wait for the first /clock (ROS time is zero before it)
while clock.now().nanoseconds == 0:
    rclpy.spin_once(node, timeout_sec=0.1)
# 60 s of /clock pass in about 0.6 s: the sleep counts /clock, not the wall (it takes
# the /clock messages itself, nobody spins)
wall, sim = time.monotonic(), clock.now()
assert clock.sleep_for(Duration(seconds=60))
slept = clock.now() - sim
assert slept >= Duration(seconds=60), slept
assert time.monotonic() - wall < 30, time.monotonic() - wall
# a Rate of the node counts its ROS clock: 3 periods of 20 s of /clock
rate = node.create_rate(0.05)
sim = clock.now()
for _ in range(3):
    rate.sleep()
assert clock.now() - sim >= Duration(seconds=40), clock.now() - sim
assert time.monotonic() - wall < 60, time.monotonic() - wall
node.get_logger().info(f'slept on /clock: {slept.nanoseconds // 10 ** 9} s')
rclpy.shutdown()
try:
    rate.sleep()
except rclpy.exceptions.ROSInterruptException:
    pass
else:
    raise SystemExit('a Rate must refuse to sleep after shutdown')
