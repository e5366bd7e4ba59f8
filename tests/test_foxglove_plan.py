# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The --foxglove options and the schema texts the launcher hands the Node host."""

import argparse
import io
import json
import os

from colcon_wasm.launch import LaunchError
from colcon_wasm.launch.foxglove import add_foxglove_arguments
from colcon_wasm.launch.foxglove import foxglove_plan
from colcon_wasm.launch.foxglove import schema_file
from colcon_wasm.ros2msg import DELIMITER
from colcon_wasm.ros2msg import Ros2MsgSchemas
import pytest


def _args(*argv):
    parser = argparse.ArgumentParser()
    add_foxglove_arguments(parser)
    parser.add_argument('what', nargs='*')
    return parser.parse_args(list(argv))


def test_foxglove_default_address_and_queue():
    """--foxglove alone (last) listens on 127.0.0.1:8765; --foxglove-queue sets the queue."""
    assert foxglove_plan(_args('--foxglove')) == {
        'foxglove': {'host': '127.0.0.1', 'port': 8765, 'queueMessages': 10}}
    plan = foxglove_plan(_args('--foxglove', '9000', '--foxglove-queue', '3'))
    assert plan['foxglove']['port'] == 9000 and plan['foxglove']['queueMessages'] == 3
    assert foxglove_plan(_args('x')) == {}


def test_foxglove_other_host_warns_and_bad_values_are_named():
    """A non-loopback host warns; a value that is no address names --foxglove."""
    err = io.StringIO()
    plan = foxglove_plan(_args('--foxglove', '0.0.0.0:8765'), err=err)
    assert plan['foxglove']['host'] == '0.0.0.0'
    assert 'no authentication' in err.getvalue()
    with pytest.raises(LaunchError, match=r"--foxglove 'a:b' is not \[HOST:\]PORT"):
        foxglove_plan(_args('--foxglove', 'a:b'))
    with pytest.raises(LaunchError, match='--foxglove port 70000 is not a port'):
        foxglove_plan(_args('--foxglove', '70000'))


class _Space:
    def __init__(self, messages):
        self._messages = messages

    def ros2msg_schemas(self):
        return Ros2MsgSchemas(self._messages)

    def share_folders(self):
        return {}


def test_schema_file_has_full_texts_and_names_what_cannot_be_assembled():
    """The file holds rosbag2's complete texts; a type with a missing dependency is in errors."""
    messages = {
        'a/msg/Outer': {'definition': 'b/Inner inner\n', 'fields': [{'type': 'b/msg/Inner'}]},
        'b/msg/Inner': {'definition': 'int32 x\n', 'fields': [{'type': 'int32'}]},
        'c/msg/Broken': {'definition': 'd/Gone g\n', 'fields': [{'type': 'd/msg/Gone'}]},
    }
    description = {'foxglove': {'host': '127.0.0.1', 'port': 0}}
    with schema_file(description, _Space(messages)) as path:
        data = json.loads(open(path, encoding='utf-8').read())
        assert description['foxglove']['schemas'] == path
    assert data['messages']['a/msg/Outer'] == \
        f'b/Inner inner\n\n{DELIMITER}\nMSG: b/Inner\nint32 x\n'
    assert "'d/msg/Gone'" in data['errors']['c/msg/Broken']
    assert 'c/msg/Broken' not in data['messages']
    assert not os.path.exists(path)
    with schema_file({}, _Space(messages)) as nothing:
        assert nothing is None
    # the rosbridge server's rosapi (topics_and_raw_types) reads the same file
    description = {'rosbridge': {'host': '127.0.0.1', 'port': 0}}
    with schema_file(description, _Space(messages)) as path:
        assert description['rosbridge']['schemas'] == path and os.path.exists(path)
        assert 'shares' not in description['rosbridge']
