# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Python console of the launcher page: a REPL on the page's bus.

Each line typed into the page's log dock (this process' standard input)
goes to an :class:`code.InteractiveConsole` with ``rclpy`` initialised and
imported; the line is echoed after its prompt, results and tracebacks go to
the log pane. End of input (Ctrl-D in the dock) ends it. Callbacks run when
the user spins: ``rclpy.spin_once(node, timeout_sec=1)``, or all the time
with a spin thread (``threading.Thread(target=rclpy.spin, args=(node,),
daemon=True).start()``, rclpy/_threads.py): it runs while a statement sleeps
or waits, and while the console waits for the next line.
"""

import code
import os
import sys

import rclpy
from rclpy._waiting import block
from rclpy._waiting import runnable_threads
from rclpy._waiting import WaitSet
from rclpy.node import Node


def input_lines():
    """Yield the lines of standard input; the spin threads run while none is there."""
    import _colcon_wasm_bus
    pending = b''
    while True:
        while b'\n' not in pending:
            if runnable_threads():
                block(WaitSet(), done=_colcon_wasm_bus.stdin_ready)
            chunk = os.read(0, 4096)
            if not chunk:
                if pending:
                    yield pending.decode('utf-8', 'replace')
                return
            pending += chunk
        line, pending = pending.split(b'\n', 1)
        yield line.decode('utf-8', 'replace')


def main():
    """Read lines until the end of input, as Python's own REPL does."""
    rclpy.init()
    console = code.InteractiveConsole(locals={'rclpy': rclpy, 'Node': Node})
    print(f'Python {sys.version.split()[0]} on the bus of this page; rclpy is imported and '
          "initialised: node = rclpy.create_node('my_node')", flush=True)
    more = False
    for line in input_lines():
        print(f"{'...' if more else '>>>'} {line}", flush=True)
        more = console.push(line)
        sys.stdout.flush()
        sys.stderr.flush()
    rclpy.try_shutdown()


if __name__ == '__main__':
    main()
