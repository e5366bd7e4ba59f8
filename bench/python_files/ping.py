"""
bench/python: Python talker -> C++ listener latency.

Sends std_msgs/String messages of 32 characters on bench/ping, one at a
time, to the probe's C++ echo (``probe bench_pong_string`` of the Humble
build's rmw_wasm_cpp_node_tests), waits for each to come back on bench/pong,
and prints ``RESULT count=N p50_us=… p99_us=… min_us=… max_us=…`` with the
one-way latency (round trip / 2), the line the probe's own C++
``bench_ping_string`` prints, so both are read alike.
"""

import time

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node

from std_msgs.msg import String

COUNT = 2000
WARMUP = 200


def main():
    rclpy.init()
    node = Node('py_bench_ping')
    publisher = node.create_publisher(String, 'bench/ping', 10)
    answer = []
    node.create_subscription(String, 'bench/pong', lambda msg: answer.append(msg.data), 10)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    while publisher.get_subscription_count() == 0 or node.count_publishers('bench/pong') == 0:
        executor.spin_once(timeout_sec=0.1)  # woken by the graph change
    message = String()
    one_way = []
    for i in range(WARMUP + COUNT):
        message.data = f'{i:08d}'.ljust(32, 'x')
        answer.clear()
        started = time.perf_counter()
        publisher.publish(message)
        while message.data not in answer:
            executor.spin_once(timeout_sec=5.0)
        if i >= WARMUP:
            one_way.append((time.perf_counter() - started) * 1e6 / 2)
    one_way.sort()

    def pct(p):
        return one_way[min(len(one_way) - 1, int(p * len(one_way)))]

    print(f'RESULT count={len(one_way)} p50_us={pct(0.5):.2f} p99_us={pct(0.99):.2f} '
          f'min_us={one_way[0]:.2f} max_us={one_way[-1]:.2f}', flush=True)
    rclpy.shutdown()


main()
