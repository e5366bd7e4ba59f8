# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The ``connectionGraph`` capability of ``serve --foxglove``.

Which node publishes, subscribes to and serves what, across the pages of
serve: the relay's rosapi knows it, as each page reports which of its nodes
holds which endpoint (``colcon_wasm_graph`` with ``endpoints``,
bridges/rosbridge/client.mjs), and a third-party rosbridge client stands
for one node. While a session subscribes (``subscribeConnectionGraph``),
this asks ``/rosapi/nodes`` and each node's ``/rosapi/node_details`` once a
second, and sends each subscribed session a ``connectionGraphUpdate``: the
first one complete, the next ones what changed and what was removed, as
foxglove_bridge and the Node.js server of ``run``/``launch --foxglove``
(bridges/foxglove/catalog.mjs) do. Node names are fully qualified
(``/talker``); the relay's own rosapi services are left out, as they are of
the advertised services.
"""

import threading

from colcon_core.logging import colcon_logger
from colcon_wasm.server.foxglove_link import CallError

logger = colcon_logger.getChild(__name__)

INTERVAL = 1.0
_KINDS = (('publishing', 'publishedTopics', 'publisherIds'),
          ('subscribing', 'subscribedTopics', 'subscriberIds'),
          ('services', 'advertisedServices', 'providerIds'))


def graph_update(before, after):
    """
    Return what changed between two graphs, as a ``connectionGraphUpdate``.

    A graph is ``{kind: {name: sorted node names}}`` for the kinds
    ``publishing``, ``subscribing`` (both with every topic, an empty list
    when it has none) and ``services``; ``before`` None: all of ``after``.
    """
    out = {'op': 'connectionGraphUpdate'}
    for kind, key, ids in _KINDS:
        old = (before or {}).get(kind, {})
        out[key] = [{'name': name, ids: nodes} for name, nodes in sorted(after[kind].items())
                    if old.get(name) != nodes]

    def topics(graph):
        return set(graph['publishing']) | set(graph['subscribing']) if graph else set()
    out['removedTopics'] = sorted(topics(before) - topics(after))
    out['removedServices'] = sorted(set((before or {}).get('services', {})) -
                                    set(after['services']))
    return out


class ConnectionGraph:
    """The graph by node, followed while a session of the server subscribes to it."""

    def __init__(self, server):
        """Follow the graph through the server's own relay link (``server.control``)."""
        self.server = server
        self.lock = threading.Lock()
        self.sessions = {}        # session -> the graph it was last sent (None: nothing yet)
        self._wake = threading.Event()
        self._stop = threading.Event()
        threading.Thread(target=self._loop, daemon=True).start()

    def subscribe(self, session):
        """``subscribeConnectionGraph``: the complete graph soon, then its changes."""
        with self.lock:
            self.sessions[session] = None
        self._wake.set()

    def unsubscribe(self, session):
        """``unsubscribeConnectionGraph``, or the session ended."""
        with self.lock:
            self.sessions.pop(session, None)

    def stop(self):
        """Stop following."""
        self._stop.set()
        self._wake.set()

    def _loop(self):
        while not self._stop.is_set():
            self._wake.wait(INTERVAL)
            self._wake.clear()
            with self.lock:
                wanted = bool(self.sessions)
            if not wanted or self._stop.is_set():
                continue
            try:
                graph = self.read()
            except CallError as e:
                logger.debug(f'serve --foxglove: cannot read the graph: {e}')
                continue
            self._send(graph)

    def read(self):
        """
        Ask the relay's rosapi for the graph by node.

        :returns: ``{kind: {name: sorted node names}}``
        :raises CallError: when the relay does not answer
        """
        link = self.server.control
        nodes = link.values(link.call('/rosapi/nodes', {})).get('nodes') or []
        futures = {n: link.call('/rosapi/node_details', {'node': n}) for n in nodes}
        graph = {kind: {} for kind, _, _ in _KINDS}
        for node, future in futures.items():
            details = link.values(future)
            for kind, _, _ in _KINDS:
                for name in details.get(kind) or []:
                    if not name.startswith('/rosapi/'):
                        graph[kind].setdefault(name, set()).add(node)
        # as foxglove_bridge: every topic has both lists, so a topic whose last
        # subscriber (or publisher) left is sent with an empty one
        for name in set(graph['publishing']) | set(graph['subscribing']):
            graph['publishing'].setdefault(name, set())
            graph['subscribing'].setdefault(name, set())
        return {kind: {name: sorted(nodes) for name, nodes in names.items()}
                for kind, names in graph.items()}

    def _send(self, graph):
        with self.lock:
            sessions = list(self.sessions.items())
            for session, _ in sessions:
                self.sessions[session] = graph
        for session, before in sessions:
            update = graph_update(before, graph)
            if before is None or any(v for k, v in update.items() if k != 'op'):
                session.send_json(**update)
