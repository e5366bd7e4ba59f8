# A node that says what it was given (tests/test_pyodide_snapshot.py): its argv and
# environment are its own, not those of the Pyodide the snapshot was taken of, and a
# message goes through the bus to itself.
import os
import sys

import rclpy
from std_msgs.msg import String

rclpy.init()
node = rclpy.create_node('snapshot_node')
heard = []
node.create_subscription(String, 'snap', lambda m: heard.append(m.data), 10)
publisher = node.create_publisher(String, 'snap', 10)
publisher.publish(String(data='through the bus'))
rclpy.spin_once(node, timeout_sec=5)
print('argv', sys.argv[1:], 'index', os.environ.get('NODE_INDEX'), 'heard', heard)
node.destroy_node()
rclpy.shutdown()
