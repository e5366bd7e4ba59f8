# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""QoS profiles as rclpy spells them, mapped to the bus' QoS objects (qos.mjs)."""

import enum
import json


class HistoryPolicy(enum.IntEnum):
    """History policy."""

    SYSTEM_DEFAULT = 0
    KEEP_LAST = 1
    KEEP_ALL = 2


class ReliabilityPolicy(enum.IntEnum):
    """Reliability policy."""

    SYSTEM_DEFAULT = 0
    RELIABLE = 1
    BEST_EFFORT = 2


class DurabilityPolicy(enum.IntEnum):
    """Durability policy."""

    SYSTEM_DEFAULT = 0
    TRANSIENT_LOCAL = 1
    VOLATILE = 2


class QoSProfile:
    """History, depth, reliability and durability of an endpoint."""

    def __init__(self, *, history=HistoryPolicy.KEEP_LAST, depth=None,
                 reliability=ReliabilityPolicy.RELIABLE,
                 durability=DurabilityPolicy.VOLATILE):
        """Describe a profile; KEEP_LAST needs a depth, as in rclpy."""
        if history == HistoryPolicy.KEEP_LAST and depth is None:
            raise ValueError('A QoSProfile with history KEEP_LAST needs a depth')
        self.history = HistoryPolicy(history)
        self.depth = depth if depth is not None else 0
        self.reliability = ReliabilityPolicy(reliability)
        self.durability = DurabilityPolicy(durability)

    def __repr__(self):
        """Show the policies."""
        return (f'QoSProfile(history={self.history.name}, depth={self.depth}, '
                f'reliability={self.reliability.name}, durability={self.durability.name})')

    def to_bus(self):
        """Return the bus QoS object as JSON text."""
        keep_all = self.history == HistoryPolicy.KEEP_ALL
        return json.dumps({
            'history': 'keep_all' if keep_all else 'keep_last',
            'depth': max(1, self.depth) if not keep_all else max(1, self.depth or 1000),
            'reliability': 'best_effort' if self.reliability == ReliabilityPolicy.BEST_EFFORT
            else 'reliable',
            'durability': 'transient_local'
            if self.durability == DurabilityPolicy.TRANSIENT_LOCAL else 'volatile',
        })


def profile_of(qos_profile):
    """Accept a QoSProfile or a depth (int), as rclpy's create_* do."""
    if isinstance(qos_profile, QoSProfile):
        return qos_profile
    if isinstance(qos_profile, int) and not isinstance(qos_profile, bool):
        if qos_profile < 0:
            raise ValueError(f'history depth must be >= 0, got {qos_profile}')
        return QoSProfile(depth=qos_profile)
    raise TypeError(f'Expected QoSProfile or int, but received {type(qos_profile)!r}')


qos_profile_system_default = QoSProfile(depth=10)
qos_profile_services_default = QoSProfile(depth=10)
qos_profile_sensor_data = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
