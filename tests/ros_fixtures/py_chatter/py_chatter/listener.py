"""A listener of demo_interfaces/msg/Chatter on chatter."""

from demo_interfaces.msg import Chatter
import rclpy
from rclpy.node import Node


class Listener(Node):

    def __init__(self):
        super().__init__('py_package_listener')
        self.create_subscription(Chatter, 'chatter', self.heard, 10)

    def heard(self, msg):
        self.get_logger().info(f'I heard: [{msg.data}] count={msg.count}')


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(Listener())
