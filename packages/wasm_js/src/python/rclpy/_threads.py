# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Threads where Python cannot start any: spin threads and an inline pool.

Pyodide's Python has no threads: ``threading.Thread.start()`` raises
``RuntimeError: can't start new thread``. Where threads cannot start,
rclpy (``_attach_to_worker``) puts two things in place; where they start
(CPython natively), nothing is replaced.

**Spin threads.** ``threading.Thread(target=rclpy.spin, args=(node,),
daemon=True).start()``, then a main loop that publishes and sleeps, is the
tutorials' pattern. A thread whose target spins (``rclpy.spin``,
``rclpy.spin_until_future_complete``, or ``spin`` /
``spin_until_future_complete`` of an executor, also through
``functools.partial``) starts as a :class:`SpinThread`: it adds the node
to the executor, as the target would, and then runs one callback at a
time wherever the program blocks: in ``time.sleep``, ``Rate.sleep``, a
clock's sleep, a spin or a wait of another executor, ``Event.wait`` and
every ``threading.Condition`` wait (queues, semaphores, barriers,
``concurrent.futures`` results), ``Thread.join``, ``wait_for_service``
(rclpy/_waiting.py). ``is_alive()`` and ``join()`` follow its spin: it ends
when the spin would return (the context shut down, the executor shut down,
the future done), and then removes the node as the target would. An
exception of a callback ends the thread and is printed as Python prints
one of a thread (``Exception in thread ...``), and the program goes on, as
natively. At the end of the script, the threads that are not daemons are
joined, as Python does before it exits. Any other target, and a subclass
that overrides ``run()``, cannot start: ``start()`` says what can. A
``Condition.wait()`` without a timeout that nothing could ever notify (no
spin thread can run) raises a ``RuntimeError`` rather than hang.

**An inline thread pool.** Executors written for rclpy hand their callbacks
to ``concurrent.futures.ThreadPoolExecutor`` (the ros2/examples custom
executor does), and would fail at their first callback. ``import rclpy``
puts :class:`InlineThreadPoolExecutor` in its place: ``submit`` runs the
call at once on the caller's thread and returns a done ``Future`` (result
or exception kept, as a pool's future keeps them). The callbacks then run
one after the other, as in rclpy's MultiThreadedExecutor here
(docs/python.md).
"""

import concurrent.futures
import concurrent.futures.thread
import functools
import inspect
import threading
import time

from rclpy._waiting import block
from rclpy._waiting import runnable_threads
from rclpy._waiting import STEPPING
from rclpy._waiting import THREADS
from rclpy._waiting import WaitSet


def threads_can_start():
    """Return True when this Python can start a thread (it starts and joins one)."""
    try:
        thread = threading.Thread(target=lambda: None, name='colcon-wasm-thread-probe')
        thread.start()
    except RuntimeError:
        return False
    thread.join()
    return True


class InlineThreadPoolExecutor(concurrent.futures.Executor):
    """``ThreadPoolExecutor``'s interface; each submitted call runs inside ``submit``."""

    def __init__(self, max_workers=None, thread_name_prefix='', initializer=None, initargs=()):
        """Accept ThreadPoolExecutor's arguments; ``initializer`` runs before the first call."""
        if max_workers is not None and max_workers <= 0:
            raise ValueError('max_workers must be greater than 0')
        if initializer is not None and not callable(initializer):
            raise TypeError('initializer must be a callable')
        self._max_workers = max_workers or 1
        self._thread_name_prefix = thread_name_prefix
        self._initializer = initializer
        self._initargs = initargs
        self._initialized = False
        self._broken = None
        self._shutdown = False

    def submit(self, fn, /, *args, **kwargs):
        """Run ``fn(*args, **kwargs)`` now; return a done Future with its result or exception."""
        if self._broken is not None:
            raise concurrent.futures.thread.BrokenThreadPool(self._broken)
        if self._shutdown:
            raise RuntimeError('cannot schedule new futures after shutdown')
        if not self._initialized:
            self._initialized = True
            if self._initializer is not None:
                try:
                    self._initializer(*self._initargs)
                except BaseException:
                    self._broken = ('A thread initializer failed, the thread pool '
                                    'is not usable anymore')
                    raise concurrent.futures.thread.BrokenThreadPool(self._broken)
        future = concurrent.futures.Future()
        future.set_running_or_notify_cancel()
        try:
            result = fn(*args, **kwargs)
        except BaseException as e:
            future.set_exception(e)
        else:
            future.set_result(result)
        return future

    def shutdown(self, wait=True, *, cancel_futures=False):
        """Refuse new calls from now on (no call is ever pending)."""
        self._shutdown = True


