"""A node whose timer raises: its traceback, then it dies as with ros2 run."""

import rclpy
from rclpy.node import Node


def explode():
    raise RuntimeError('the packaged crasher gives up')


def main(args=None):
    rclpy.init(args=args)
    node = Node('py_package_crasher')
    node.create_timer(0.5, explode)
    rclpy.spin(node)
