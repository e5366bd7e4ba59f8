"""spin_once runs one callback per call, in rclpy's order, with messages of the C++ talker."""

import time

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


def main():
    rclpy.init()
    node = Node('py_spin_once')
    calls = []
    node.create_timer(0.2, lambda: calls.append('timer'))
    node.create_subscription(Chatter, 'chatter', lambda msg: calls.append('A'), 10)
    node.create_subscription(Chatter, 'chatter', lambda msg: calls.append('B'), 10)
    guard = node.create_guard_condition(lambda: calls.append('guard'))
    # until the C++ talker's messages arrive (bounded)
    for _ in range(300):
        rclpy.spin_once(node, timeout_sec=0.1)
        if 'A' in calls and 'B' in calls:
            break
    assert 'A' in calls and 'B' in calls, calls
    # now a message waits on each subscription, the timer is due and the guard triggered
    time.sleep(1.0)
    guard.trigger()
    calls.clear()
    for n in range(1, 5):
        rclpy.spin_once(node, timeout_sec=0)
        node.get_logger().info(f'after {n} spin_once: {calls}')
    # one message per subscription and wait: the next wait takes the next message
    calls.clear()
    rclpy.spin_once(node, timeout_sec=0)
    rclpy.spin_once(node, timeout_sec=0)
    node.get_logger().info(f'the next wait: {calls}')
    rclpy.shutdown()


if __name__ == '__main__':
    main()
