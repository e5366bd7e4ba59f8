"""
bench/python: a Python talker for the start-up measure.

Publishes demo_interfaces/msg/Chatter on /chatter every 20 ms and logs
``Publishing: …`` each time, as the C++ demo talker does at ``rate:=50``
beside it in the same launch: the two first messages come one period after
each node's start.
"""

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


def main():
    rclpy.init()
    node = Node('py_first_message')
    publisher = node.create_publisher(Chatter, 'chatter', 10)
    count = [0]

    def tick():
        count[0] += 1
        msg = Chatter(data=f'Hello from Python: {count[0]}', count=count[0])
        node.get_logger().info(f'Publishing: "{msg.data}"')
        publisher.publish(msg)

    node.create_timer(0.02, tick)
    rclpy.spin(node)


main()
