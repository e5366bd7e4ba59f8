"""A talker of demo_interfaces/msg/Chatter on chatter, as the C++ demo talker."""

from demo_interfaces.msg import Chatter
from py_words import greeting
import rclpy
from rclpy.node import Node


class Talker(Node):

    def __init__(self):
        super().__init__('py_package_talker')
        self.publisher = self.create_publisher(Chatter, 'chatter', 10)
        self.count = 0
        self.create_timer(0.2, self.tick)

    def tick(self):
        self.count += 1
        msg = Chatter(data=greeting(self.count), count=self.count)
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.publisher.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    rclpy.spin(Talker())
