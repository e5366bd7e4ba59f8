"""rclpy.time, rclpy.duration and the graph queries, beside the C++ demo nodes; exits 0."""

import time

import rclpy
from rclpy.clock import Clock
from rclpy.clock import ClockType
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.node import NodeNameNonExistentError
from rclpy.qos import DurabilityPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rclpy.time import Time
from rclpy.topic_endpoint_info import TopicEndpointTypeEnum

from demo_interfaces.msg import Chatter


def raises(kind, text, make):
    try:
        make()
    except kind as e:
        assert text in str(e), str(e)
    else:
        raise SystemExit(f'no {kind.__name__} for {text}')


# --- rclpy.duration and rclpy.time, as rclpy's behave
d = Duration(seconds=1.5, nanoseconds=20)
assert d.nanoseconds == 1_500_000_020 and repr(d) == 'Duration(nanoseconds=1500000020)'
assert Duration(seconds=-1).nanoseconds == -10 ** 9
assert Duration(seconds=1) < Duration(seconds=2)
assert Duration(nanoseconds=5) == Duration(nanoseconds=5)
raises(TypeError, "Can't compare duration with object of type", lambda: Duration() == 0)
msg = Duration(nanoseconds=-1).to_msg()
assert (msg.sec, msg.nanosec) == (-1, 999_999_999), (msg.sec, msg.nanosec)
assert Duration.from_msg(msg) == Duration(nanoseconds=-1)

t = Time(seconds=10, nanoseconds=5, clock_type=ClockType.ROS_TIME)
assert t.seconds_nanoseconds() == (10, 5) and t.clock_type == ClockType.ROS_TIME
assert repr(t) == 'Time(nanoseconds=10000000005, clock_type=ROS_TIME)', repr(t)
assert t + Duration(seconds=1) == Time(seconds=11, nanoseconds=5, clock_type=ClockType.ROS_TIME)
assert Duration(seconds=1) + t == t + Duration(seconds=1)
assert t - Time(seconds=4, clock_type=ClockType.ROS_TIME) == Duration(seconds=6, nanoseconds=5)
assert t - Duration(nanoseconds=5) == Time(seconds=10, clock_type=ClockType.ROS_TIME)
raises(TypeError, "Can't compare times with different clock types",
       lambda: t < Time(seconds=1))
raises(ValueError, 'Seconds value must not be negative', lambda: Time(seconds=-1))
stamp = t.to_msg()
assert type(stamp).__name__ == 'Time' and (stamp.sec, stamp.nanosec) == (10, 5)
assert Time.from_msg(stamp) == t
assert {t: 1}[Time(nanoseconds=10_000_000_005, clock_type=ClockType.ROS_TIME)] == 1

rclpy.init()
node = Node('py_graph')
clock = node.get_clock()
assert clock.clock_type == ClockType.ROS_TIME and not clock.ros_time_is_active
now = clock.now()
assert now.clock_type == ClockType.ROS_TIME
assert abs(now.nanoseconds - time.time_ns()) < 5 * 10 ** 9
assert clock.now() >= now
steady = Clock(clock_type=ClockType.STEADY_TIME)
a = steady.now()
assert steady.now() - a >= Duration()

# --- the graph: the C++ talker, listener and add_two_ints_server, and this node
pub = node.create_publisher(Chatter, 'py_chatter', QoSProfile(
    depth=7, reliability=ReliabilityPolicy.BEST_EFFORT,
    durability=DurabilityPolicy.TRANSIENT_LOCAL))
deadline = time.monotonic() + 60
while time.monotonic() < deadline:
    names = node.get_node_names()
    services = dict(node.get_service_names_and_types())
    if {'talker', 'listener', 'add_two_ints_server'} <= set(names) and \
            '/add_two_ints' in services and node.count_subscribers('/chatter'):
        break
    rclpy.spin_once(node, timeout_sec=0.2)
else:
    raise SystemExit(f'the C++ nodes did not show up: {node.get_node_names_and_namespaces()}')

assert ('py_graph', '/') in node.get_node_names_and_namespaces()
assert ('talker', '/', '/') in node.get_node_names_and_namespaces_with_enclaves()
topics = dict(node.get_topic_names_and_types())
assert topics['/chatter'] == ['demo_interfaces/msg/Chatter'], topics
assert topics['/py_chatter'] == ['demo_interfaces/msg/Chatter'], topics
assert node.get_topic_names_and_types() == sorted(node.get_topic_names_and_types())
assert services['/add_two_ints'] == ['demo_interfaces/srv/AddTwoInts'], services
assert node.count_publishers('/chatter') == 1 and node.count_subscribers('chatter') >= 1
assert node.count_publishers('/nothing_here') == 0
assert ('/chatter', ['demo_interfaces/msg/Chatter']) in \
    node.get_publisher_names_and_types_by_node('talker', '/')
assert ('/chatter', ['demo_interfaces/msg/Chatter']) in \
    node.get_subscriber_names_and_types_by_node('listener', '/')
assert ('/add_two_ints', ['demo_interfaces/srv/AddTwoInts']) in \
    node.get_service_names_and_types_by_node('add_two_ints_server', '/')
assert node.get_client_names_and_types_by_node('talker', '/') == []
raises(NodeNameNonExistentError, "node 'ghost' in namespace '/'",
       lambda: node.get_publisher_names_and_types_by_node('ghost', '/'))
(info,) = node.get_publishers_info_by_topic('/py_chatter')
assert (info.node_name, info.node_namespace, info.topic_type) == \
    ('py_graph', '/', 'demo_interfaces/msg/Chatter'), str(info)
assert info.endpoint_type == TopicEndpointTypeEnum.PUBLISHER and len(info.endpoint_gid) == 24
assert info.qos_profile.depth == 7, str(info)
assert info.qos_profile.reliability == ReliabilityPolicy.BEST_EFFORT, str(info)
assert info.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL, str(info)
subs = node.get_subscriptions_info_by_topic('/chatter')
assert [s.node_name for s in subs] == ['listener'], [str(s) for s in subs]
assert subs[0].endpoint_type == TopicEndpointTypeEnum.SUBSCRIPTION
# a node that leaves is gone from the graph
node.destroy_publisher(pub)
assert '/py_chatter' not in dict(node.get_topic_names_and_types())
node.get_logger().info('time, duration and graph queries behave')
rclpy.shutdown()
