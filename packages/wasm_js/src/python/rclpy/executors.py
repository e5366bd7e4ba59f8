# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Executors: wait for the nodes' entities, then call back; tasks; time.sleep.

A wait blocks the worker in Atomics.wait on the process' doorbell until a
message arrives, a timer is due or a guard condition was triggered: nothing
polls. spin_once runs every callback that is ready after one wait (rclpy
runs one), then resumes the tasks (coroutine callbacks, rclpy.task.Task).
QoS events (rclpy.qos_event) are items of the same wait.

Pyodide has no threads here: MultiThreadedExecutor runs on this one thread,
and where a thread of rclpy's would block, in ``time.sleep`` inside a
callback, it runs the other callbacks that are ready meanwhile, except
those of a busy MutuallyExclusiveCallbackGroup (rclpy.callback_groups).
So an action's execute callback that sleeps still hears its cancel
request, as with rclpy's thread pool. Outside of that, ``time.sleep``
blocks in an Atomics wait (Pyodide's own spins the CPU).
"""

import inspect
import time

from rclpy._bus import bus
from rclpy._bus import handles_to_js
from rclpy.context import default_context
from rclpy.task import Task

"""The tasks of this process: every executor resumes them (one thread)."""
_TASKS = []
"""The executors inside a callback, innermost last (for time.sleep)."""
_DISPATCHING = []


class ExternalShutdownException(Exception):
    """The context was shut down while spinning."""


class ShutdownException(Exception):
    """The executor was shut down."""


class TimeoutException(Exception):
    """Nothing was ready in the time given (wait_for_ready_callbacks)."""


def create_task(callback, *args, **kwargs):
    """Schedule ``callback(*args, **kwargs)`` (or a coroutine) as a Task; returns it."""
    task = Task(callback, args, kwargs)
    _TASKS.append(task)
    return task


def _wait(timeout_sec):
    """Block for at most ``timeout_sec`` (None: until the doorbell rings)."""
    bus.wait(handles_to_js([]), handles_to_js([]),
             -1 if timeout_sec is None else max(0.0, timeout_sec) * 1000.0)


def wait_for(subscription, timeout_sec):
    """Block until ``subscription`` has a message, for at most ``timeout_sec``."""
    bus.wait(handles_to_js([subscription._handle]), handles_to_js(['subscription']),
             max(0.0, timeout_sec) * 1000.0, handles_to_js([0]))


def sleep_spins():
    """Return True when time.sleep here spins a MultiThreadedExecutor (see above)."""
    executor = _DISPATCHING[-1] if _DISPATCHING else None
    return isinstance(executor, MultiThreadedExecutor) and executor.context.ok()


def wait_a_while(seconds):
    """
    Let time pass, at most ``seconds``, for a sleep that checks its own end.

    In a MultiThreadedExecutor's callback, until the executor's next ready
    callbacks have run (a message for the sleeper may be among them);
    elsewhere, nothing else runs meanwhile: the whole ``seconds``.
    """
    if sleep_spins():
        _DISPATCHING[-1].spin_once(timeout_sec=seconds)
    else:
        _wait(seconds)


def sleep(seconds):
    """Do what time.sleep does (this module installs it as time.sleep; see above)."""
    if seconds < 0:
        raise ValueError('sleep length must be non-negative')
    end = time.monotonic() + seconds
    while True:
        left = end - time.monotonic()
        if left <= 0:
            return
        if sleep_spins():
            _DISPATCHING[-1].spin_once(timeout_sec=left)
        else:
            _wait(left)


time.sleep = sleep


class Executor:
    """Runs the callbacks of its nodes."""

    def __init__(self, *, context=None):
        """Create an executor of ``context`` (default: the default context)."""
        self.context = context or default_context()
        self._nodes = []
        self._ready = None

    def add_node(self, node):
        """Add a node; returns True when it was not there yet."""
        if node in self._nodes:
            return False
        self._nodes.append(node)
        node.executor = self
        return True

    def remove_node(self, node):
        """Remove a node."""
        if node in self._nodes:
            self._nodes.remove(node)
            if getattr(node, 'executor', None) is self:
                node.executor = None

    def get_nodes(self):
        """Return the nodes."""
        return list(self._nodes)

    def create_task(self, callback, *args, **kwargs):
        """Schedule a callback or coroutine as a Task; returns it."""
        return create_task(callback, *args, **kwargs)

    def shutdown(self, timeout_sec=None):
        """Forget the nodes."""
        for node in list(self._nodes):
            self.remove_node(node)
        return True

    def wake(self):
        """Nothing to wake: the only thread is the caller."""

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

    def spin_once_until_future_complete(self, future, timeout_sec=None):
        """Spin once, unless ``future`` is done."""
        if not future.done():
            self.spin_once(timeout_sec=timeout_sec)

    def spin_once(self, timeout_sec=None):
        """Wait for work (at most ``timeout_sec``; None: until there is some) and do it."""
        for call, _, _ in self._ready_callbacks(timeout_sec):
            call()
        self._resume_tasks()

    def wait_for_ready_callbacks(self, timeout_sec=None):
        """Return (handler, entity, node) of the next ready callback, as rclpy's does.

        ``handler`` is a Task that runs the callback when called (custom
        executors call it, or give it to a pool). One wait yields every
        callback that is ready then; the next call returns the next of
        them, and waits again when none is left. TimeoutException when
        nothing was ready in ``timeout_sec``, ShutdownException when the
        context was shut down.
        """
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while True:
            if not self.context.ok():
                raise ShutdownException()
            if self._ready is None:
                left = None if end is None else max(0.0, end - time.monotonic())
                self._ready = self._ready_callbacks(left)
            try:
                call, entity, node = next(self._ready)
            except StopIteration:
                self._ready = None
                if end is not None and time.monotonic() >= end:
                    raise TimeoutException()
                continue
            return Task(call), entity, node

    def _ready_callbacks(self, timeout_sec):
        """Wait once, then yield (call, entity, node) for each callback ready then.

        Lazily: each is taken (a message, a request) when the one before
        it was run, and only while its callback group lets it start.
        """
        self._resume_tasks()
        may_run = self._may_run
        nodes = [n for n in self._nodes if n._handle is not None]
        subscriptions = [(s, n) for n in nodes for s in n.subscriptions
                         if s._handle is not None and may_run(s)]
        services = [(s, n) for n in nodes for s in n.services
                    if s._handle is not None and may_run(s)]
        clients = [(c, n) for n in nodes for c in n.clients
                   if c._handle is not None and may_run(c)]
        timers = [(t, n) for n in nodes for t in n.timers if not t.is_canceled() and may_run(t)]
        guards = [(g, n) for n in nodes for g in n.guards if g._triggered and may_run(g)]
        events = [(h, n) for n in nodes for e in n.publishers + n.subscriptions
                  if e._handle is not None for h in getattr(e, 'event_handlers', ())
                  if may_run(h)]
        wait = -1.0 if timeout_sec is None or timeout_sec < 0 else timeout_sec
        if guards:
            wait = 0.0
        lefts = [left for left in (t._seconds_left() for t, _ in timers) if left is not None]
        if lefts:
            wait = min(lefts) if wait < 0 else min(wait, min(lefts))
        timeout_ms = -1 if wait < 0 else wait * 1000.0
        entities = [e for e, _ in subscriptions + services + clients + events]
        kinds = (['subscription'] * len(subscriptions) + ['service'] * len(services)
                 + ['client'] * len(clients) + ['event'] * len(events))
        event_types = [0] * (len(entities) - len(events)) + [h.event_type for h, _ in events]
        ready = list(bus.wait(handles_to_js(e._handle for e in entities), handles_to_js(kinds),
                              timeout_ms, handles_to_js(event_types)))
        for guard, node in guards:
            guard._triggered = False
            yield lambda g=guard: self._call(g, g.callback), guard, node
        for (subscription, node), flag in zip(subscriptions, ready):
            while flag and subscription._handle is not None and may_run(subscription):
                msg = subscription._take()
                if msg is None:
                    break
                yield (lambda s=subscription, m=msg: self._call(s, s.callback, m),
                       subscription, node)
        offset = len(subscriptions)
        for (service, node), flag in zip(services, ready[offset:offset + len(services)]):
            while flag and service._handle is not None and may_run(service):
                taken = service._take_request()
                if taken is None:
                    break
                yield (lambda s=service, t=taken: self._call(
                    s, s.callback, t[0], s.srv_type.Response(),
                    done=lambda response: s._respond(t[1], response)), service, node)
        offset += len(services)
        for (client, _), flag in zip(clients, ready[offset:offset + len(clients)]):
            # a response completes its future here; the futures' callbacks run as tasks
            while flag and client._handle is not None and client._take_one():
                pass
        offset += len(clients)
        for (handler, node), flag in zip(events, ready[offset:]):
            status = handler._take() if flag and handler._handle is not None else None
            if status is not None:
                yield (lambda h=handler, st=status: self._call(h, h.callback, st),
                       handler, node)
        for timer, node in timers:
            if timer._due() and may_run(timer):
                timer._advance()
                yield lambda t=timer: self._call(t, t.callback), timer, node

    def _may_run(self, entity):
        group = getattr(entity, 'callback_group', None)
        return group is None or group.can_execute(entity)

    def _call(self, entity, callback, *args, done=None):
        """Run a callback in its group; a coroutine becomes a task; ``done(result)`` after."""
        group = getattr(entity, 'callback_group', None)
        if group is not None and not group.beginning_execution(entity):
            return
        _DISPATCHING.append(self)
        try:
            result = callback(*args)
        finally:
            _DISPATCHING.pop()
            if group is not None:
                group.ending_execution(entity)
        if inspect.iscoroutine(result):
            task = create_task(result)
            task._group = (group, entity)
            if done is not None:
                task.add_done_callback(lambda t: done(t.result()) if t.exception() is None
                                       else None)
            self._step(task)
        elif done is not None:
            done(result)

    def _step(self, task):
        group, entity = getattr(task, '_group', (None, None))
        if group is not None and not group.beginning_execution(entity):
            return
        _DISPATCHING.append(self)
        try:
            task()
        finally:
            _DISPATCHING.pop()
            if group is not None:
                group.ending_execution(entity)

    def _resume_tasks(self):
        """Resume the tasks that are not done and not running; again while that changed any."""
        for _ in range(100):
            count = len(_TASKS)
            pending = [t for t in _TASKS if not t.done() and not t.executing()]
            for task in pending:
                self._step(task)
            changed = len(_TASKS) > count or any(t.done() for t in pending)
            _TASKS[:] = [t for t in _TASKS if not t.done()]
            if not changed:
                break


class SingleThreadedExecutor(Executor):
    """An executor on this thread."""


class MultiThreadedExecutor(Executor):
    """rclpy's thread pool on this one thread: see the module's comment."""

    def __init__(self, num_threads=None, *, context=None):
        """Create the executor; ``num_threads`` is accepted (one thread runs the callbacks)."""
        super().__init__(context=context)
        self._num_threads = num_threads
