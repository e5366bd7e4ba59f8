# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The bus of the build host's rclpy: its ``_colcon_wasm_bus`` functions over a socket.

A Python launch file runs on the build host (colcon_wasm/launch/python_launch/),
and launch_ros makes a ROS node there for LoadComposableNodes, LifecycleNode
and its ROS events. This rclpy's bus functions then run in the launch's
Node.js host (launch/host_link_worker.mjs: one bus process, ``launch_ros`` in
the graph), called over the launch's socket; their answers come back as
JSON. Several threads may call at once (launch's loop and the spin thread
of launch_ros' ROS adapter): each call waits for its own answer.
"""

import itertools
import json
import socket
import sys
import threading

#: what JSON cannot carry safely: integers beyond 2**53
_SAFE = 2 ** 53


def _to_wire(value):
    """Make a plain value JSON-safe: big integers as ``{'$int': 'digits'}``, arrays as lists."""
    if isinstance(value, bool) or value is None or isinstance(value, (float, str)):
        return value
    if isinstance(value, int):
        return value if -_SAFE < value < _SAFE else {'$int': str(value)}
    if isinstance(value, dict):
        return {k: _to_wire(v) for k, v in value.items()}
    if isinstance(value, (bytes, bytearray, memoryview)):
        return list(bytes(value))
    if hasattr(value, 'tolist'):  # array.array
        return [_to_wire(v) for v in value.tolist()]
    return [_to_wire(v) for v in value]


def _plain(value):
    """Turn an answer's JSON back into plain Python (``{'$int': ...}`` into int)."""
    if isinstance(value, list):
        return [_plain(v) for v in value]
    if isinstance(value, dict):
        if len(value) == 1 and isinstance(value.get('$int'), str):
            return int(value['$int'])
        return {k: _plain(v) for k, v in value.items()}
    return value


class JsLike(dict):
    """An answer's object as rclpy reads a JavaScript one: fields by attribute, ``to_py()``."""

    def __getattr__(self, name):
        """Return a field, objects wrapped alike."""
        try:
            return _wrap(self[name])
        except KeyError:
            raise AttributeError(name) from None

    def to_py(self):
        """Return the object as plain Python."""
        return _plain(self)


def _wrap(value):
    return JsLike(value) if isinstance(value, dict) and '$int' not in value else _plain(value)


class HostLink:
    """A connection to the launch's Node.js host that calls the bus functions."""

    def __init__(self, path):
        """Connect to the launch's socket and ask for a bus process."""
        self._socket = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self._socket.connect(path)
        self._reader = self._socket.makefile('r', encoding='utf-8')
        self._send_lock = threading.Lock()
        self._ids = itertools.count(1)
        self._pending = {}
        self._send({'op': 'link'})
        first = json.loads(self._reader.readline() or 'null')
        if not first or first.get('ev') != 'linked':
            raise RuntimeError(f'the launch host at {path} gave no bus to rclpy: {first!r}')
        threading.Thread(target=self._read, name='colcon-wasm host link', daemon=True).start()

    def _send(self, message):
        data = (json.dumps(message) + '\n').encode()
        with self._send_lock:
            self._socket.sendall(data)

    def _read(self):
        for line in self._reader:
            answer = json.loads(line)
            pending = self._pending.pop(answer.get('id'), None)
            if pending is not None:
                pending[1] = answer
                pending[0].set()
        for event, _ in list(self._pending.values()):  # the host has gone
            event.set()

    def call(self, fn, *args):
        """Call a bus function and return its answer."""
        number = next(self._ids)
        pending = [threading.Event(), None]
        self._pending[number] = pending
        self._send({'id': number, 'fn': fn, 'args': _to_wire(list(args))})
        pending[0].wait()
        answer = pending[1]
        if answer is None:
            raise RuntimeError(f"rclpy: the launch's bus has gone (calling '{fn}')")
        if 'error' in answer:
            error = answer['error']
            kind = TypeError if error.get('name') == 'TypeError' else RuntimeError
            raise kind(error.get('message', 'the bus call failed'))
        return _wrap(answer['result'])


#: the bus functions rclpy calls (python/bus_module.mjs), all through the link
FUNCTIONS = (
    'create_node', 'destroy_node', 'create_publisher', 'create_subscription',
    'destroy_endpoint', 'publish', 'take', 'create_service', 'create_client', 'take_request',
    'send_response', 'send_request', 'take_response', 'server_available', 'wait_for_server',
    'matched_count', 'event_status', 'assert_liveliness', 'graph_version', 'wait', 'graph_json',
    'has_type')


class HostFunctions:
    """The ``_colcon_wasm_bus`` functions of the build host: the link's, and local ones."""

    def __init__(self, link):
        """Bind each bus function to ``link``."""
        for name in FUNCTIONS:
            setattr(self, name, lambda *args, _name=name: link.call(_name, *args))

    @staticmethod
    def log(stream, text):
        """Print a line of rclpy's logging, as the process' own output."""
        print(text, file=sys.stderr if stream == 'stderr' else sys.stdout, flush=True)

    @staticmethod
    def stdin_ready():
        """Say that no standard input is there: the launch's rclpy reads none."""
        return False


def attach(path):
    """Give rclpy the bus of the launch at ``path`` (its Unix socket)."""
    from rclpy import _bus
    _bus.attach_host(HostFunctions(HostLink(path)))
