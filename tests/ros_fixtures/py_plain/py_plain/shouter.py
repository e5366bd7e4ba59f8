"""A talker of demo_interfaces/msg/Chatter on chatter, from a plain Python package."""

from demo_interfaces.msg import Chatter
import rclpy
from rclpy.node import Node


def main(args=None):
    rclpy.init(args=args)
    node = Node('py_plain_shouter')
    publisher = node.create_publisher(Chatter, 'chatter', 10)
    count = [0]

    def tick():
        count[0] += 1
        msg = Chatter(data=f'SHOUTED FROM A PLAIN PACKAGE: {count[0]}', count=count[0])
        node.get_logger().info(f'Publishing: "{msg.data}"')
        publisher.publish(msg)

    node.create_timer(0.2, tick)
    rclpy.spin(node)
