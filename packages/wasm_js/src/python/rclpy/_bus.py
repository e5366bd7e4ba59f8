# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The bus, as the Python worker gives it (``_colcon_wasm_bus``, python_worker.mjs).

Messages cross to JavaScript as plain objects (Pyodide's ``to_js``) and
cdr.mjs encodes and decodes them, so Python nodes and C++ nodes share one
CDR implementation.

rclpy's modules are imported into the host's Pyodide memory snapshot
(pyodide_snapshot.mjs), before any bus exists and where no JavaScript
object may be held: :data:`bus` is a Python module whose functions
:func:`attach` takes from the worker's ``_colcon_wasm_bus`` when the node
starts.
"""

import threading
import types

try:
    from pyodide.ffi import to_js
except ImportError:
    # the build host's Python (a Python launch file, colcon_wasm/launch/python_launch/):
    # launch_ros imports rclpy's pure parts (names, parameters, messages); a node there
    # has no bus until one is attached (see _no_bus)
    to_js = None

# rclpy's modules import it from here; its functions come with attach()
bus = types.ModuleType('_colcon_wasm_bus', "the bus functions of this node's worker")


# the socket of a Python launch file's host (link_on_first_use), and its guard
_link_path = None
_link_lock = threading.Lock()


def link_on_first_use(path):
    """On the build host: attach the bus of the launch at ``path`` when rclpy first needs it."""
    global _link_path
    _link_path = path


def attach_host(functions):
    """Take the bus functions of the build host (rclpy/_host_link.py)."""
    for name in dir(functions):
        if not name.startswith('_'):
            setattr(bus, name, getattr(functions, name))


def _no_bus(name):
    """Attach the launch's bus on first use, or fail a bus call saying where this rclpy runs."""
    global _link_path
    if name.startswith('__'):
        raise AttributeError(name)
    with _link_lock:
        if _link_path is not None and name not in bus.__dict__:
            from rclpy import _host_link
            path, _link_path = _link_path, None
            _host_link.attach(path)
    if name in bus.__dict__:
        return bus.__dict__[name]
    raise AttributeError(
        f"rclpy: '{name}' needs the bus, and this process has none: colcon-wasm's rclpy runs "
        "nodes inside its Python worker (Pyodide on the bus: 'colcon-wasm run --python "
        "FILE.py'); on the build host (a Python launch file) it gives launch_ros its "
        'names, parameters and messages, but no node yet')


bus.__getattr__ = _no_bus

# looked up once, by attach(): a lookup through js costs as much as the rest of the conversion
_from_entries = None


def attach(functions):
    """Take the bus functions of the worker's ``_colcon_wasm_bus`` module."""
    global _from_entries
    import js
    for name in dir(functions):
        if not name.startswith('_'):
            setattr(bus, name, getattr(functions, name))
    _from_entries = js.Object.fromEntries


def plain_to_js(value):
    """Convert a message's plain value (dicts, lists, numbers, strings) for cdr.mjs."""
    return to_js(value, dict_converter=_from_entries) if to_js else value


def handles_to_js(handles):
    """Convert a list of endpoint handles."""
    return to_js(list(handles)) if to_js else list(handles)
