# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""rclpy.task: Future (done, result, exception, callbacks)."""


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
        self._run_callbacks()

    def set_exception(self, exception):
        """Complete with an exception."""
        self._exception = exception
        self._done = True
        self._run_callbacks()

    def add_done_callback(self, callback):
        """Call ``callback(future)`` once done (now, if it is)."""
        if self.done():
            callback(self)
        else:
            self._callbacks.append(callback)

    def _run_callbacks(self):
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)
