"""A Python talker set up by its arguments: its own (argparse) and the ROS ones (-p, -r)."""

import argparse
import time

import rclpy
from rclpy.node import Node
from rclpy.utilities import remove_ros_args

from demo_interfaces.msg import Chatter


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--count', type=int, default=1)
    args = parser.parse_args(remove_ros_args()[1:])
    rclpy.init()
    node = Node('py_args_talker')
    greeting = node.declare_parameter('greeting', 'Hello').value
    publisher = node.create_publisher(Chatter, 'talk', 10)
    node.get_logger().info(f'{node.get_fully_qualified_name()} on {publisher.topic_name}: '
                           f'count={args.count} greeting={greeting}')
    deadline = time.monotonic() + 10
    while not publisher.get_subscription_count() and time.monotonic() < deadline:
        time.sleep(0.05)
    for i in range(1, args.count + 1):
        publisher.publish(Chatter(data=f'{greeting} {i}', count=i))
        time.sleep(0.1)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
