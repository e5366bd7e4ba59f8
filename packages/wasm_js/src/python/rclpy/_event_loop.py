# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
An asyncio event loop that blocks on the bus, in place of Pyodide's WebLoop.

Pyodide runs asyncio on the JS event loop (its WebLoop, always "running"):
``loop.run_until_complete`` cannot block there, and returns at once. A Python
node is a bus process whose Python runs from start to end without giving its
worker's JS event loop a turn (it blocks in Atomics waits, as the C++ nodes
do), so a WebLoop's callbacks would never run. Nodes written for rclpy that
use asyncio (ros2/examples' ``client_asyncio``: ``spin_once`` in one task,
``await`` on goal futures in others, ``loop.run_until_complete``) need a
loop that blocks like CPython's. Where the WebLoop is the running loop,
``import rclpy`` installs :class:`BusEventLoop` instead: asyncio's own
``BaseEventLoop`` (its scheduling, tasks, timers, unchanged) whose wait for
the next timer sleeps on the bus' doorbell (a stop of the process still
ends it). There are no file descriptors to watch in Pyodide, so readers,
writers and sockets are not available, as in WebLoop. The policy makes the
loop on first use, as Humble's Python 3.10 does for ``get_event_loop``.
"""

import asyncio
import asyncio.events

from rclpy._waiting import sleep_on_bus


class _BusSelector:
    """What BaseEventLoop asks of a selector: wait at most ``timeout`` s; no files."""

    def select(self, timeout=None):
        """Sleep on the bus' doorbell for ``timeout`` seconds (None: until it rings).

        The spin threads (rclpy/_threads.py) run meanwhile.
        """
        sleep_on_bus(timeout)
        return []

    def close(self):
        """Nothing to release."""


class BusEventLoop(asyncio.BaseEventLoop):
    """asyncio's BaseEventLoop, waiting on the bus between its callbacks."""

    def __init__(self):
        """Create the loop (not running, not current)."""
        super().__init__()
        self._selector = _BusSelector()

    def _process_events(self, event_list):
        """No file events: nothing to process."""

    def _write_to_self(self):
        """One thread: a callback scheduled is seen at the next iteration anyway."""


# Pyodide's Python names it with an underscore; older ones (the build host's, which
# imports rclpy for a Python launch file and never installs this loop) without
_BasePolicy = getattr(asyncio.events, '_BaseDefaultEventLoopPolicy', None) or \
    asyncio.events.BaseDefaultEventLoopPolicy


class BusEventLoopPolicy(_BasePolicy):
    """Loops are BusEventLoops; ``get_event_loop`` makes one on first use."""

    _loop_factory = BusEventLoop

    def get_event_loop(self):
        """Return the current loop, made now if there is none (as Python 3.10's)."""
        if self._local._loop is None:
            self.set_event_loop(self.new_event_loop())
        return self._local._loop


def install_bus_event_loop():
    """Where Pyodide's WebLoop is the running loop, make BusEventLoop asyncio's (once)."""
    running = asyncio.events._get_running_loop()
    if running is None or type(running).__name__ != 'WebLoop':
        return
    asyncio.events._set_running_loop(None)
    set_policy = getattr(asyncio.events, '_set_event_loop_policy', None) or \
        asyncio.set_event_loop_policy
    set_policy(BusEventLoopPolicy())
