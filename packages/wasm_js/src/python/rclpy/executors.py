"""
Executors: wait for the nodes' entities, then call back; tasks; time.sleep.

As rclpy's: ``spin_once`` runs one callback (or one step of a task), the
next ready one of the executor's last wait, and waits again when none is
left; ``wait_for_ready_callbacks`` hands out the same (task, entity, node)
triples. One wait yields, as rclpy's does, the tasks in progress first
(newest first), then the QoS events, then per node its timers,
subscriptions, guard conditions, clients and services, one callback per
entity (a subscription with three messages is ready at three waits). A
message or request is taken when its callback runs. A wait blocks the
worker in Atomics.wait on the process' doorbell until a message arrives,
a timer is due or a guard condition was triggered: nothing polls
(rclpy/_waiting.py, which also runs the spin threads meanwhile).

Pyodide has no threads here: MultiThreadedExecutor runs on this one thread,
and where a thread of rclpy's would block, in ``time.sleep`` inside a
callback, it runs the other callbacks that are ready meanwhile, except
those of a busy MutuallyExclusiveCallbackGroup (rclpy.callback_groups).
So an action's execute callback that sleeps still hears its cancel
request, as with rclpy's thread pool. Outside of that, ``time.sleep``
blocks in an Atomics wait (Pyodide's own spins the CPU), while the spin
threads (rclpy/_threads.py) run.
"""

import inspect
import sys
import time

from rclpy._waiting import block
from rclpy._waiting import sleep_on_bus
from rclpy._waiting import WaitSet
from rclpy.context import default_context
from rclpy.task import note_progress
from rclpy.task import Task

"""The tasks of this process, (task, entity, node), oldest first: every executor steps them."""
_TASKS = []
"""The executors inside a callback, innermost last (for time.sleep)."""
_DISPATCHING = []


class ExternalShutdownException(Exception):
    """The context was shut down while spinning."""


class ShutdownException(Exception):
    """The executor was shut down."""


class TimeoutException(Exception):
    """Nothing was ready in the time given (wait_for_ready_callbacks)."""


class ConditionReachedException(Exception):
    """The condition given to wait_for_ready_callbacks became true."""


def create_task(callback, *args, **kwargs):
    """Schedule ``callback(*args, **kwargs)`` (or a coroutine) as a Task; returns it."""
    task = Task(callback, args, kwargs)
    _TASKS.append((task, None, None))
    return task


def _wait(timeout_sec):
    """Block for at most ``timeout_sec`` (None: until the doorbell rings); spin threads run."""
    sleep_on_bus(timeout_sec)


def wait_for(subscription, timeout_sec):
    """Block until ``subscription`` has a message, for at most ``timeout_sec``."""
    wait_set = WaitSet(max(0.0, timeout_sec))
    wait_set.add('subscription', subscription._handle)
    block(wait_set)


def sleep_spins():
    """Return True when time.sleep here spins a MultiThreadedExecutor (see above)."""
    executor = _DISPATCHING[-1] if _DISPATCHING else None
    return isinstance(executor, MultiThreadedExecutor) and executor.context.ok()


