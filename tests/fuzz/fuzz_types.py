# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The type descriptions the fuzz targets load: cdr_test_msgs, with no build.

``types.json`` as colcon_wasm.typedesc writes it for the package
(tests/data/cdr/cdr_test_msgs, every CDR feature), and ``schemas.json``,
the complete definitions the launcher hands the Foxglove and rosbridge
servers (colcon_wasm/launch/foxglove.py ``schema_texts``).
"""

import json
from pathlib import Path
import sys

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

import cdr_fastcdr  # noqa: E402, I100


def write_types(folder):
    """Write ``types.json`` and ``schemas.json`` into ``folder``; return their paths."""
    from colcon_wasm.ros2msg import Ros2MsgSchemas
    from colcon_wasm.ros2msg import SchemaError
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    types = cdr_fastcdr.load_types()
    schemas = Ros2MsgSchemas.from_documents([types])
    messages, errors = {}, {}
    for name in sorted(schemas.names()):
        try:
            messages[name] = schemas.full_text(name)
        except SchemaError as e:
            errors[name] = str(e)
    types_path = folder / 'types.json'
    schemas_path = folder / 'schemas.json'
    types_path.write_text(json.dumps(types), encoding='utf-8')
    schemas_path.write_text(json.dumps({'messages': messages, 'errors': errors}),
                            encoding='utf-8')
    return types_path, schemas_path
