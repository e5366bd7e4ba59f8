# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The rosbridge connections of ``serve --foxglove`` to serve's relay.

:class:`RelayLink` is one WebSocket client of the relay (relay.py): it
sends rosbridge requests, and hands every message the relay sends to a
callback, except the answers to its own calls (:meth:`RelayLink.call`),
which complete a :class:`concurrent.futures.Future`. The Foxglove server
(foxglove_relay.py) has two: one for the data its clients subscribe to
(``cbor-raw``), and one for its own requests (rosapi, the nodes' parameter
services, ``/parameter_events`` in JSON), so that the relay, which sends one
form of a topic per client, gives each what it needs.
"""

from concurrent.futures import Future
from concurrent.futures import TimeoutError as FutureTimeout
import itertools
import json
import threading

import cbor2
from colcon_wasm.error import ColconWasmError
from colcon_wasm.server.websocket import connect

CALL_TIMEOUT = 10.0
"""The node this server stands for in the relay's graph (as run/launch --foxglove's)."""
NODE = '/foxglove_bridge'


class CallError(ColconWasmError):
    """A call through the relay that failed: no such service, no answer, an error."""


class RelayLink:
    """One rosbridge connection to serve's relay."""

    def __init__(self, url, on_message, node=NODE):
        """
        Connect, and tell the relay which node this link stands for.

        ``on_message(msg)`` gets each decoded relay message (reader thread)
        but the answers to :meth:`call`.
        """
        self.connection = connect(url, timeout=10, max_message_bytes=256 << 20,
                                  max_queued_bytes=64 << 20)
        self._on_message = on_message
        self._calls = {}      # call id -> Future
        self._ids = itertools.count(1)
        self._lock = threading.Lock()
        # no 'version': this client publishes JSON only (the relay asks no forms of it)
        self.send(op='colcon_wasm_graph', nodes=[node])
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        def receive(data, binary):
            try:
                msg = cbor2.loads(data) if binary else json.loads(data)
            except (ValueError, cbor2.CBORDecodeError):
                return
            if not isinstance(msg, dict):
                return
            if msg.get('op') == 'service_response':
                with self._lock:
                    future = self._calls.pop(str(msg.get('id', '')), None)
                if future is not None:
                    future.set_result(msg)
                    return
            self._on_message(msg)
        try:
            self.connection.run(receive)
        finally:
            with self._lock:
                pending, self._calls = list(self._calls.values()), {}
            for future in pending:
                future.set_exception(CallError('the connection to the relay closed'))

    def send(self, **msg):
        """Send one rosbridge request."""
        self.connection.send(json.dumps(msg))

    def call(self, service, args, timeout=CALL_TIMEOUT):
        """
        Call a service through the relay (JSON arguments).

        :returns: a Future of the relay's ``service_response`` (``result``
          false when the service does not exist, failed or did not answer
          within ``timeout`` s: the relay says so in ``values``)
        """
        future = Future()
        rid = f'foxglove-rpc:{next(self._ids)}'
        with self._lock:
            self._calls[rid] = future
        future.call_id = rid
        self.send(op='call_service', service=service, args=args, id=rid, timeout=timeout)
        return future

    def values(self, future, timeout=CALL_TIMEOUT):
        """
        Wait for a call's answer.

        :returns: its ``values``
        :raises CallError: with the relay's text when the call failed, or
          when no answer came (the relay times calls out itself; this is a
          bound on a relay that went away)
        """
        try:
            msg = future.result(timeout + 2)
        except FutureTimeout:
            with self._lock:
                self._calls.pop(getattr(future, 'call_id', None), None)
            raise CallError(f'no answer from the relay within {timeout + 2:g} s') from None
        if not msg.get('result'):
            raise CallError(str(msg.get('values') or f"{msg.get('service')} failed"))
        values = msg.get('values')
        return values if isinstance(values, dict) else {}

    def close(self):
        """Close the connection."""
        self.connection.close(1000, 'stopping')
