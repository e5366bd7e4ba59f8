# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Python console of the launcher page: a REPL on the page's bus.

Each line typed into the page's log dock (this process' standard input)
goes to an :class:`code.InteractiveConsole` with ``rclpy`` initialised and
imported; the line is echoed after its prompt, results and tracebacks go to
the log pane. End of input (Ctrl-D in the dock) ends it. Callbacks run when
the user spins: ``rclpy.spin_once(node, timeout_sec=1)``.
"""

import code
import sys

import rclpy
from rclpy.node import Node


def main():
    """Read lines until the end of input, as Python's own REPL does."""
    rclpy.init()
    console = code.InteractiveConsole(locals={'rclpy': rclpy, 'Node': Node})
    print(f'Python {sys.version.split()[0]} on the bus of this page; rclpy is imported and '
          "initialised: node = rclpy.create_node('my_node')", flush=True)
    more = False
    for line in sys.stdin:
        line = line.rstrip('\n')
        print(f"{'...' if more else '>>>'} {line}", flush=True)
        more = console.push(line)
        sys.stdout.flush()
        sys.stderr.flush()
    rclpy.try_shutdown()


if __name__ == '__main__':
    main()
