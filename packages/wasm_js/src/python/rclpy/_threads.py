# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A thread pool that runs its work inline, where Python cannot start threads.

Pyodide's Python has no threads: ``threading.Thread.start()`` raises
``RuntimeError: can't start new thread``. Executors written for rclpy hand
their callbacks to ``concurrent.futures.ThreadPoolExecutor`` (the
ros2/examples custom executor does), and would fail at their first
callback. Where threads cannot start, ``import rclpy`` puts
:class:`InlineThreadPoolExecutor` in its place: ``submit`` runs the call at
once on the caller's thread and returns a done ``Future`` (result or
exception kept, as a pool's future keeps them). The callbacks then run one
after the other, as in rclpy's MultiThreadedExecutor here (docs/python.md).
Where threads start (CPython natively), nothing is replaced.
"""

import concurrent.futures
import concurrent.futures.thread
import threading


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
