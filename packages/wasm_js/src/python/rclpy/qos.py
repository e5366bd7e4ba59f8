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


class LivelinessPolicy(enum.IntEnum):
    """Liveliness policy."""

    SYSTEM_DEFAULT = 0
    AUTOMATIC = 1
    MANUAL_BY_TOPIC = 3


class QoSPolicyKind(enum.IntEnum):
    """The policy a QoS incompatibility is about (rmw_qos_policy_kind_t)."""

    INVALID = 1 << 0
    DURABILITY = 1 << 1
    DEADLINE = 1 << 2
    LIVELINESS = 1 << 3
    RELIABILITY = 1 << 4
    HISTORY = 1 << 5
    LIFESPAN = 1 << 6
    DEPTH = 1 << 7
    LIVELINESS_LEASE_DURATION = 1 << 8
    AVOID_ROS_NAMESPACE_CONVENTIONS = 1 << 9


def _milliseconds(duration, name):
    """Return a Duration (or a number of seconds) in milliseconds; 0: no limit."""
    if duration is None:
        return 0
    nanoseconds = getattr(duration, 'nanoseconds', None)
    if nanoseconds is None:
        if not isinstance(duration, (int, float)) or isinstance(duration, bool):
            raise TypeError(f'the QoS {name} must be an rclpy.duration.Duration, '
                            f'not {type(duration).__name__}')
        nanoseconds = int(duration * 1e9)
    if nanoseconds < 0:
        raise ValueError(f'the QoS {name} must not be negative')
    return nanoseconds / 1e6


class QoSProfile:
    """History, depth, reliability and durability of an endpoint."""

    def __init__(self, *, history=HistoryPolicy.KEEP_LAST, depth=None,
                 reliability=ReliabilityPolicy.RELIABLE,
                 durability=DurabilityPolicy.VOLATILE, deadline=None, lifespan=None,
                 liveliness=LivelinessPolicy.SYSTEM_DEFAULT, liveliness_lease_duration=None):
        """Describe a profile; KEEP_LAST needs a depth, as in rclpy. Durations: no limit."""
        if history == HistoryPolicy.KEEP_LAST and depth is None:
            raise ValueError('A QoSProfile with history KEEP_LAST needs a depth')
        self.history = HistoryPolicy(history)
        self.depth = depth if depth is not None else 0
        self.reliability = ReliabilityPolicy(reliability)
        self.durability = DurabilityPolicy(durability)
        from rclpy.duration import Duration
        self.deadline = deadline if deadline is not None else Duration()
        self.lifespan = lifespan if lifespan is not None else Duration()
        self.liveliness = LivelinessPolicy(liveliness)
        self.liveliness_lease_duration = liveliness_lease_duration \
            if liveliness_lease_duration is not None else Duration()

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
            'deadlineMs': _milliseconds(self.deadline, 'deadline'),
            'lifespanMs': _milliseconds(self.lifespan, 'lifespan'),
            'liveliness': 'manual_by_topic'
            if self.liveliness == LivelinessPolicy.MANUAL_BY_TOPIC else 'automatic',
            'leaseMs': _milliseconds(self.liveliness_lease_duration, 'liveliness lease duration'),
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
