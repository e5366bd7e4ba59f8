# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The subscriptions of the rosbridge relay (relay.py): combination, throttle, queue, forms.

As the Node.js server's topics.mjs does them: one subscription per topic and
client; several subscribe requests (ids) combine to the lowest
``throttle_rate``, ``queue_length`` and ``fragment_size`` and the "largest"
``compression`` (cbor-raw > cbor > png > none). ``throttle_rate`` alone
drops what comes within the window; with ``queue_length`` the last n wait
and one is sent per ``throttle_rate`` (and only while the client's socket
holds less than a high-water mark, so a slow client gets the newest
messages, not a backlog). The waits are kept by one scheduler thread that
sleeps on a condition until the next one is due (or a socket drains).

A ``Message`` is one ``publish`` as it came: a JSON form or a CDR form
(cbor-raw). Its outgoing forms (JSON text, cbor, cbor-raw, png) are built
once however many clients get it (``ttl`` apart, which is what is left of
it when each copy leaves).
"""

import collections
import heapq
import itertools
import json
import math
import threading
import time

from colcon_wasm.server.relay_forms import cbor_raw_publish
from colcon_wasm.server.relay_forms import COMPRESSION_RANK
from colcon_wasm.server.relay_forms import FormError
from colcon_wasm.server.relay_forms import fragments
from colcon_wasm.server.relay_forms import png_message


class Message:
    """One published message: ``json`` (a dict) or ``cdr`` (bytes, with secs/nsecs)."""

    def __init__(self, topic, type_name, *, json_msg=None, cdr=None, secs=None, nsecs=None,
                 ttl=None):
        """Keep the message; ``ttl`` is the ms it had left when it came."""
        self.topic = topic
        self.type = type_name
        self.json = json_msg
        self.cdr = cdr
        if cdr is not None and not (isinstance(secs, int) and isinstance(nsecs, int)):
            now = time.time()
            secs, nsecs = int(now), int((now % 1) * 1e9)
        self.secs, self.nsecs = secs, nsecs
        self.ttl = ttl
        self.arrived = time.monotonic()
        self._text = None
        self._cbor = None
        self._raw = None

    def ttl_left(self, now):
        """Return the milliseconds of its lifespan left (None without one; <= 0 when stale)."""
        if self.ttl is None:
            return None
        return self.ttl - (now - self.arrived) * 1000.0

    def text(self, ttl):
        """Return the JSON text of its ``publish``."""
        if self._text is None:
            self._text = json.dumps({'op': 'publish', 'topic': self.topic, 'msg': self.json},
                                    separators=(',', ':'))
        if ttl is None:
            return self._text
        return f'{self._text[:-1]},"ttl":{ttl}}}'

    def cbor(self, forms, ttl):
        """Return the cbor ``publish`` (FormError when the type is not described)."""
        if ttl is not None:
            return forms.cbor_publish(self.topic, self.type, self.json, ttl)
        if self._cbor is None:
            self._cbor = forms.cbor_publish(self.topic, self.type, self.json)
        return self._cbor

    def cbor_raw(self, ttl):
        """Return the cbor-raw ``publish`` of its CDR bytes."""
        if ttl is not None:
            return cbor_raw_publish(self.topic, self.cdr, self.secs, self.nsecs, ttl)
        if self._raw is None:
            self._raw = cbor_raw_publish(self.topic, self.cdr, self.secs, self.nsecs)
        return self._raw


class Subscription:
    """One client's subscription to one topic (all its subscribe requests)."""

    def __init__(self, peer, topic, type_name):  # noqa: D107
        self.peer = peer
        self.topic = topic
        self.type = type_name
        self.requests = {}
        self.throttle = 0.0
        self.queue_length = 0
        self.fragment_size = None
        self.compression = 'none'
        self.queue = collections.deque()
        self.last = -math.inf
        self.scheduled = False
        self.closed = False
        self.warned = set()

    def update(self):
        """Combine the requests as rosbridge does; return what the queue must drop."""
        r = list(self.requests.values())
        self.throttle = min(x['throttle'] for x in r) / 1000.0
        self.queue_length = min(x['queue_length'] for x in r)
        sizes = [x['fragment_size'] for x in r if x['fragment_size']]
        self.fragment_size = min(sizes) if sizes else None
        self.compression = max((x['compression'] for x in r), key=COMPRESSION_RANK.get)
        dropped = 0
        while self.queue_length and len(self.queue) > self.queue_length:
            self.queue.popleft()
            dropped += 1
        return dropped


