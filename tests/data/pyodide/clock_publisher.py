"""Publishes /clock at 100 times real time (10 s of it every 0.1 s), from 1000 s on."""

import time

import rclpy
from rclpy.node import Node

from builtin_interfaces.msg import Time as TimeMsg
from rosgraph_msgs.msg import Clock

rclpy.init()
node = Node('clock_publisher')
publisher = node.create_publisher(Clock, '/clock', 10)
sec = 1000
while rclpy.ok():
    publisher.publish(Clock(clock=TimeMsg(sec=sec)))
    sec += 10
    time.sleep(0.1)