def install_inline_pool():
    """Where no thread can start, make ThreadPoolExecutor the inline pool (once)."""
    if concurrent.futures.ThreadPoolExecutor is InlineThreadPoolExecutor:
        return
    if threads_can_start():
        return
    concurrent.futures.ThreadPoolExecutor = InlineThreadPoolExecutor
    concurrent.futures.thread.ThreadPoolExecutor = InlineThreadPoolExecutor


WHAT_WORKS = ("Pyodide starts no threads; colcon-wasm's rclpy runs a thread whose target "
              "spins: rclpy.spin, rclpy.spin_until_future_complete, or an executor's spin or "
              'spin_until_future_complete (its callbacks run while the program sleeps or '
              'waits: time.sleep, Rate.sleep, Event.wait, Thread.join, ...; docs/python.md)')


class SpinThread:
    """
    A started thread whose target spins an executor, run where the program blocks.

    ``kind`` is what the target is: ``'rclpy.spin'`` (spins while the context
    is ok), ``'spin'`` (an executor's: also until the executor's shutdown) or
    ``'until_future'`` (until its future is done, or ``timeout_sec``).
    """

    def __init__(self, thread, kind, executor, node=None, future=None, timeout_sec=None):
        """Describe the thread's spin (start() begins it)."""
        self.thread = thread
        self.kind = kind
        self.executor = executor
        self.node = node
        self.future = future
        self._end_time = None if timeout_sec is None or timeout_sec < 0 else \
            time.monotonic() + timeout_sec
        self._remove_node = False
        self._ended = False

    def start(self):
        """Begin as the target begins: add the node to the executor."""
        if self.node is not None:
            added = self.executor.add_node(self.node)
            self._remove_node = added or self.kind == 'rclpy.spin'  # rclpy.spin always removes it
        THREADS.append(self)

    def alive(self):
        """Return True while the spin goes on; end the thread when it would have returned."""
        if self._ended:
            return False
        executor = self.executor
        if self.kind == 'rclpy.spin':
            going = executor.context.ok()
        else:
            going = executor.context.ok() and not executor._is_shutdown
            if self.kind == 'until_future':
                going = going and not self.future.done() and \
                    (self._end_time is None or time.monotonic() < self._end_time)
        if not going:
            self._end()
        return going

    def executor_waiting(self):
        """Return True while a wait of this thread's executor is on the stack (it serves it)."""
        return self.executor._waiting > 0

    def wait_set(self):
        """Return what the thread's next step waits for (rclpy/_waiting.py)."""
        wait_set = self.executor._wait_set()
        if self._end_time is not None:
            wait_set.limit(self._end_time - time.monotonic())
        return wait_set

    def step(self):
        """Run one callback of the spin, without waiting; an exception ends the thread."""
        if not self.alive():
            return
        STEPPING.append(self)
        try:
            if self.kind == 'until_future':
                self.executor.spin_once_until_future_complete(self.future, 0)
            else:
                self.executor.spin_once(timeout_sec=0)
        except SystemExit:
            self._end()  # ends the thread quietly, as in Python's threads
        except Exception as e:  # what Python prints for a thread, then the thread ends
            report_exception(self.thread, e)
            self._end()
        finally:
            STEPPING.remove(self)
        self.alive()

    def _end(self):
        """End the thread, its spin returned: remove the node as the target would."""
        if self._ended:
            return
        self._ended = True
        if self in THREADS:
            THREADS.remove(self)
        if self._remove_node:
            self.executor.remove_node(self.node)


def report_exception(thread, exception):
    """Print an exception that ended a thread, as Python does (threading.excepthook)."""
    threading.excepthook(threading.ExceptHookArgs(
        [type(exception), exception, exception.__traceback__, thread]))


def _spin_of(thread):
    """
    Return the SpinThread of a thread whose target spins, else None.

    A TypeError for arguments the target would refuse (the thread would
    fail with it) is returned to be reported.
    """
    if type(thread).run is not threading.Thread.run:
        return None
    target = getattr(thread, '_target', None)
    args = tuple(getattr(thread, '_args', ()) or ())
    kwargs = dict(getattr(thread, '_kwargs', {}) or {})
    while isinstance(target, functools.partial):
        args = tuple(target.args) + args
        kwargs = {**target.keywords, **kwargs}
        target = target.func
    import rclpy
    from rclpy.executors import Executor
    if target is rclpy.spin or target is rclpy.spin_until_future_complete:
        try:
            bound = inspect.signature(target).bind(*args, **kwargs)
        except TypeError as e:
            return e
        bound.apply_defaults()
        values = bound.arguments
        executor = values['executor'] or rclpy._global_executor()
        if target is rclpy.spin:
            return SpinThread(thread, 'rclpy.spin', executor, node=values['node'])
        return SpinThread(thread, 'until_future', executor, node=values['node'],
                          future=values['future'], timeout_sec=values['timeout_sec'])
    if inspect.ismethod(target) and isinstance(target.__self__, Executor):
        executor, function = target.__self__, target.__func__
        for name, kind in (('spin', 'spin'), ('spin_until_future_complete', 'until_future')):
            if function is getattr(Executor, name):
                try:
                    bound = inspect.signature(target).bind(*args, **kwargs)
                except TypeError as e:
                    return e
                bound.apply_defaults()
                values = bound.arguments
                return SpinThread(thread, kind, executor, future=values.get('future'),
                                  timeout_sec=values.get('timeout_sec'))
    return None