def wait_a_while(seconds):
    """
    Let time pass, at most ``seconds``, for a sleep that checks its own end.

    In a MultiThreadedExecutor's callback, until the executor's next ready
    callback has run (a message for the sleeper may be among them);
    elsewhere, the whole ``seconds``, while the spin threads run.
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
        wait_a_while(left)


# in the Python worker only (Pyodide's own sleep spins a core); the build host's Python,
# which imports rclpy for a Python launch file, keeps its sleep
if sys.platform == 'emscripten':
    time.sleep = sleep


class Executor:
    """Runs the callbacks of its nodes."""

    def __init__(self, *, context=None):
        """Create an executor of ``context`` (default: the default context)."""
        self.context = context or default_context()
        self._nodes = []
        self._is_shutdown = False
        # the generator of wait_for_ready_callbacks, reused while its arguments are the same
        self._cb_iter = None
        self._last_args = None
        # True from a wait until the callbacks it found were all handed out
        self._leftovers = False
        # how many waits of this executor are on the stack
        self._waiting = 0

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
        """Stop: spin returns, no callback runs any more; the nodes are forgotten."""
        self._is_shutdown = True
        for node in list(self._nodes):
            self.remove_node(node)
        self._cb_iter = None
        self._leftovers = False
        return True

    def wake(self):
        """Nothing to wake: the only thread is the caller."""

    def spin(self):
        """Spin until the context or the executor is shut down."""
        while self.context.ok() and not self._is_shutdown:
            self.spin_once()

    def spin_until_future_complete(self, future, timeout_sec=None):
        """Spin until ``future`` is done, or ``timeout_sec`` passed."""
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        while self.context.ok() and not future.done() and not self._is_shutdown:
            left = None if end is None else end - time.monotonic()
            if left is not None and left <= 0:
                return
            self.spin_once_until_future_complete(future, left)

    def spin_once_until_future_complete(self, future, timeout_sec=None):
        """Spin once (one callback), unless ``future`` is done."""
        if not future.done():
            self.spin_once(timeout_sec=timeout_sec)

    def spin_once(self, timeout_sec=None):
        """
        Run one callback: the next ready one, waiting at most ``timeout_sec`` for it.

        None or negative: wait until there is one; 0: do not wait. An
        exception of the callback goes on up from here, as from rclpy's.
        """
        try:
            handler, _, _ = self.wait_for_ready_callbacks(timeout_sec=timeout_sec)
        except (ShutdownException, TimeoutException, ConditionReachedException):
            return
        self._run(handler)

    def _run(self, handler):
        """Run a handler of this executor; raise its exception."""
        _DISPATCHING.append(self)
        try:
            handler()
        finally:
            _DISPATCHING.pop()
        if handler.exception() is not None:
            raise handler.exception()

    def wait_for_ready_callbacks(self, timeout_sec=None, nodes=None, condition=None):
        """Return (handler, entity, node) of the next ready callback, as rclpy's does.

        ``handler`` is a Task that runs the callback when called (custom
        executors call it, or give it to a pool). One wait yields every
        callback that is ready then; the next call (with the same
        arguments) returns the next of them, and waits again when none is
        left. TimeoutException when nothing was ready in ``timeout_sec``,
        ShutdownException when the executor was shut down,
        ConditionReachedException when ``condition()`` became true, and
        ExternalShutdownException when the context was shut down during
        the wait.
        """
        args = (timeout_sec, nodes, condition)
        while True:
            if self._cb_iter is None or self._last_args != args:
                self._last_args = args
                self._leftovers = False
                self._cb_iter = self._wait_for_ready_callbacks(timeout_sec, nodes, condition)
            try:
                return next(self._cb_iter)
            except StopIteration:
                self._cb_iter = None

    def _wait_for_ready_callbacks(self, timeout_sec=None, nodes=None, condition=None):
        """Yield (handler, entity, node) for each callback ready after one wait (see above)."""
        condition = condition or (lambda: False)
        end = None if timeout_sec is None or timeout_sec < 0 else time.monotonic() + timeout_sec
        yielded = False
        while not yielded and not self._is_shutdown and not condition():
            if not self.context.ok():
                raise ShutdownException()
            nodes_to_use = self._live_nodes(nodes)
            for task, entity, node in reversed(list(_TASKS)):
                if task._may_step() and (node is None or node in nodes_to_use):
                    yielded = True
                    yield task, entity, node
            _TASKS[:] = [t for t in _TASKS if not t[0].done()]
            ready = self._gather(nodes_to_use)
            left = None if end is None else end - time.monotonic()
            ready.wait_set.limit(left)
            self._waiting += 1
            try:
                flags = block(ready.wait_set)
            finally:
                self._waiting -= 1
            note_progress()
            if self._is_shutdown:
                raise ShutdownException()
            if not self.context.ok():
                raise ExternalShutdownException()
            self._leftovers = True
            for handler in ready.handlers(self, flags):
                yielded = True
                yield handler
            self._leftovers = False
            if not yielded and end is not None and time.monotonic() >= end:
                raise TimeoutException()
        if self._is_shutdown:
            raise ShutdownException()
        if condition():
            raise ConditionReachedException()

    def _live_nodes(self, nodes=None):
        return [n for n in (self._nodes if nodes is None else nodes) if n._handle is not None]

    def _gather(self, nodes):
        """Return what the next wait is for: the nodes' entities that may run (_Ready)."""
        return _Ready(nodes, self.can_execute)

    def _wait_set(self):
        """Return what a wait of this executor is for now (for rclpy/_waiting.py's threads)."""
        if self._is_shutdown or not self.context.ok():
            return WaitSet()  # its spin returns: nothing to wait for
        nodes = self._live_nodes()
        wait_set = self._gather(nodes).wait_set
        if self._leftovers or any(task._may_step() and (node is None or node in nodes)
                                  for task, _, node in _TASKS):
            wait_set.limit(0.0)
        return wait_set

    def can_execute(self, entity):
        """Return True when a callback of ``entity`` may be handed out now (as rclpy's)."""
        if getattr(entity, '_executor_event', False):
            return False
        group = getattr(entity, 'callback_group', None)
        return group is None or group.can_execute(entity)

    def _make_handler(self, entity, node, take, call):
        """Make the Task of one callback: it takes (a message, ...) and calls back when run."""
        entity._executor_event = True

        def handler():
            try:
                taken = take(entity)
            finally:
                entity._executor_event = False
            return call(entity, taken)
        task = Task(handler)
        task._group = (getattr(entity, 'callback_group', None), entity)
        _TASKS.append((task, entity, node))
        return task