class Scheduler:
    """Send each waiting subscription's next message when it is due (one thread, a condition)."""

    def __init__(self, lock, flush):
        """``flush(sub)`` runs under ``lock`` when ``sub`` is due."""
        self.cond = threading.Condition(lock)
        self.flush = flush
        self.heap = []
        self.seq = itertools.count()
        self.stopped = False
        threading.Thread(target=self._loop, daemon=True, name='relay-scheduler').start()

    def at(self, when, sub):
        """Flush ``sub`` at ``when`` (time.monotonic); the caller holds the lock."""
        sub.scheduled = True
        heapq.heappush(self.heap, (when, next(self.seq), sub))
        self.cond.notify()

    def stop(self):
        """End the thread."""
        with self.cond:
            self.stopped = True
            self.cond.notify()

    def _loop(self):
        with self.cond:
            while not self.stopped:
                now = time.monotonic()
                while self.heap and self.heap[0][0] <= now:
                    _, _, sub = heapq.heappop(self.heap)
                    sub.scheduled = False
                    if not sub.closed:
                        self.flush(sub)
                self.cond.wait(self.heap[0][0] - now if self.heap else None)


class Topics:
    """Routing of messages to subscriptions, with their forms and waits."""

    def __init__(self, relay):  # noqa: D107
        self.relay = relay
        self.scheduler = Scheduler(relay.lock, self.flush)
        self.high_water = min(1 << 20, relay.max_queued_bytes >> 2)
        self._fragment_ids = itertools.count(1)

    def offer(self, sub, m):
        """Offer a message to ``sub``: send it, drop it (throttle) or queue it (queue_length)."""
        now = time.monotonic()
        if not sub.queue_length:
            if sub.throttle and now - sub.last < sub.throttle:
                return
            sub.last = now
            self.deliver(sub, m, now)
            return
        sub.queue.append(m)
        if len(sub.queue) > sub.queue_length:
            sub.queue.popleft()
            self.relay.stats['dropped'] += 1
        self.flush(sub)

    def flush(self, sub, everything=False):
        """Send what ``sub``'s queue holds as throttle_rate and the socket allow."""
        if sub.scheduled and not everything:
            return
        conn = sub.peer.conn
        while sub.queue and not sub.closed:
            now = time.monotonic()
            if not everything:
                wait = sub.last + sub.throttle - now if sub.throttle else 0
                if wait > 0:
                    self.scheduler.at(now + wait, sub)
                    return
                if conn.queued_bytes >= self.high_water:
                    sub.peer.draining.add(sub)
                    if conn.watch_drain(self.high_water) or conn.closed:
                        return
                    sub.peer.draining.discard(sub)
            sub.last = now
            self.deliver(sub, sub.queue.popleft(), now)

    def drained(self, peer):
        """Flush what waited for the peer's socket, now below the high-water mark."""
        with self.relay.lock:
            subs, peer.draining = peer.draining, set()
            for sub in subs:
                self.flush(sub)

    def close(self, sub):
        """End a subscription."""
        sub.closed = True
        sub.queue.clear()
        sub.peer.draining.discard(sub)

    def deliver(self, sub, m, now):
        """Send one message to ``sub`` in the form it asked for."""
        peer = sub.peer
        ttl = m.ttl_left(now)
        if ttl is not None:
            if ttl <= 0:
                self.relay.stats['expired'] += 1
                return
            ttl = max(1, int(round(ttl)))
        if m.cdr is not None:
            peer.send(m.cbor_raw(ttl))
            return
        compression = sub.compression
        if compression == 'cbor':
            try:
                peer.send(m.cbor(self.relay.forms, ttl))
                return
            except FormError as e:
                self._warn(sub, 'cbor', f'cannot build the cbor form of a message of {sub.topic} '
                                        f'({m.type}): {e}; it is sent as JSON')
        elif compression == 'cbor-raw' and peer.version < 2:
            self._warn(sub, 'cbor-raw', f'the publisher of {sub.topic} gives no CDR form (it '
                                        'publishes JSON), so the relay forwards its messages as '
                                        'JSON (compression none)')
        text = m.text(ttl)
        if compression == 'png':
            text = png_message(text)
        fid = None
        if sub.fragment_size and len(text) > sub.fragment_size:
            fid = f'fragment:relay:{peer.number}:{next(self._fragment_ids)}'
        for part in fragments(text, sub.fragment_size, fid):
            peer.send(part)

    def _warn(self, sub, what, text):
        if what not in sub.warned:
            sub.warned.add(what)
            sub.peer.status('warning', text, next(iter(sub.requests), None))
