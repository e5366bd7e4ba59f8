# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
rclpy for colcon-wasm: the rclpy API on the wasm_js bus, in Pyodide.

A pure-Python client library (no rcl): nodes, publishers, subscriptions and
timers are bus entities of this process, messages are CDR made by the JS
runtime's cdr.mjs. What works and what does not yet: docs/python.md of
colcon-wasm.
"""

from rclpy import _bus
from rclpy import _event_loop
from rclpy import _messages
from rclpy import _native_only
from rclpy import _threads
from rclpy.context import Context  # noqa: F401 (rclpy.Context, as rclpy has it)
from rclpy.context import default_context
from rclpy.executors import SingleThreadedExecutor

__all__ = ['init', 'shutdown', 'try_shutdown', 'ok', 'spin', 'spin_once',
           'spin_until_future_complete', 'create_node', 'get_default_context']

_executor = None


def _attach_to_worker(functions):
    """
    Start rclpy on the worker's bus (the Python worker calls this before the script runs).

    rclpy is imported into the host's Pyodide snapshot before a bus exists;
    here it takes the bus functions (``functions``: the worker's
    ``_colcon_wasm_bus``) and the install's type descriptions, and puts its
    import finders, spin threads, thread pool and event loop in place.
    """
    _bus.attach(functions)
    _messages.load_descriptions(_bus.bus.types_json())
    _messages.install_finder()
    _native_only.install_finder()
    _threads.install_inline_pool()
    _threads.install_spin_threads()
    _event_loop.install_bus_event_loop()


def get_default_context():
    """Return the default context."""
    return default_context()


def init(*, args=None, context=None, domain_id=None):
    """Initialise rclpy (``args``: the command line, default sys.argv)."""
    (context or default_context()).init(args, domain_id=domain_id)


def ok(*, context=None):
    """Return True between init and shutdown."""
    return (context or default_context()).ok()


def shutdown(*, context=None):
    """Shut down: destroy the nodes; spin returns."""
    global _executor
    (context or default_context()).shutdown()
    _executor = None


def try_shutdown(*, context=None):
    """Shut down unless already shut down."""
    global _executor
    (context or default_context()).try_shutdown()
    _executor = None


def create_node(node_name, **kwargs):
    """Create a node (rclpy.node.Node)."""
    from rclpy.node import Node
    return Node(node_name, **kwargs)


def _global_executor():
    global _executor
    if _executor is None:
        _executor = SingleThreadedExecutor()
    return _executor


def spin_once(node, *, executor=None, timeout_sec=None):
    """Run one callback of ``node`` (or of the executor), waiting at most ``timeout_sec``."""
    executor = executor or _global_executor()
    added = executor.add_node(node)
    try:
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        if added:
            executor.remove_node(node)


def spin(node, executor=None):
    """Do the work of ``node`` until shutdown."""
    executor = executor or _global_executor()
    added = executor.add_node(node)
    try:
        executor.spin()
    finally:
        if added:
            executor.remove_node(node)


def spin_until_future_complete(node, future, executor=None, timeout_sec=None):
    """Do the work of ``node`` until ``future`` is done (or the timeout)."""
    executor = executor or _global_executor()
    added = executor.add_node(node)
    try:
        executor.spin_until_future_complete(future, timeout_sec=timeout_sec)
    finally:
        if added:
            executor.remove_node(node)
