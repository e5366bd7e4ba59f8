"""
bench/python: how fast a Python node publishes small messages.

Publishes 20000 demo_interfaces/msg/Chatter with ``Publisher.publish`` to a
topic that a subscription of the same node reads (so the bus writes every
message into its history), then the same number through the bus call under
it with the message already converted (``_colcon_wasm_bus.publish``, the
JS bus and cdr.mjs: the floor of any Pyodide node), and logs one line
``RATES {"rclpy": msg/s, "floor": msg/s}``.
"""

import json
import time

import rclpy
from rclpy._bus import bus
from rclpy._bus import plain_to_js
from rclpy.node import Node

from demo_interfaces.msg import Chatter

N = 20000


def rate(publish):
    start = time.perf_counter()
    for i in range(N):
        publish(i)
    return N / (time.perf_counter() - start)


def main():
    rclpy.init()
    node = Node('py_bench_rate')
    publisher = node.create_publisher(Chatter, 'py_bench_rate', 10)
    node.create_subscription(Chatter, 'py_bench_rate', lambda msg: None, 10)
    msg = Chatter(data='Hello World: 123456', count=0)

    def with_rclpy(i):
        msg.count = i
        publisher.publish(msg)

    plain = plain_to_js(msg._to_plain())

    def floor(i):
        bus.publish(publisher._handle, publisher._type_name, plain)

    rate(with_rclpy)  # warm up (the JIT of the runtime, the bus' first writes)
    rates = {'rclpy': [], 'floor': []}
    for _ in range(3):  # interleaved rounds
        rates['rclpy'].append(rate(with_rclpy))
        rates['floor'].append(rate(floor))
    node.get_logger().info('RATES ' + json.dumps({k: sorted(v)[1] for k, v in rates.items()}))
    rclpy.shutdown()


main()
