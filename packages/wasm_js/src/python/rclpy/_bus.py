# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The bus, as the Python worker gives it (``_colcon_wasm_bus``, python_worker.mjs).

Messages cross to JavaScript as plain objects (Pyodide's ``to_js``) and
cdr.mjs encodes and decodes them, so Python nodes and C++ nodes share one
CDR implementation.
"""

try:
    import _colcon_wasm_bus as bus  # noqa: F401 (rclpy's modules import it from here)
    import js
    from pyodide.ffi import to_js
except ImportError as e:  # pragma: no cover - outside the runtime
    raise ImportError(
        "this rclpy runs only inside colcon-wasm's Python worker (Pyodide in a bus "
        f"worker): run the script with 'colcon-wasm run --python FILE.py' ({e})") from None


# looked up once: a lookup through js costs as much as the rest of the conversion
_from_entries = js.Object.fromEntries


def plain_to_js(value):
    """Convert a message's plain value (dicts, lists, numbers, strings) for cdr.mjs."""
    return to_js(value, dict_converter=_from_entries)


def handles_to_js(handles):
    """Convert a list of endpoint handles."""
    return to_js(list(handles))
