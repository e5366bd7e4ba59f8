# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Executors: wait for the nodes' subscriptions, services, clients and timers, then call back.

A wait blocks the worker in Atomics.wait on the process' doorbell until a
message arrives or the next timer is due: nothing polls. spin_once runs
every callback that is ready after one wait (rclpy runs one).
MultiThreadedExecutor is accepted and runs on this one thread.
"""

import time

from rclpy._bus import bus
from rclpy._bus import handles_to_js
from rclpy.context import default_context


class ExternalShutdownException(Exception):
    """The context was shut down while spinning."""


class Executor:
    """Runs the callbacks of its nodes."""

    def __init__(self, *, context=None):
        """Create an executor of ``context`` (default: the default context)."""
        self.context = context or default_context()
        self._nodes = []

    def add_node(self, node):
        """Add a node; returns True when it was not there yet."""
        if node in self._nodes:
            return False
        self._nodes.append(node)
        return True

    def remove_node(self, node):
        """Remove a node."""
        if node in self._nodes:
            self._nodes.remove(node)

    def get_nodes(self):
        """Return the nodes."""
        return list(self._nodes)

    def shutdown(self, timeout_sec=None):
        """Forget the nodes."""
        self._nodes = []
        return True

    def spin(self):
        """Spin until the context is shut down."""
        while self.context.ok():
            self.spin_once()

    def spin_until_future_complete(self, future, timeout_sec=None):
        """Spin until ``future`` is done, or ``timeout_sec`` passed."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while self.context.ok() and not future.done():
            left = None if end is None else end - time.monotonic()
            if left is not None and left <= 0:
                return
            self.spin_once(timeout_sec=left)

    def spin_once(self, timeout_sec=None):
        """Wait for work (at most ``timeout_sec``; None: until there is some) and do it."""
        nodes = [n for n in self._nodes if n._handle is not None]
        subscriptions = [s for n in nodes for s in n.subscriptions if s._handle is not None]
        services = [s for n in nodes for s in n.services if s._handle is not None]
        clients = [c for n in nodes for c in n.clients if c._handle is not None]
        timers = [t for n in nodes for t in n.timers if not t.is_canceled()]
        now = time.monotonic()
        wait = -1.0 if timeout_sec is None or timeout_sec < 0 else timeout_sec
        if timers:
            until_timer = max(0.0, min(t._next for t in timers) - now)
            wait = until_timer if wait < 0 else min(wait, until_timer)
        timeout_ms = -1 if wait < 0 else wait * 1000.0
        entities = subscriptions + services + clients
        kinds = (['subscription'] * len(subscriptions) + ['service'] * len(services)
                 + ['client'] * len(clients))
        ready = list(bus.wait(handles_to_js(e._handle for e in entities), handles_to_js(kinds),
                              timeout_ms))
        for subscription, flag in zip(subscriptions, ready):
            if not flag:
                continue
            while subscription._handle is not None:
                msg = subscription._take()
                if msg is None:
                    break
                subscription.callback(msg)
        offset = len(subscriptions)
        for service, flag in zip(services, ready[offset:offset + len(services)]):
            while flag and service._handle is not None and service._serve_one():
                pass
        offset += len(services)
        for client, flag in zip(clients, ready[offset:]):
            while flag and client._handle is not None and client._take_one():
                pass
        now = time.monotonic()
        for timer in timers:
            if timer._due(now):
                timer._advance(now)
                timer.callback()


class SingleThreadedExecutor(Executor):
    """An executor on this thread."""


class MultiThreadedExecutor(Executor):
    """Accepted for compatibility: runs on this one thread (Pyodide has no threads here)."""

    def __init__(self, num_threads=None, *, context=None):
        """Create the executor; ``num_threads`` is ignored."""
        super().__init__(context=context)
