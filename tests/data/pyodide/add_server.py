"""A Python AddTwoInts server on /add_two_ints."""

import rclpy
from rclpy.node import Node

from demo_interfaces.srv import AddTwoInts


def main():
    rclpy.init()
    node = Node('py_server')

    def add(request, response):
        response.sum = request.a + request.b
        node.get_logger().info(f'Incoming request: a: {request.a} b: {request.b}')
        return response

    node.create_service(AddTwoInts, 'add_two_ints', add)
    rclpy.spin(node)


main()
