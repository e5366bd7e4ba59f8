# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy.task: Future (done, result, exception, callbacks, ``await``) and Task.

A Task runs a callback that is a coroutine (``async def``) step by step on
the executor: each ``await`` of a pending Future hands the thread back, and
the executor resumes the task once per spin until it is done, as rclpy's.

A task's exception is kept in the task (``exception()``), as rclpy's; the
executor's ``spin_once`` raises it. The executor steps a pending task again
after something happened since its last step (:func:`progress`: a future
completed, or an executor's wait returned), as rclpy's executor yields its
tasks again after each wait: a task that awaits never spins the CPU.
"""

import inspect

"""Counts what may let a pending task go on: completed futures, and executor waits."""
_progress = [0]


def progress():
    """Return the progress count (see the module's comment)."""
    return _progress[0]


def note_progress():
    """Count one more thing that may let a pending task go on."""
    _progress[0] += 1


class Future:
    """The result of an operation that completes later."""

    def __init__(self):
        """Create a pending future."""
        self._done = False
        self._cancelled = False
        self._result = None
        self._exception = None
        self._callbacks = []

    def done(self):
        """Return True when a result, an exception or a cancel was set."""
        return self._done or self._cancelled

    def cancelled(self):
        """Return True when cancelled."""
        return self._cancelled

    def cancel(self):
        """Cancel a pending future."""
        if not self._done:
            self._cancelled = True
            note_progress()
            self._run_callbacks()

    def result(self):
        """Return what completed the future; raise the exception set instead."""
        if self._exception is not None:
            raise self._exception
        return self._result

    def exception(self):
        """Return the exception that was set, or None."""
        return self._exception

    def set_result(self, result):
        """Complete with a result."""
        self._result = result
        self._done = True
        note_progress()
        self._run_callbacks()

    def set_exception(self, exception):
        """Complete with an exception."""
        self._exception = exception
        self._done = True
        note_progress()
        self._run_callbacks()

    def add_done_callback(self, callback):
        """Call ``callback(future)`` once done (now, if it is)."""
        if self.done():
            callback(self)
        else:
            self._callbacks.append(callback)

    def __await__(self):
        """Wait (in a coroutine run by the executor) until done; return the result."""
        while not self.done():
            yield
        return self.result()

    def _run_callbacks(self):
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)


class Task(Future):
    """A callback run by the executor; a coroutine one resumes at each of its awaits."""

    def __init__(self, handler, args=None, kwargs=None):
        """Wrap ``handler(*args, **kwargs)`` (a function, a coroutine function or a coroutine)."""
        super().__init__()
        self._handler = handler
        self._args = args or ()
        self._kwargs = kwargs or {}
        self._coroutine = handler if inspect.iscoroutine(handler) else None
        self._executing = False
        # (callback group, entity): each step runs inside the group, or waits for it
        self._group = None
        # the progress count at the end of the last step (None: never stepped)
        self._stepped_at = None

    def executing(self):
        """Return True while a step of the task runs (it is on the stack)."""
        return self._executing

    def _may_step(self):
        """Return True when the executor should step the task (something happened since)."""
        return not self.done() and not self._executing and self._stepped_at != progress()

    def __call__(self):
        """
        Run the task until it is done or awaits something pending.

        An exception of the callback completes the task with it (``exception()``),
        as rclpy's; a BaseException (SystemExit, ...) goes on up. A task of a
        callback group steps only while the group lets it start.
        """
        if self.done() or self._executing:
            return
        group, entity = self._group or (None, None)
        if group is not None and not group.beginning_execution(entity):
            self._stepped_at = progress()
            return
        self._executing = True
        try:
            if self._coroutine is None:
                result = self._handler(*self._args, **self._kwargs)
                if not inspect.iscoroutine(result):
                    self.set_result(result)
                    return
                self._coroutine = result
            try:
                self._coroutine.send(None)
            except StopIteration as e:
                self.set_result(e.value)
        except Exception as e:  # kept in the task, as rclpy does
            self.set_exception(e)
        finally:
            self._executing = False
            self._stepped_at = progress()
            if group is not None:
                group.ending_execution(entity)
