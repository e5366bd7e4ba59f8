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

import types

try:
    from pyodide.ffi import to_js
except ImportError as e:  # pragma: no cover - outside the runtime
    raise ImportError(
        "this rclpy runs only inside colcon-wasm's Python worker (Pyodide in a bus "
        f"worker): run the script with 'colcon-wasm run --python FILE.py' ({e})") from None

# rclpy's modules import it from here; its functions come with attach()
bus = types.ModuleType('_colcon_wasm_bus', "the bus functions of this node's worker")

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
    return to_js(value, dict_converter=_from_entries)


def handles_to_js(handles):
    """Convert a list of endpoint handles."""
    return to_js(list(handles))
