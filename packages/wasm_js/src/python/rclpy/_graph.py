# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The graph queries of rclpy.node.Node, answered from one snapshot of the bus.

Each query reads the graph of the node's domain at once
(``_colcon_wasm_bus.graph_json``): every node, publisher, subscription,
service and client of every bus process, C++ and Python alike, as
``ros2 node list`` and ``ros2 topic list`` see them.
"""

import json
import struct

from rclpy._bus import bus
from rclpy.qos import DurabilityPolicy
from rclpy.qos import HistoryPolicy
from rclpy.qos import QoSProfile
from rclpy.qos import ReliabilityPolicy
from rclpy.topic_endpoint_info import TopicEndpointInfo
from rclpy.topic_endpoint_info import TopicEndpointTypeEnum

_HISTORY = {'keep_last': HistoryPolicy.KEEP_LAST, 'keep_all': HistoryPolicy.KEEP_ALL}
_RELIABILITY = {'reliable': ReliabilityPolicy.RELIABLE,
                'best_effort': ReliabilityPolicy.BEST_EFFORT}
_DURABILITY = {'volatile': DurabilityPolicy.VOLATILE,
               'transient_local': DurabilityPolicy.TRANSIENT_LOCAL}


def snapshot(domain_id):
    """Return ``(nodes, endpoints)`` of a domain: lists of dicts (python_worker.mjs)."""
    g = json.loads(bus.graph_json(domain_id))
    return g['nodes'], g['endpoints']


def names_and_types(endpoints, kinds, node=None):
    """
    Return ``[(name, [types])]``, sorted, of the endpoints of ``kinds``.

    :param node: ``(name, namespace)`` to keep only that node's endpoints
    """
    found = {}
    for e in endpoints:
        if e['kind'] not in kinds:
            continue
        if node is not None and (e['node'], e['namespace']) != node:
            continue
        types = found.setdefault(e['name'], [])
        if e['type'] not in types:
            types.append(e['type'])
    return sorted((name, sorted(types)) for name, types in found.items())


def require_node(nodes, name, namespace):
    """Raise rclpy's error when no node of that name is in the graph."""
    if not any(n['name'] == name and n['namespace'] == namespace for n in nodes):
        raise NodeNameNonExistentError(
            f"Cannot get information of node '{name}' in namespace '{namespace}': "
            'no such node in the graph')


def count(endpoints, kind, topic):
    """Return how many endpoints of ``kind`` the topic has."""
    return sum(1 for e in endpoints if e['kind'] == kind and e['name'] == topic)


def _qos_profile(qos):
    return QoSProfile(history=_HISTORY.get(qos.get('history'), HistoryPolicy.SYSTEM_DEFAULT),
                      depth=qos.get('depth', 0),
                      reliability=_RELIABILITY.get(qos.get('reliability'),
                                                   ReliabilityPolicy.SYSTEM_DEFAULT),
                      durability=_DURABILITY.get(qos.get('durability'),
                                                 DurabilityPolicy.SYSTEM_DEFAULT))


def endpoint_infos(endpoints, kind, topic):
    """Return TopicEndpointInfo records of the topic's endpoints of ``kind``."""
    endpoint_type = (TopicEndpointTypeEnum.PUBLISHER if kind == 'publisher'
                     else TopicEndpointTypeEnum.SUBSCRIPTION)
    out = []
    for e in endpoints:
        if e['kind'] != kind or e['name'] != topic:
            continue
        # the bus' gid is four 32-bit words; rmw's is RMW_GID_STORAGE_SIZE (24) bytes
        gid = list(struct.pack('<4I', *(w & 0xFFFFFFFF for w in e['gid']))) + [0] * 8
        out.append(TopicEndpointInfo(node_name=e['node'], node_namespace=e['namespace'],
                                     topic_type=e['type'], endpoint_type=endpoint_type,
                                     endpoint_gid=gid, qos_profile=_qos_profile(e['qos'])))
    return out


class NodeNameNonExistentError(Exception):
    """A graph query about a node that is not in the graph (rclpy's error)."""
