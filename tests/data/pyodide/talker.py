"""A Python talker: demo_interfaces/msg/Chatter on /chatter, like the C++ demo talker."""

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


class Talker(Node):

    def __init__(self):
        super().__init__('py_talker')
        self.publisher = self.create_publisher(Chatter, 'chatter', 10)
        self.count = 0
        self.create_timer(0.2, self.tick)

    def tick(self):
        self.count += 1
        msg = Chatter(data=f'Hello from Python: {self.count}', count=self.count)
        self.get_logger().info(f'Publishing: "{msg.data}"')
        self.publisher.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Talker())


if __name__ == '__main__':
    main()