class _Ready:
    """The entities of one wait, in rclpy's order, and the handlers of those ready after it."""

    def __init__(self, nodes, can_execute):
        """Gather the nodes' entities that may run; the wait set for them."""
        self.nodes = nodes
        self.wait_set = WaitSet()
        self.events = [(h, n) for n in nodes for e in n.publishers + n.subscriptions
                       if e._handle is not None for h in getattr(e, 'event_handlers', ())
                       if can_execute(h)]
        self.subscriptions = [s for n in nodes for s in n.subscriptions
                              if s._handle is not None and can_execute(s)]
        self.clients = [c for n in nodes for c in n.clients
                        if c._handle is not None and can_execute(c)]
        self.services = [s for n in nodes for s in n.services
                         if s._handle is not None and can_execute(s)]
        self.timers = [t for n in nodes for t in n.timers
                       if not t.is_canceled() and can_execute(t)]
        self.guards = [g for n in nodes for g in n.guards if g._triggered and can_execute(g)]
        for handler, _ in self.events:
            self.wait_set.add('event', handler._handle, handler.event_type)
        for kind, entities in (('subscription', self.subscriptions), ('client', self.clients),
                               ('service', self.services)):
            for entity in entities:
                self.wait_set.add(kind, entity._handle)
        if self.guards:
            self.wait_set.limit(0.0)
        for timer in self.timers:
            self.wait_set.limit(timer._seconds_left())

    def handlers(self, executor, flags):
        """Yield (handler, entity, node) of each entity ready after the wait (flags)."""
        ready = set()
        for entity, flag in zip([h for h, _ in self.events] + self.subscriptions + self.clients
                                + self.services, flags):
            if flag:
                ready.add(id(entity))
        make = executor._make_handler
        for handler, node in self.events:
            if id(handler) in ready and executor.can_execute(handler) and \
                    handler._handle is not None:
                yield make(handler, node, _take_event, _call_event), handler, node
        for node in self.nodes:
            for timer in node.timers:
                if timer in self.timers and timer._due() and executor.can_execute(timer):
                    yield make(timer, node, _take_timer, _call_timer), timer, node
            for subscription in node.subscriptions:
                if id(subscription) in ready and executor.can_execute(subscription) and \
                        subscription._handle is not None:
                    yield (make(subscription, node, _take_message, _call_subscription),
                           subscription, node)
            for guard in node.guards:
                if guard in self.guards and guard._triggered and executor.can_execute(guard):
                    yield make(guard, node, _take_guard, _call_guard), guard, node
            for client in node.clients:
                if id(client) in ready and executor.can_execute(client) and \
                        client._handle is not None:
                    yield make(client, node, _take_response, _call_client), client, node
            for service in node.services:
                if id(service) in ready and executor.can_execute(service) and \
                        service._handle is not None:
                    yield make(service, node, _take_request, _call_service), service, node


def _take_event(handler):
    return handler._take() if handler._handle is not None else None


def _call_event(handler, status):
    if status is not None:
        return handler.callback(status)


def _take_timer(timer):
    if timer.is_canceled() or not timer._due():
        return False
    timer._advance()
    return True


def _call_timer(timer, due):
    if due:
        return timer.callback()


def _take_message(subscription):
    return subscription._take() if subscription._handle is not None else None


def _call_subscription(subscription, msg):
    if msg is not None:
        return subscription.callback(msg)


def _take_guard(guard):
    triggered, guard._triggered = guard._triggered, False
    return triggered


def _call_guard(guard, triggered):
    if triggered and guard.callback is not None:
        return guard.callback()


def _take_response(client):
    return client._take_response() if client._handle is not None else None


def _call_client(client, taken):
    if taken is not None:
        client._complete(*taken)


def _take_request(service):
    return service._take_request() if service._handle is not None else None


def _call_service(service, taken):
    """Call back with the request; send what it returns (a coroutine's result when done)."""
    if taken is None:
        return None
    request, request_id = taken
    result = service.callback(request, service.srv_type.Response())
    if inspect.iscoroutine(result):
        async def respond():
            service._respond(request_id, await result)
        return respond()
    service._respond(request_id, result)


class SingleThreadedExecutor(Executor):
    """An executor on this thread."""


class MultiThreadedExecutor(Executor):
    """rclpy's thread pool on this one thread: see the module's comment."""

    def __init__(self, num_threads=None, *, context=None):
        """Create the executor; ``num_threads`` is accepted (one thread runs the callbacks)."""
        super().__init__(context=context)
        self._num_threads = num_threads

    def spin_once_until_future_complete(self, future, timeout_sec=None):
        """Run one callback; return as soon as ``future`` is done, as rclpy's."""
        try:
            handler, _, _ = self.wait_for_ready_callbacks(timeout_sec, None, future.done)
        except (ShutdownException, TimeoutException, ConditionReachedException,
                ExternalShutdownException):
            return
        self._run(handler)
