"""Two spin threads (an executor's spin, no daemon; spin_until_future_complete) and a service."""

import threading
import time

import rclpy
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node

from demo_interfaces.srv import AddTwoInts


def main():
    rclpy.init()
    node = Node('py_thread_client')
    executor = MultiThreadedExecutor()
    executor.add_node(node)
    ticks = []

    def tick():
        ticks.append(len(ticks) + 1)
        node.get_logger().info(f'timer tick {len(ticks)}')
        if len(ticks) == 3:
            node.get_logger().info('the timer shuts rclpy down')
            rclpy.shutdown()

    thread = threading.Thread(target=executor.spin)  # no daemon: Python waits for it
    thread.start()
    client = node.create_client(AddTwoInts, 'add_two_ints')
    if not client.wait_for_service(timeout_sec=60.0):
        raise RuntimeError('no server on /add_two_ints')
    # a future completed by the spin thread while the main thread sleeps
    future = client.call_async(AddTwoInts.Request(a=2, b=3))
    while not future.done():
        time.sleep(0.05)
    node.get_logger().info(f'call_async while sleeping: 2 + 3 = {future.result().sum}')
    # the synchronous call, as with rclpy's spin thread
    response = client.call(AddTwoInts.Request(a=40, b=2))
    node.get_logger().info(f'call: 40 + 2 = {response.sum}')
    # a second spin thread: rclpy.spin_until_future_complete of another node, joined
    other = Node('py_future_node')
    other_client = other.create_client(AddTwoInts, 'add_two_ints')
    other_future = other_client.call_async(AddTwoInts.Request(a=100, b=23))
    waiter = threading.Thread(target=rclpy.spin_until_future_complete,
                              args=(other, other_future), kwargs={'timeout_sec': 60.0})
    waiter.start()
    waiter.join()
    node.get_logger().info(f'spin_until_future_complete thread: 100 + 23 = '
                           f'{other_future.result().sum}, alive={waiter.is_alive()}')
    node.create_timer(0.2, tick)
    node.get_logger().info('main returns; the spin thread goes on')


if __name__ == '__main__':
    main()
