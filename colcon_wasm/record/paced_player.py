# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Play one bag in its recorded timing, with pause, step, seek and rate.

The page's replay (``/bag`` of ``colcon-wasm serve``) drives it: a thread
reads the file (:func:`colcon_wasm.record.bag_reader.read_messages`, so a
truncated or corrupt file plays up to the damage and is then named) and
hands each message to ``send(channel, bag_ms, data)`` when it is due. The
clock is rebased at every resume, seek and rate change, so a pause never
makes the next messages burst out.
"""

import threading
import time

from colcon_wasm.record import BagError
from colcon_wasm.record.bag_reader import read_messages


class BagSpan:
    """What one pass over a bag found: first and last log time, count, error."""

    def __init__(self, path, on_topic):
        """
        Read the bag once (no message is sent).

        :param on_topic: called once per channel; returns whether it is played
        """
        self.start = None
        self.end = None
        self.count = 0
        self.error = None
        try:
            for _, log_time, _, _ in read_messages(path, on_topic):
                if self.start is None:
                    self.start = log_time
                self.end = log_time
                self.count += 1
        except BagError as e:
            self.error = str(e)


class PacedPlayer:
    """
    A bag being played: ``play``, ``pause``, ``step``, ``seek``, ``set_rate``.

    ``send(channel, bag_ms, data)`` gets each message (``bag_ms``: its time
    from the bag's first message); ``report(state)`` gets ``{'state',
    'position_ms', 'sent'}`` on each change and a few times a second, and
    ``{'state': 'ended', ...}`` (with ``error`` for a damaged file) at the end.
    With ``set_clock(hz)``, ``tick(time_ns)`` gets the bag time (since the
    epoch) ``hz`` times a second while playing, and after each step and seek,
    for a ``/clock`` that ``use_sim_time`` nodes follow.
    """

    REPORT_INTERVAL = 0.2

    def __init__(self, path, channels, start, send, report, tick=None):
        """
        Prepare a paused player.

        :param channels: topic name -> channel id of the played topics
        :param start: the bag's first log time (ns), the origin of positions
        """
        self.path = path
        self.channels = channels
        self.start = start
        self.send = send
        self.report = report
        self.tick = tick or (lambda time_ns: None)
        self.clock_hz = 0.0
        self.rate = 1.0
        self.state = 'paused'
        self.sent = 0
        self._cond = threading.Condition()
        self._changed = False
        self._steps = 0
        self._seek = 0
        self._closed = False
        self._messages = None
        self._pending = None
        self._position = 0
        self._wall0 = self._bag0 = 0
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    # ------------------------------------------------------------------ controls

    def play(self):
        """Play from where it stands (from the start again once it ended)."""
        with self._cond:
            if self.state == 'ended':
                self._seek = 0
            self.state = 'playing'
            self._changed = True
            self._cond.notify_all()

    def pause(self):
        """Stop sending; the position stays."""
        with self._cond:
            if self.state == 'playing':
                self.state = 'paused'
            self._changed = True
            self._cond.notify_all()

    def step(self):
        """Pause, and send the next message at once."""
        with self._cond:
            if self.state == 'playing':
                self.state = 'paused'
            self._steps += 1
            self._changed = True
            self._cond.notify_all()

    def seek(self, position_ms):
        """Go to ``position_ms`` from the start; nothing before it is sent."""
        with self._cond:
            self._seek = max(0.0, float(position_ms))
            if self.state == 'ended':
                self.state = 'paused'
            self._changed = True
            self._cond.notify_all()

    def set_rate(self, rate):
        """Play ``rate`` times as fast as recorded (> 0)."""
        if not rate > 0:
            raise ValueError(f'the rate must be > 0, not {rate!r}')
        with self._cond:
            self.rate = float(rate)
            self._changed = True
            self._cond.notify_all()

    def set_clock(self, hz):
        """Publish the bag time ``hz`` times a second while playing (0: no clock)."""
        if not hz >= 0:
            raise ValueError(f'the clock rate must be >= 0, not {hz!r}')
        with self._cond:
            self.clock_hz = float(hz)
            self._changed = True
            self._cond.notify_all()

    def close(self):
        """Stop the thread."""
        with self._cond:
            self._closed = True
            self._cond.notify_all()
        self._thread.join(timeout=5)

    # ------------------------------------------------------------------ thread

    def _open(self, position_ms):
        """Read from the start, skipping what comes before ``position_ms``."""
        self._messages = read_messages(self.path, lambda t: t.name in self.channels)
        self._pending = None
        target = self.start + int(position_ms * 1e6)
        while True:
            message = self._next()
            if message is None or message[1] >= target:
                self._pending = message
                break
        self._position = position_ms

    def _next(self):
        try:
            return next(self._messages, None)
        except BagError as e:
            self._error = str(e)
            return None

    def _rebase(self):
        self._wall0 = time.monotonic()
        self._bag0 = self._pending[1] if self._pending else 0

    def _state(self, **extra):
        return dict({'state': self.state, 'position_ms': self._position, 'sent': self.sent,
                     'rate': self.rate}, **extra)

    def _run(self):
        self._error = None
        while True:
            with self._cond:
                while not self._closed and not self._changed and (
                        self.state != 'playing' or self._pending is None) and \
                        self._messages is not None:
                    self._cond.wait(self.REPORT_INTERVAL)
                if self._closed:
                    return
                seek, self._seek = self._seek, None
                steps, self._steps = self._steps, 0
                self._changed = False
                state = self.state
            if seek is not None or self._messages is None:
                self._error = None
                self._open(seek or 0.0)
            if self._pending is not None:
                self._rebase()
            for _ in range(steps):
                if self._pending is None:
                    break
                self._clock_at(self._pending[1])
                self._emit(self._pending)
                self._pending = self._next()
            if seek is not None and self._pending is not None:
                self._clock_at(self._pending[1])
            if state == 'playing':
                self._play_until_changed()
            if self._pending is None and self._messages is not None:
                with self._cond:
                    self.state = 'ended'
                self.report(self._state(**({'error': self._error} if self._error else {})))
                with self._cond:
                    while not self._closed and not self._changed:
                        self._cond.wait()
                continue
            self.report(self._state())

    def _clock_at(self, time_ns):
        if self.clock_hz > 0:
            self.tick(int(time_ns))

    def _play_until_changed(self):
        last_report = time.monotonic()
        next_tick = time.monotonic()
        while self._pending is not None:
            due = self._wall0 + (self._pending[1] - self._bag0) / 1e9 / self.rate
            with self._cond:
                while not self._changed and not self._closed:
                    now = time.monotonic()
                    if self.clock_hz > 0 and now >= next_tick:
                        self.tick(int(self._bag0 + (now - self._wall0) * self.rate * 1e9))
                        next_tick = now + 1.0 / self.clock_hz
                    left = due - now
                    if left <= 0:
                        break
                    wait = min(left, self.REPORT_INTERVAL)
                    if self.clock_hz > 0:
                        wait = min(wait, max(0.0, next_tick - now))
                    self._cond.wait(wait)
                if self._changed or self._closed:
                    return
            self._emit(self._pending)
            self._pending = self._next()
            now = time.monotonic()
            if now - last_report >= self.REPORT_INTERVAL:
                self.report(self._state())
                last_report = now

    def _emit(self, message):
        topic, log_time, _, data = message
        self._position = (log_time - self.start) / 1e6
        self.send(self.channels[topic.name], self._position, data)
        self.sent += 1
