# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.qos_event: QoS event callbacks of publishers and subscriptions.

The bus counts deadlines, liveliness, lost messages and incompatible QoS on
each endpoint (wasm_js client/events.mjs, what rmw_wasm_cpp's events read
too). An event handler is one of those events of one endpoint in the
executor's wait: when its status changed, the callback gets the status,
with rclpy's field names (``total_count``, ``total_count_change``, ...).
Without an ``incompatible_qos`` callback, a warning is logged, as rclpy's
default callback does.
"""

import enum

from rclpy._bus import bus
from rclpy.qos import QoSPolicyKind


class QoSSubscriptionEventType(enum.IntEnum):
    """A subscription's events (the bus' EventType numbers)."""

    RCL_SUBSCRIPTION_LIVELINESS_CHANGED = 0
    RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED = 1
    RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS = 2
    RCL_SUBSCRIPTION_MESSAGE_LOST = 3


class QoSPublisherEventType(enum.IntEnum):
    """A publisher's events (the bus' EventType numbers)."""

    RCL_PUBLISHER_LIVELINESS_LOST = 4
    RCL_PUBLISHER_OFFERED_DEADLINE_MISSED = 5
    RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS = 6


class _Status:
    """An event's status: the fields rclpy's status structs have."""

    def __init__(self, **fields):
        self.__dict__.update(fields)

    def __repr__(self):
        """Show the fields."""
        inner = ', '.join(f'{k}={v!r}' for k, v in self.__dict__.items())
        return f'{type(self).__name__}({inner})'


class QoSRequestedDeadlineMissedInfo(_Status):
    """A subscription missed its deadline: total_count, total_count_change."""


class QoSOfferedDeadlineMissedInfo(_Status):
    """A publisher missed its deadline: total_count, total_count_change."""


class QoSLivelinessChangedInfo(_Status):
    """A subscription's publishers' liveliness: alive_count, not_alive_count and changes."""


class QoSLivelinessLostInfo(_Status):
    """A publisher lost its liveliness: total_count, total_count_change."""


class QoSRequestedIncompatibleQoSInfo(_Status):
    """A publisher offers incompatible QoS: total_count(_change), last_policy_kind."""


class QoSOfferedIncompatibleQoSInfo(_Status):
    """A subscription requests incompatible QoS: total_count(_change), last_policy_kind."""


class QoSMessageLostInfo(_Status):
    """Messages were lost: total_count, total_count_change."""


def _counts(cls):
    return lambda s: cls(total_count=s.total, total_count_change=s.change)


def _incompatible(cls):
    return lambda s: cls(total_count=s.total, total_count_change=s.change,
                         last_policy_kind=QoSPolicyKind(s.policy) if s.policy else
                         QoSPolicyKind.INVALID)


"""Event type: how its bus status becomes rclpy's status object."""
_STATUS = {
    0: lambda s: QoSLivelinessChangedInfo(
        alive_count=s.alive, not_alive_count=s.notAlive, alive_count_change=s.aliveChange,
        not_alive_count_change=s.notAliveChange),
    1: _counts(QoSRequestedDeadlineMissedInfo),
    2: _incompatible(QoSRequestedIncompatibleQoSInfo),
    3: _counts(QoSMessageLostInfo),
    4: _counts(QoSLivelinessLostInfo),
    5: _counts(QoSOfferedDeadlineMissedInfo),
    6: _incompatible(QoSOfferedIncompatibleQoSInfo),
}


class QoSEventHandler:
    """One event of one endpoint: the executor calls ``callback(status)`` when it changed."""

    def __init__(self, parent, event_type, callback):
        """Made by the endpoint's event callbacks."""
        self.parent = parent
        self.event_type = int(event_type)
        self.callback = callback
        self.callback_group = parent.callback_group

    @property
    def _handle(self):
        return self.parent._handle

    def _take(self):
        """Read (and reset the changes of) the status, or None when nothing changed."""
        status = bus.event_status(self._handle, self.event_type)
        if not status.changed:
            return None
        return _STATUS[self.event_type](status)


def _incompatible_warning(endpoint, offering):
    def warn(event):
        if offering:
            text = (f"New subscription discovered on topic '{endpoint.topic_name}', requesting "
                    'incompatible QoS. No messages will be sent to it. Last incompatible '
                    f'policy: {event.last_policy_kind.name}')
        else:
            text = (f"New publisher discovered on topic '{endpoint.topic_name}', offering "
                    'incompatible QoS. No messages will be received from it. Last '
                    f'incompatible policy: {event.last_policy_kind.name}')
        endpoint.node.get_logger().warning(text)
    return warn


class SubscriptionEventCallbacks:
    """The QoS event callbacks of a subscription (create_subscription's event_callbacks)."""

    def __init__(self, *, deadline=None, incompatible_qos=None, liveliness=None,
                 message_lost=None, use_default_callbacks=True):
        """Keep the callbacks; each gets its event's status."""
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.message_lost = message_lost
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, subscription):
        """Create the handlers of the callbacks that are set (and rclpy's default ones)."""
        incompatible = self.incompatible_qos or (
            _incompatible_warning(subscription, False) if self.use_default_callbacks else None)
        pairs = ((QoSSubscriptionEventType.RCL_SUBSCRIPTION_REQUESTED_DEADLINE_MISSED,
                  self.deadline),
                 (QoSSubscriptionEventType.RCL_SUBSCRIPTION_REQUESTED_INCOMPATIBLE_QOS,
                  incompatible),
                 (QoSSubscriptionEventType.RCL_SUBSCRIPTION_LIVELINESS_CHANGED, self.liveliness),
                 (QoSSubscriptionEventType.RCL_SUBSCRIPTION_MESSAGE_LOST, self.message_lost))
        return [QoSEventHandler(subscription, kind, callback)
                for kind, callback in pairs if callback is not None]


class PublisherEventCallbacks:
    """The QoS event callbacks of a publisher (create_publisher's event_callbacks)."""

    def __init__(self, *, deadline=None, incompatible_qos=None, liveliness=None,
                 use_default_callbacks=True):
        """Keep the callbacks; each gets its event's status."""
        self.deadline = deadline
        self.incompatible_qos = incompatible_qos
        self.liveliness = liveliness
        self.use_default_callbacks = use_default_callbacks

    def create_event_handlers(self, publisher):
        """Create the handlers of the callbacks that are set (and rclpy's default ones)."""
        incompatible = self.incompatible_qos or (
            _incompatible_warning(publisher, True) if self.use_default_callbacks else None)
        pairs = ((QoSPublisherEventType.RCL_PUBLISHER_OFFERED_DEADLINE_MISSED, self.deadline),
                 (QoSPublisherEventType.RCL_PUBLISHER_OFFERED_INCOMPATIBLE_QOS, incompatible),
                 (QoSPublisherEventType.RCL_PUBLISHER_LIVELINESS_LOST, self.liveliness))
        return [QoSEventHandler(publisher, kind, callback)
                for kind, callback in pairs if callback is not None]
