"""A Python node whose timer callback raises after a second."""

import rclpy
from rclpy.node import Node


def explode():
    raise ValueError('the Python crasher gives up')


rclpy.init()
node = Node('py_crasher')
node.create_timer(1.0, explode)
rclpy.spin(node)
