"""A Python node with parameters: logs each change; refuses a rate <= 0."""

import rclpy
from rclpy.node import Node
from rclpy.parameter import SetParametersResult


def main():
    rclpy.init()
    node = Node('py_params')
    node.declare_parameter('greeting', 'hello')
    node.declare_parameter('rate', 5)

    def on_set(parameters):
        for p in parameters:
            if p.name == 'rate' and p.value <= 0:
                return SetParametersResult(successful=False, reason='rate must be > 0')
        for p in parameters:
            node.get_logger().info(f'PARAM {p.name} now {p.value!r}')
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(on_set)
    node.get_logger().info('READY')
    rclpy.spin(node)


if __name__ == '__main__':
    main()
