"""What a thread cannot do here, and an exception in a spin thread's callback."""

import threading

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


def main():
    rclpy.init()
    node = Node('py_thread_errors')
    try:
        threading.Thread(target=print, args=('never',)).start()
    except RuntimeError as e:
        node.get_logger().info(f'a thread of print: {e}')
    try:
        threading.Event().wait()
    except RuntimeError as e:
        node.get_logger().info(f'Event.wait() with no spin thread: {e}')

    def explode(msg):
        raise ValueError(f'the callback gives up on [{msg.data}]')

    node.create_subscription(Chatter, 'chatter', explode, 10)
    thread = threading.Thread(target=rclpy.spin, args=(node,), name='spinner', daemon=True)
    thread.start()
    thread.join(timeout=60)
    node.get_logger().info(f'the main thread goes on: spin thread alive={thread.is_alive()}')
    rclpy.shutdown()


if __name__ == '__main__':
    main()
