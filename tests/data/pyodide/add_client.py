"""A Python AddTwoInts client of /cpp_add_two_ints: three calls, a synchronous one, a Rate."""

import sys
import time

import rclpy
from rclpy.node import Node

from demo_interfaces.srv import AddTwoInts


def main():
    rclpy.init()
    node = Node('py_client')
    client = node.create_client(AddTwoInts, 'cpp_add_two_ints')
    if not client.wait_for_service(timeout_sec=60.0):
        node.get_logger().error('no server on /cpp_add_two_ints')
        sys.exit(3)
    for a in (1, 20, 2 ** 40):
        future = client.call_async(AddTwoInts.Request(a=a, b=2 * a))
        rclpy.spin_until_future_complete(node, future, timeout_sec=10.0)
        if not future.done():
            node.get_logger().error(f'no response for a={a}')
            sys.exit(4)
        node.get_logger().info(f'Result of add_two_ints: for {a} + {2 * a} = '
                               f'{future.result().sum}')
    # the synchronous call spins the node until the response is there
    response = client.call(AddTwoInts.Request(a=7, b=5))
    node.get_logger().info(f'Synchronous call: 7 + 5 = {response.sum}')
    rate = node.create_rate(20)
    start = time.monotonic()
    for _ in range(5):
        rate.sleep()
    node.get_logger().info(f'Rate: 5 periods of 50 ms took {time.monotonic() - start:.3f} s')
    rclpy.shutdown()


main()