_original_start = threading.Thread.start
_original_join = threading.Thread.join
_original_is_alive = threading.Thread.is_alive
_original_condition_wait = threading.Condition.wait


def _start(self):
    """Start a spin thread (SpinThread); refuse any other target, saying what works."""
    if getattr(self, '_colcon_wasm_spin', None) is not None or self._started.is_set():
        raise RuntimeError('threads can only be started once')
    spin = _spin_of(self)
    if spin is None:
        try:
            return _original_start(self)
        except RuntimeError as e:
            target = getattr(self, '_target', None)
            what = f'the target {target!r}' if type(self).run is threading.Thread.run \
                else f'{type(self).__name__}.run()'
            raise RuntimeError(f"can't start new thread {self.name!r} with {what}: "
                               f'{WHAT_WORKS}') from e
    self._started.set()
    if isinstance(spin, TypeError):
        self._colcon_wasm_spin = SpinThread(self, 'failed', None)
        self._colcon_wasm_spin._ended = True
        report_exception(self, spin)
        return None
    self._colcon_wasm_spin = spin
    spin.start()
    return None


def _is_alive(self):
    """Return whether the thread is alive (a spin thread: while it spins)."""
    spin = getattr(self, '_colcon_wasm_spin', None)
    return _original_is_alive(self) if spin is None else spin.alive()


def _join(self, timeout=None):
    """Wait until the thread ends (a spin thread runs meanwhile), or ``timeout`` passed."""
    spin = getattr(self, '_colcon_wasm_spin', None)
    if spin is None:
        return _original_join(self, timeout)
    if spin in STEPPING:
        raise RuntimeError('cannot join current thread')
    end = None if timeout is None else time.monotonic() + max(timeout, 0)
    while spin.alive():
        left = None if end is None else end - time.monotonic()
        if left is not None and left <= 0:
            return None
        if spin not in runnable_threads():
            if left is None:
                raise RuntimeError(f'{self.name!r}.join() would wait forever: its spin cannot '
                                   'run here (a wait of its executor is in progress further '
                                   'up the stack)')
            block(WaitSet(left))
            continue
        block(WaitSet(left), done=lambda: not spin.alive())
    return None


def _condition_wait(self, timeout=None):
    """Wait until notified or ``timeout`` passed; the spin threads run meanwhile."""
    if not self._is_owned():
        raise RuntimeError('cannot wait on un-acquired lock')
    waiter = threading._allocate_lock()
    waiter.acquire()
    self._waiters.append(waiter)
    saved_state = self._release_save()
    got = [False]

    def notified():
        got[0] = got[0] or waiter.acquire(False)
        return got[0]
    try:
        end = None if timeout is None else time.monotonic() + timeout
        while not notified():
            left = None if end is None else end - time.monotonic()
            if left is not None and left <= 0:
                break
            if left is None and not runnable_threads():
                raise RuntimeError('threading.Condition.wait() (Event.wait(), Queue.get(), '
                                   '...) without a timeout would wait forever: Pyodide has '
                                   'no other thread to notify it, and no spin thread can run '
                                   'here (docs/python.md)')
            block(WaitSet(left), done=notified)
        return got[0]
    finally:
        self._acquire_restore(saved_state)
        if not got[0]:
            try:
                self._waiters.remove(waiter)
            except ValueError:
                pass


def install_spin_threads():
    """Where no thread can start, make spin targets start as SpinThreads (once; see above)."""
    if threading.Thread.start is _start or threads_can_start():
        return
    threading.Thread.start = _start
    threading.Thread.is_alive = _is_alive
    threading.Thread.join = _join
    threading.Condition.wait = _condition_wait


def join_spin_threads():
    """Join the spin threads that are not daemons, as Python does at its end (the worker's)."""
    for spin in list(THREADS):
        if not spin.thread.daemon and spin.alive():
            try:
                spin.thread.join()
            except RuntimeError:
                return
