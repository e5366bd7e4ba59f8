"""QoS events of rclpy: deadlines, liveliness, incompatible QoS; exits 0 when all were heard."""

import time

import rclpy
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSPolicyKind
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rclpy.qos_event import PublisherEventCallbacks
from rclpy.qos_event import SubscriptionEventCallbacks

from std_msgs.msg import String

rclpy.init()
node = Node('py_events')
seen = {'requested': [], 'offered': [], 'liveliness': [], 'incompatible': [], 'warned': []}
deadline = QoSProfile(depth=10, deadline=Duration(seconds=0.2))
publisher = node.create_publisher(
    String, 'events', deadline, event_callbacks=PublisherEventCallbacks(
        deadline=lambda e: seen['offered'].append(e.total_count)))
node.create_subscription(String, 'events', lambda m: None, deadline,
                         event_callbacks=SubscriptionEventCallbacks(
                             deadline=lambda e: seen['requested'].append(e.total_count),
                             liveliness=lambda e: seen['liveliness'].append(
                                 (e.alive_count, e.alive_count_change))))
# a reliable subscription and a best-effort publisher: incompatible
node.create_subscription(String, 'mismatch', lambda m: None, 10,
                         event_callbacks=SubscriptionEventCallbacks(
                             incompatible_qos=lambda e: seen['incompatible'].append(
                                 e.last_policy_kind)))
mismatch = node.create_publisher(String, 'mismatch',
                                 QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
executor = SingleThreadedExecutor()
executor.add_node(node)


def spin_for(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        executor.spin_once(timeout_sec=end - time.monotonic())


for i in range(5):  # in time: no deadline missed
    publisher.publish(String(data=f'in time {i}'))
    spin_for(0.05)
assert not seen['requested'] and not seen['offered'], seen
spin_for(1.0)  # silent for 1 s: about five deadlines of 200 ms missed, on both sides
assert seen['requested'] and seen['requested'] == sorted(seen['requested']), seen
assert 3 <= seen['requested'][-1] <= 6 and 3 <= seen['offered'][-1] <= 6, seen
assert seen['liveliness'] and seen['liveliness'][0] == (1, 1), seen
node.destroy_publisher(publisher)
spin_for(0.3)
assert seen['liveliness'][-1] == (0, -1), seen
assert seen['incompatible'] == [QoSPolicyKind.RELIABILITY], seen
node.get_logger().info(f'QoS events heard: {seen}')
rclpy.shutdown()
