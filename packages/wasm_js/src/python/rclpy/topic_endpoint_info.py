# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.topic_endpoint_info: what get_publishers_info_by_topic returns, as rclpy's."""

import enum


class TopicEndpointTypeEnum(enum.IntEnum):
    """rmw_endpoint_type_t."""

    INVALID = 0
    PUBLISHER = 1
    SUBSCRIPTION = 2


class TopicEndpointInfo:
    """One publisher or subscription of a topic: its node, type, gid and QoS."""

    def __init__(self, *, node_name='', node_namespace='', topic_type='',
                 endpoint_type=TopicEndpointTypeEnum.INVALID, endpoint_gid=(), qos_profile=None):
        """Create the record (made by Node.get_publishers_info_by_topic and friends)."""
        self.node_name = node_name
        self.node_namespace = node_namespace
        self.topic_type = topic_type
        self.endpoint_type = TopicEndpointTypeEnum(endpoint_type)
        self.endpoint_gid = list(endpoint_gid)
        self.qos_profile = qos_profile

    def __eq__(self, other):  # noqa: D105
        if not isinstance(other, TopicEndpointInfo):
            return NotImplemented
        return vars(self) == vars(other)

    def __str__(self):  # noqa: D105
        gid = '.'.join(format(x, '02x') for x in self.endpoint_gid)
        return '\n'.join([
            f'Node name: {self.node_name}',
            f'Node namespace: {self.node_namespace}',
            f'Topic type: {self.topic_type}',
            f'Endpoint type: {self.endpoint_type.name}',
            f'GID: {gid}',
            f'QoS profile:\n  {self.qos_profile}',
        ])
