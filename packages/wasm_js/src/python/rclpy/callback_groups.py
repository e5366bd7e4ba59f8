# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.callback_groups: which callbacks may run at the same time.

One thread runs every callback here; the groups matter while a callback of
a MultiThreadedExecutor sleeps (``time.sleep``) or waits: then the executor
runs other ready callbacks, as its other threads would, but never a second
one of a busy MutuallyExclusiveCallbackGroup (rclpy.executors).
"""


class CallbackGroup:
    """The base of the groups: counts the callbacks of the group that are running."""

    def __init__(self):
        """Create a group with nothing running."""
        self.entities = []
        self._running = 0

    def add_entity(self, entity):
        """Add an entity (a subscription, timer, service, client, action server...)."""
        self.entities.append(entity)

    def has_entity(self, entity):
        """Return True when the entity is in the group."""
        return entity in self.entities

    def can_execute(self, entity):
        """Return True when a callback of ``entity`` may start now."""
        raise NotImplementedError

    def beginning_execution(self, entity):
        """Note that a callback of ``entity`` starts; False when it may not."""
        if not self.can_execute(entity):
            return False
        self._running += 1
        return True

    def ending_execution(self, entity):
        """Note that a callback of ``entity`` ended."""
        self._running -= 1


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One callback of the group at a time (a node's default group)."""

    def can_execute(self, entity):
        """Return True when no callback of the group is running."""
        return self._running == 0


class ReentrantCallbackGroup(CallbackGroup):
    """Any number of callbacks of the group at a time."""

    def can_execute(self, entity):
        """Return True: reentrant."""
        return True
