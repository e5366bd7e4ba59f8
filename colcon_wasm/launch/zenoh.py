# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The Zenoh option of ``colcon-wasm run`` and ``colcon-wasm launch``.

``--zenoh ENDPOINT`` joins the launch's nodes to a ROS 2 graph of rmw_zenoh
participants through a Zenoh router (``packages/wasm_js/src/bridges/zenoh/``),
with the zenoh-pico build of the ``zenoh_wasm_gateway`` package of the
install space. This module checks the option and finds that build.
"""

import os
import re

from colcon_wasm.launch.errors import LaunchError

"""The package whose share folder holds the zenoh-pico session module."""
GATEWAY_PACKAGE = 'zenoh_wasm_gateway'
"""The module's file name in that folder."""
GATEWAY_MODULE = 'zenoh_session.mjs'

_ENDPOINT = re.compile(r'^(ws|tcp)/(\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9_.-]+):(\d{1,5})$')


def add_zenoh_arguments(parser):
    """Add the Zenoh options."""
    parser.add_argument(
        '--zenoh', metavar='ENDPOINT',
        help='Join the nodes to the ROS 2 graph of a Zenoh router, speaking rmw_zenoh '
             '(ws/HOST:PORT for its WebSocket listener, tcp/HOST:PORT for its TCP one, '
             'e.g. tcp/127.0.0.1:7447; docs/zenoh.md)')


def parse_endpoint(text):
    """
    Check a Zenoh endpoint (``ws/HOST:PORT`` or ``tcp/HOST:PORT``).

    :returns: the endpoint
    :raises LaunchError: naming what is expected
    """
    match = _ENDPOINT.match(text or '')
    if not match or not 1 <= int(match.group(3)) <= 65535:
        raise LaunchError(
            f"--zenoh '{text}' is not a Zenoh endpoint: expected ws/HOST:PORT or "
            'tcp/HOST:PORT, e.g. tcp/127.0.0.1:7447 (a router listens on tcp/7447 by default)')
    return text


def zenoh_plan(args, environ=None):
    """
    Turn ``--zenoh`` into the plan entry for the Node host.

    The ROS domain is ``$ROS_DOMAIN_ID`` (default 0), as rmw_zenoh reads it.

    :returns: ``{'zenoh': {'endpoint', 'domain'}}`` or ``{}``
    :raises LaunchError: for a bad endpoint or domain
    """
    endpoint = getattr(args, 'zenoh', None)
    if not endpoint:
        return {}
    environ = os.environ if environ is None else environ
    domain_text = environ.get('ROS_DOMAIN_ID', '').strip() or '0'
    if not domain_text.isdigit() or int(domain_text) > 232:
        raise LaunchError(f"ROS_DOMAIN_ID '{domain_text}' is not a domain id (0 to 232)")
    return {'zenoh': {'endpoint': parse_endpoint(endpoint), 'domain': int(domain_text)}}


def resolve_gateway_module(description, install_space):
    """
    Add the path of the zenoh-pico session module to a plan's ``zenoh`` entry.

    :raises LaunchError: when no install base has the gateway, saying how to get it
    """
    spec = description.get('zenoh')
    if not spec:
        return
    packages = install_space.packages()
    package = packages.get(GATEWAY_PACKAGE)
    module = package.prefix / 'share' / GATEWAY_PACKAGE / GATEWAY_MODULE if package else None
    if module is None or not module.is_file():
        raise LaunchError(
            f"--zenoh needs the package '{GATEWAY_PACKAGE}' (zenoh-pico built for the gateway), "
            f"which is not in '{install_space.base}' or its underlays: 'colcon build --wasm' "
            'builds it when zenoh-pico is a source of the workspace, e.g. '
            "'git clone -b 1.9.0 https://github.com/eclipse-zenoh/zenoh-pico src/zenoh-pico' "
            '(docs/zenoh.md)')
    spec['module'] = str(module)
