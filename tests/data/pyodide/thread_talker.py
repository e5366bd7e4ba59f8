"""The tutorials' pattern: rclpy.spin in a daemon thread, a main loop that publishes and sleeps."""

import threading
import time

import rclpy
from rclpy.node import Node

from demo_interfaces.msg import Chatter


def main():
    rclpy.init()
    node = Node('py_thread_talker')
    publisher = node.create_publisher(Chatter, 'chatter', 10)
    heard = []

    def on_chatter(msg):
        if msg.data.startswith('Hello World'):  # the C++ talker's
            heard.append(msg.data)
            node.get_logger().info(f'heard while the main thread sleeps: [{msg.data}]')

    node.create_subscription(Chatter, 'chatter', on_chatter, 10)
    thread = threading.Thread(target=rclpy.spin, args=(node,), daemon=True)
    thread.start()
    node.get_logger().info(f'spin thread started: alive={thread.is_alive()}')
    rate = node.create_rate(10)
    count = 0
    # Rate.sleep and time.sleep: the spin thread runs meanwhile
    while rclpy.ok() and len(heard) < 3:
        count += 1
        publisher.publish(Chatter(data=f'Hello from the main thread: {count}', count=count))
        if count % 2:
            rate.sleep()
        else:
            time.sleep(0.1)
    node.get_logger().info(f'main loop done: published {count}, heard {len(heard)}')
    # Event.wait: set by a callback of the spin thread
    event = threading.Event()
    node.create_subscription(Chatter, 'chatter', lambda msg: event.set(), 10)
    node.get_logger().info(f'Event.wait returned {event.wait(timeout=60)}')
    rclpy.shutdown()
    thread.join(timeout=10)
    node.get_logger().info(f'after shutdown and join: alive={thread.is_alive()}')


if __name__ == '__main__':
    main()
