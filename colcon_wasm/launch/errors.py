# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The one error type of launch-file loading."""

from colcon_wasm.error import ColconWasmError


class LaunchError(ColconWasmError):
    """A launch file or item that cannot be run; names the file and line."""

    def __init__(self, message, path=None, line=None):
        """Format the message as ``path:line: message`` when the place is known."""
        self.path = path
        self.line = line
        location = ''
        if path is not None:
            location = f"{path}{(f':{line}' if line else '')}: "
        super().__init__(location + message)
