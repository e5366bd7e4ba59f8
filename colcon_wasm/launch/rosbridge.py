# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The rosbridge options of ``colcon-wasm run`` and ``colcon-wasm launch``.

``--rosbridge [HOST:]PORT`` starts a rosbridge v2 server over the launch's
bus, ``--rosbridge-connect ws://HOST:PORT`` bridges the launch's nodes to a
remote rosbridge server; both run in the Node host
(``packages/wasm_js/src/bridges/rosbridge/``). This module checks the
options and turns them into the plan entries the host reads.
"""

import ipaddress
from pathlib import Path
import re
from urllib.parse import urlsplit

from colcon_wasm.launch.errors import LaunchError
import yaml

DEFAULT_HOST = '127.0.0.1'
DEFAULT_PORT = 9090
CAPABILITY_VERBS = ('publish', 'subscribe', 'call', 'advertise')


def _positive_int(text):
    value = int(text)
    if value <= 0:
        raise ValueError(text)
    return value


def add_rosbridge_arguments(parser):
    """Add the rosbridge options."""
    parser.add_argument(
        '--rosbridge', nargs='?', const=f'{DEFAULT_HOST}:{DEFAULT_PORT}',
        metavar='[HOST:]PORT',
        help="Serve the rosbridge v2 protocol (roslibjs, roslibpy) over the nodes' bus on "
             f'HOST:PORT (default {DEFAULT_HOST}:{DEFAULT_PORT}; only this machine unless HOST '
             'names another address; '
             'port 0 picks a free one)')
    parser.add_argument(
        '--rosbridge-token', metavar='TOKEN',
        help='rosbridge clients must present TOKEN (ws://HOST:PORT/?token=TOKEN or an '
             'Authorization: Bearer header); with --rosbridge-connect, the token sent')
    parser.add_argument(
        '--rosbridge-capabilities', metavar='FILE',
        help='A YAML or JSON file listing which topics, services and actions rosbridge clients '
             'may publish, subscribe, call and advertise (name patterns per verb)')
    parser.add_argument(
        '--rosbridge-max-message-bytes', type=_positive_int, metavar='N',
        help='The largest message a rosbridge client may send (default 16 MiB)')
    parser.add_argument(
        '--rosbridge-max-queued-bytes', type=_positive_int, metavar='N',
        help='Bytes waiting to be sent to one rosbridge client before it is cut off '
             '(default 64 MiB); for --rosbridge-connect, the bound of what is queued while '
             'disconnected')
    parser.add_argument(
        '--rosbridge-connect', metavar='URL',
        help='Bridge the nodes to the rosbridge server at ws://HOST:PORT: what they publish, '
             'subscribe, serve and call crosses (reconnects with backoff)')


def parse_listen_address(text, option='--rosbridge', default_port=DEFAULT_PORT):
    """
    Read ``[HOST:]PORT`` (the value of ``option``, named in the errors).

    :returns: ``(host, port)``
    :raises LaunchError: for anything else
    """
    match = re.fullmatch(r'(?:\[([^\]]+)\]|([^:\[\]]*)):(\d+)|(\d+)', text.strip())
    if not match:
        raise LaunchError(f"{option} '{text}' is not [HOST:]PORT (e.g. {default_port}, "
                          f'127.0.0.1:{default_port}, 0.0.0.0:{default_port}); to take the '
                          f'default, put {option} last among the options or write '
                          f'{option}=127.0.0.1:{default_port}')
    host = match.group(1) or match.group(2) or DEFAULT_HOST
    port = int(match.group(3) or match.group(4))
    if port > 65535:
        raise LaunchError(f'{option} port {port} is not a port (0 to 65535)')
    return host, port


def is_loopback(host):
    """Return True for an address only this machine reaches."""
    if host == 'localhost':
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def load_capabilities(path):
    """
    Read a capability list (YAML or JSON): ``{verb: [pattern, ...]}``.

    :raises LaunchError: naming the file and what is wrong
    """
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text(encoding='utf-8'))
    except OSError as e:
        raise LaunchError(f"cannot read the capability list '{path}': {e.strerror or e}") from None
    except yaml.YAMLError as e:
        raise LaunchError(f"the capability list '{path}' is not YAML or JSON: {e}") from None
    if not isinstance(data, dict):
        raise LaunchError(f"the capability list '{path}' must be a mapping of "
                          f"{', '.join(CAPABILITY_VERBS)} to lists of name "
                          'patterns')
    for verb, patterns in data.items():
        if verb not in CAPABILITY_VERBS:
            raise LaunchError(f"the capability list '{path}' has an unknown key '{verb}': use "
                              f"{', '.join(CAPABILITY_VERBS)}")
        if not isinstance(patterns, list) or not all(isinstance(p, str) for p in patterns):
            raise LaunchError(f"the capability list '{path}': '{verb}' must be a list of name "
                              'patterns '
                              "(strings like '/chatter' or '/camera/*')")
    return data


def bridge_plan(args, *, err=None):
    """
    Turn the rosbridge options into plan entries for the Node host.

    :returns: a dict with ``rosbridge`` and/or ``rosbridge_connect`` (maybe empty)
    :raises LaunchError: for a bad option
    """
    plan = {}
    limits = {}
    if getattr(args, 'rosbridge_max_message_bytes', None):
        limits['maxMessageBytes'] = args.rosbridge_max_message_bytes
    if getattr(args, 'rosbridge_max_queued_bytes', None):
        limits['maxQueuedBytes'] = args.rosbridge_max_queued_bytes
    if getattr(args, 'rosbridge', None):
        host, port = parse_listen_address(args.rosbridge)
        capabilities = None
        if args.rosbridge_capabilities:
            capabilities = load_capabilities(args.rosbridge_capabilities)
        plan['rosbridge'] = {
            'host': host, 'port': port, 'token': args.rosbridge_token,
            'capabilities': capabilities, 'limits': limits,
        }
        if not is_loopback(host) and err is not None:
            missing = '' if args.rosbridge_token else ' (no --rosbridge-token)'
            print(f'warning: --rosbridge listens on {host}: other machines can drive your '
                  f'nodes{missing}', file=err)
    elif getattr(args, 'rosbridge_capabilities', None):
        raise LaunchError('--rosbridge-capabilities applies to a server: add --rosbridge')
    if getattr(args, 'rosbridge_connect', None):
        url = args.rosbridge_connect
        parts = urlsplit(url)
        if parts.scheme != 'ws' or not parts.hostname:
            raise LaunchError(f"--rosbridge-connect '{url}' is not a ws://HOST:PORT URL (wss:// "
                              'is '
                              'not supported in Node.js)')
        plan['rosbridge_connect'] = {
            'url': url, 'token': args.rosbridge_token, 'limits': limits,
        }
    return plan
