# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Record and replay the bus in rosbag2's MCAP layout.

``colcon-wasm launch|run … --record FILE.mcap`` and ``colcon-wasm play FILE``
(``launch … --play FILE``). The Node host taps the bus and publishes
(``packages/wasm_js/src/bridges/record/``); this package reads and writes
the files with Foxglove's ``mcap`` package, and the two talk over a pipe
(:mod:`colcon_wasm.record.frames`). See docs/record.md.
"""

from colcon_wasm.error import ColconWasmError


class BagError(ColconWasmError):
    """A bag that cannot be read or written (the text names the file and where)."""


__all__ = ['BagError']
