"""use_sim_time: a node's ROS clock and timers follow /clock while use_sim_time is true."""

import time

import rclpy
from rclpy.clock import ClockType
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter
from rclpy.time import Time

from builtin_interfaces.msg import Time as TimeMsg
from rosgraph_msgs.msg import Clock

rclpy.init(args=['sim_time.py', '--ros-args', '-p', 'sim:use_sim_time:=true'])
sim = Node('sim')
wall = Node('wall')
assert sim.get_parameter('use_sim_time').value is True
assert sim.get_clock().ros_time_is_active
assert wall.get_parameter('use_sim_time').value is False
assert not wall.get_clock().ros_time_is_active
# no /clock yet: ROS time is zero, as rclpy's
assert sim.get_clock().now() == Time(nanoseconds=0, clock_type=ClockType.ROS_TIME)

executor = SingleThreadedExecutor()
executor.add_node(sim)
executor.add_node(wall)
# a timer of the sim node counts ROS time: it fires as /clock advances, 3 s of /clock apart
fired = []
sim.create_timer(3.0, lambda: fired.append(sim.get_clock().now().nanoseconds // 10 ** 9))
clock = wall.create_publisher(Clock, '/clock', 10)
deadline = time.monotonic() + 30
while not clock.get_subscription_count() and time.monotonic() < deadline:
    executor.spin_once(timeout_sec=0.1)
assert clock.get_subscription_count() == 1, 'the sim node does not subscribe to /clock'
for sec in range(1000, 1010):
    clock.publish(Clock(clock=TimeMsg(sec=sec, nanosec=500)))
    executor.spin_once(timeout_sec=0.5)
deadline = time.monotonic() + 10
want = Time(seconds=1009, nanoseconds=500, clock_type=ClockType.ROS_TIME)
# one callback per spin_once, as rclpy's: the timer due at the last /clock fires at the wait after
while (sim.get_clock().now() != want or len(fired) < 4) and time.monotonic() < deadline:
    executor.spin_once(timeout_sec=0.1)
assert sim.get_clock().now() == want, sim.get_clock().now()
# due at ROS time 3 s (created before any /clock): the first /clock fires it, then 3 s apart
assert fired == [1000, 1003, 1006, 1009], fired
assert abs(wall.get_clock().now().nanoseconds - time.time_ns()) < 5 * 10 ** 9
assert ('/clock', ['rosgraph_msgs/msg/Clock']) in \
    sim.get_subscriber_names_and_types_by_node('sim', '/')

# a value that is no boolean is refused; false goes back to the system time
(refused,) = sim.set_parameters([Parameter('use_sim_time', value='yes')])
assert not refused.successful and 'use_sim_time parameter must be a boolean' in refused.reason
assert sim.get_clock().ros_time_is_active
(done,) = sim.set_parameters([Parameter('use_sim_time', value=False)])
assert done.successful and not sim.get_clock().ros_time_is_active
assert abs(sim.get_clock().now().nanoseconds - time.time_ns()) < 5 * 10 ** 9
assert not sim.get_subscriber_names_and_types_by_node('sim', '/')
sim.get_logger().info('sim time follows /clock')
rclpy.shutdown()
