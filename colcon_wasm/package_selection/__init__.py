# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0
