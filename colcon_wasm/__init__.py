# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""colcon-wasm: build ROS 2 workspaces to WebAssembly with `colcon build --wasm`."""

__version__ = '0.1.0'
