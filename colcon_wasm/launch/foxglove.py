# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The Foxglove options of ``colcon-wasm run`` and ``colcon-wasm launch``.

``--foxglove [HOST:]PORT`` starts a Foxglove WebSocket protocol server
(what Foxglove and Lichtblick connect to, as to foxglove_bridge) over the
launch's bus, in the Node host (``packages/wasm_js/src/bridges/foxglove/``).
This module checks the options, turns them into the plan entry the host
reads, and writes the complete message definitions the server advertises
(rosbag2's ``ros2msg`` text, :mod:`colcon_wasm.ros2msg`) into a JSON file
the entry names: the texts are assembled here only, never in JavaScript.
"""

import contextlib
import json
import os
import tempfile

from colcon_wasm.launch.rosbridge import _positive_int
from colcon_wasm.launch.rosbridge import DEFAULT_HOST
from colcon_wasm.launch.rosbridge import is_loopback
from colcon_wasm.launch.rosbridge import parse_listen_address
from colcon_wasm.ros2msg import SchemaError

DEFAULT_PORT = 8765
DEFAULT_QUEUE_MESSAGES = 10


def add_foxglove_arguments(parser):
    """Add the Foxglove options."""
    parser.add_argument(
        '--foxglove', nargs='?', const=f'{DEFAULT_HOST}:{DEFAULT_PORT}',
        metavar='[HOST:]PORT',
        help="Serve the Foxglove WebSocket protocol (Foxglove, Lichtblick) over the nodes' bus "
             f'on HOST:PORT (default {DEFAULT_HOST}:{DEFAULT_PORT}; only this machine unless '
             'HOST names another address; port 0 picks a free one)')
    parser.add_argument(
        '--foxglove-queue', type=_positive_int, metavar='N',
        help='Messages of one topic waiting for a slow Foxglove client before the oldest is '
             f'dropped (default {DEFAULT_QUEUE_MESSAGES}; each topic has its own queue)')


def foxglove_plan(args, *, err=None):
    """
    Turn the Foxglove options into the plan entry for the Node host.

    The entry's ``schemas`` file is added by :func:`schema_file`, once the
    install space is known.

    :returns: ``{'foxglove': {...}}``, or an empty dict without ``--foxglove``
    :raises LaunchError: for a bad option
    """
    if not getattr(args, 'foxglove', None):
        return {}
    host, port = parse_listen_address(args.foxglove, '--foxglove', DEFAULT_PORT)
    if not is_loopback(host) and err is not None:
        print(f'warning: --foxglove listens on {host}: other machines can see and '
              'drive your nodes (the Foxglove protocol has no authentication)', file=err)
    return {'foxglove': {
        'host': host, 'port': port,
        'queueMessages': getattr(args, 'foxglove_queue', None) or DEFAULT_QUEUE_MESSAGES,
    }}


def schema_texts(install_space):
    """
    Assemble the complete definition of every message type of an install.

    :returns: ``{'messages': {type: text}, 'errors': {type: why}}``; a type
      whose definition cannot be assembled (a dependency missing, an old
      types.json) is in ``errors``, and the server names it when a topic
      uses it
    """
    schemas = install_space.ros2msg_schemas()
    messages = {}
    errors = {}
    for name in sorted(schemas.names()):
        try:
            messages[name] = schemas.full_text(name)
        except SchemaError as e:
            errors[name] = str(e)
    return {'messages': messages, 'errors': errors}


@contextlib.contextmanager
def schema_file(description, install_space):
    """
    Write the schema texts for a plan's Foxglove and rosbridge servers, for the host's run.

    Each server's entry gets the file as ``schemas``: the Foxglove server's
    channel schemas, the rosbridge server's rosapi ``topics_and_raw_types``.
    The Foxglove entry also gets ``shares``, each package's share folder,
    from which the server answers ``fetchAsset`` of ``package://`` URIs.

    Without a ``foxglove`` or ``rosbridge`` entry in ``description`` this
    does nothing. The file is removed when the block ends.
    """
    entries = [description[key] for key in ('foxglove', 'rosbridge') if description.get(key)]
    if not entries:
        yield None
        return
    fd, path = tempfile.mkstemp(prefix='colcon-wasm-schemas-', suffix='.json')
    try:
        with os.fdopen(fd, 'w', encoding='utf-8') as f:
            json.dump(schema_texts(install_space), f)
        for entry in entries:
            entry['schemas'] = path
        if description.get('foxglove'):
            # fetchAsset serves package:// files from these (as the ament index resolves them)
            description['foxglove']['shares'] = {
                name: str(share) for name, share in install_space.share_folders().items()}
        yield path
    finally:
        with contextlib.suppress(OSError):
            os.unlink(path)
