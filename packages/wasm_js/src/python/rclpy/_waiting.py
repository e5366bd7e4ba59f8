# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Where time passes: every blocking wait of rclpy here, and the spin threads.

Pyodide starts no thread, so a ``threading.Thread`` whose target spins an
executor (rclpy/_threads.py) is emulated: it is a :class:`SpinThread` of
:data:`THREADS`, and it runs where the thread that started it blocks. Each
wait of this process (an executor's, ``time.sleep``, ``Rate.sleep``, a
clock's sleep, ``Event.wait``, ``Thread.join``, ``wait_for_service``, the
asyncio loop's) is :func:`block`: one bus wait for what the caller waits
for *and* for the entities of every spin thread that can run; when an
entity of a spin thread is ready (or its timer is due), the thread takes
one step (``spin_once`` without waiting: one callback), and the wait goes
on until the caller's own item is ready, its ``done()`` is true or its
time is up. Nothing polls: the bus wait sleeps on the process' doorbell.

A spin thread does not run while it is itself on the stack (its callback
waits: the other spin threads run then), nor while its executor waits
lower on the stack (that wait serves the same entities).
"""

import time

from rclpy._bus import bus
from rclpy._bus import handles_to_js

"""The spin threads started (SpinThread), in start order; ended ones are removed."""
THREADS = []
"""The spin threads taking a step now, innermost last."""
STEPPING = []


class WaitSet:
    """What one wait is for: bus entities (kind, handle, event type) and a time limit."""

    def __init__(self, timeout_sec=None):
        """Create an empty set; ``timeout_sec``: at most this long (None: no limit)."""
        self.handles = []
        self.kinds = []
        self.event_types = []
        self.timeout_sec = timeout_sec

    def add(self, kind, handle, event_type=0):
        """Add an entity: kind 'subscription', 'service', 'client', 'event' or 'graph'."""
        self.handles.append(handle)
        self.kinds.append(kind)
        self.event_types.append(event_type)

    def limit(self, seconds):
        """Wait at most ``seconds`` (None: no new limit)."""
        if seconds is not None:
            seconds = max(0.0, seconds)
            self.timeout_sec = seconds if self.timeout_sec is None else \
                min(self.timeout_sec, seconds)

    def __len__(self):
        """Return the number of entities."""
        return len(self.handles)


def bus_wait(wait_set):
    """Wait once on the bus for the set's entities (at most its time); their ready flags."""
    timeout = wait_set.timeout_sec
    timeout_ms = -1 if timeout is None else max(0.0, timeout) * 1000.0
    return [bool(f) for f in bus.wait(handles_to_js(wait_set.handles),
                                      handles_to_js(wait_set.kinds), timeout_ms,
                                      handles_to_js(wait_set.event_types))]


def runnable_threads():
    """Return the spin threads that may take a step here (see the module's comment)."""
    return [t for t in list(THREADS) if t not in STEPPING and t.alive()
            and not t.executor_waiting()]


def block(wait_set, done=None):
    """
    Wait for ``wait_set`` (or until ``done()``) while the spin threads run.

    Returns the ready flags of the set's entities (all False when its time
    ran out, or when ``done()`` became true). Without a spin thread that
    can run, it is one bus wait; with ``done`` and none, nothing could make
    ``done()`` true: it sleeps the time left and returns (at once when the
    time is unlimited: the caller says why it cannot wait).
    """
    end = None if wait_set.timeout_sec is None else time.monotonic() + wait_set.timeout_sec
    own = len(wait_set)
    while True:
        if done is not None and done():
            return [False] * own
        left = None if end is None else max(0.0, end - time.monotonic())
        threads = runnable_threads() if left != 0.0 else []
        if not threads:
            if done is not None and own == 0 and left is None:
                return []
            once = WaitSet(left)
            once.handles, once.kinds, once.event_types = \
                wait_set.handles, wait_set.kinds, wait_set.event_types
            return bus_wait(once)
        combined = WaitSet(left)
        combined.handles = list(wait_set.handles)
        combined.kinds = list(wait_set.kinds)
        combined.event_types = list(wait_set.event_types)
        theirs = []
        for thread in threads:
            their = thread.wait_set()
            theirs.append((thread, len(combined), len(their), their.timeout_sec))
            combined.handles += their.handles
            combined.kinds += their.kinds
            combined.event_types += their.event_types
            combined.limit(their.timeout_sec)
        start = time.monotonic()
        flags = bus_wait(combined)
        if any(flags[:own]):
            return flags[:own]
        waited = time.monotonic() - start
        for thread, offset, count, timeout in theirs:
            if any(flags[offset:offset + count]) or (timeout is not None and waited >= timeout):
                thread.step()
        if end is not None and time.monotonic() >= end:
            return [False] * own


def sleep_on_bus(seconds):
    """Let ``seconds`` pass (None: until the doorbell rings) while the spin threads run."""
    block(WaitSet(seconds))
