# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The host process of one wasm node started by a Python launch file.

Humble's ``launch`` starts every process on the build host. For a ``Node``
of the install space, launch_ros' ``ExecutableInPackage`` finds
``lib/<pkg>/<exe>`` in the launch's host prefix (``host_prefix.py``): this
file, run with the launcher's Python. It asks the Node.js host of the launch
(``packages/wasm_js/src/launch/process_server.mjs``) to run the executable
on the launch's bus, then is that node for launch: it prints the node's
output, passes SIGINT and SIGTERM on (the node stops, as rclcpp's signal
handler ends it natively) and exits with the node's exit code. So launch's
process events, ``on_exit``, ``respawn`` and ``Shutdown()`` see the node as
they see a native one.

Only the standard library is imported: launch starts one of these per node.

Usage (the shims ``host_prefix.py`` writes)::

    python3 node_shim.py CONFIG PKG/EXE [ARGS ...]
"""

import json
import os
import re
import signal
import socket
import sys
import threading

#: ROS variables a node gets although the launch did not set them (the rest of the
#: launcher's environment is the host's, not the node's)
_ROS_VARIABLES = ('ROS_', 'RCUTILS_', 'RMW_', 'RCL_')
#: Variables of the host's launch that mean nothing in WebAssembly
_HOST_ONLY = ('PYTHONPATH', 'PATH', 'LD_LIBRARY_PATH', 'COLCON_WASM_LAUNCH_CONFIG')


def _real_paths(config):
    """Return a function mapping host-prefix paths in a text to the install's real ones."""
    shares = config['shares']
    prefix = re.escape(config['host_prefix'].rstrip('/') + '/share/')
    pattern = re.compile(prefix + r'([^/\s:;,"\'=]+)')

    def replace(match):
        return shares.get(match.group(1), match.group(0))
    return lambda text: pattern.sub(replace, text)


def node_environment(config, real, environ=None):
    """
    Return the environment the wasm node gets.

    What the launch set (a ``SetEnvironmentVariable``, a node's ``env``): what
    differs from the launcher's own environment, which ``front.py`` wrote;
    the ROS variables; ``AMENT_PREFIX_PATH`` of the install's real prefixes.
    """
    environ = os.environ if environ is None else environ
    base = config.get('base_environment', {})
    env = {}
    for name, value in environ.items():
        if name in _HOST_ONLY:
            continue
        if base.get(name) != value or name.startswith(_ROS_VARIABLES):
            env[name] = real(value)
    if environ.get('AMENT_PREFIX_PATH') == base.get('AMENT_PREFIX_PATH'):
        env['AMENT_PREFIX_PATH'] = config['ament_prefix_path']
    return env


def parameter_files(args, mounted):
    """
    Read the ``--params-file`` files the node is given outside its read-only views.

    launch_ros writes a node's ``parameters=[{...}]`` into a temporary file;
    the node's file system gets each such file at its path, as natively.
    """
    files = {}
    for at, arg in enumerate(args[:-1]):
        if arg != '--params-file':
            continue
        path = os.path.abspath(args[at + 1])
        if any(path == m or path.startswith(m.rstrip('/') + '/') for m in mounted):
            continue
        try:
            with open(path, encoding='utf-8') as f:
                files[path] = f.read()
        except OSError as e:
            raise SystemExit(f'colcon-wasm: cannot read the parameters file {path!r}: {e}')
    return files


def _request(config, item, args):
    """Describe the spawn of ``item`` (PKG/EXE) with its arguments."""
    real = _real_paths(config)
    process = dict(config['processes'][item])
    process['args'] = [real(a) for a in args]
    process['env'] = dict(process.get('env', {}), **node_environment(config, real))
    process['files'] = parameter_files(process['args'], config.get('mounted', []))
    return {'op': 'spawn', 'process': process}


def _print(stream, text):
    stream.write(text if text.endswith('\n') else text + '\n')
    stream.flush()


def run(config, item, args):
    """Run ``item`` on the launch's bus and return its exit status."""
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        connection.connect(config['socket'])
    except OSError as e:
        _print(sys.stderr, f"colcon-wasm: cannot reach the launch's bus at {config['socket']}: "
                           f'{e}; this program runs only inside colcon-wasm launch')
        return 1
    lock = threading.Lock()

    def send(message):
        with lock:
            try:
                connection.sendall((json.dumps(message) + '\n').encode())
            except OSError:
                pass  # the host has gone: its end is read below

    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, lambda n, _: send(
            {'op': 'signal', 'name': signal.Signals(n).name}))
    send(_request(config, item, args))
    status = 1
    reader = connection.makefile('r', encoding='utf-8')
    for line in reader:
        event = json.loads(line)
        if event['ev'] == 'log':
            _print(sys.stderr if event['stream'] == 'stderr' else sys.stdout, event['text'])
        elif event['ev'] == 'exit':
            status = _status(event)
            if event.get('crashed') and event.get('reason'):
                _print(sys.stderr, f"[colcon-wasm] {item}: {event['reason']}")
            break
    connection.close()
    return status


def _status(event):
    """Map the end of a wasm program to an exit status, as the native program would end."""
    if event.get('crashed'):
        return 1 if event.get('code') in (None, 0) else event['code']
    if event.get('reason') == 'stopped':
        return 0  # stopped by a signal: rclcpp's handler ends a node cleanly
    return event.get('code') or 0


def main(argv=None):
    """Run the shim: ``node_shim.py CONFIG PKG/EXE [ARGS ...]``."""
    argv = sys.argv[1:] if argv is None else argv
    with open(argv[0], encoding='utf-8') as f:
        config = json.load(f)
    return run(config, argv[1], argv[2:])


if __name__ == '__main__':
    sys.exit(main())
