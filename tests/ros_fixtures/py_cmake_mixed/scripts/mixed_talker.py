#!/usr/bin/env python3
"""A talker installed by CMake (install(PROGRAMS)), using its package's module."""

from py_cmake_mixed import shout
import rclpy
from std_msgs.msg import String


def main():
    rclpy.init()
    node = rclpy.create_node('mixed_talker')
    publisher = node.create_publisher(String, 'topic', 10)
    count = [0]

    def tick():
        count[0] += 1
        node.get_logger().info(f'Publishing: "{shout(count[0])}"')
        publisher.publish(String(data=shout(count[0])))

    node.create_timer(0.2, tick)
    rclpy.spin(node)


if __name__ == '__main__':
    main()
