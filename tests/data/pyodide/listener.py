"""A Python listener of /chatter (demo_interfaces/msg/Chatter)."""

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


def main():
    rclpy.init()
    node = Node('py_listener')

    def heard(msg):
        node.get_logger().info(f'I heard: [{msg.data}] count={msg.count}')

    node.create_subscription(Chatter, 'chatter', heard, 10)
    rclpy.spin(node)


main()
