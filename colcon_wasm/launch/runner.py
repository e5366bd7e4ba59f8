# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Run a launch plan headless in Node.js, all processes on one bus.

The plan goes to the runtime's ``tools/launch_host.mjs`` as JSON; the host
starts each process with the wasm_js ``Runtime``, prints its output prefixed
``[label]`` as ``ros2 launch`` does, stops everything after ``duration``
seconds, and exits non-zero when a process crashed.
"""

import json
import os
from pathlib import Path
import shutil
import signal
import subprocess
import threading

from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.install_space import InstallSpaceError

HOST_SCRIPT = Path('tools') / 'launch_host.mjs'
LAUNCH_FILE_SUFFIXES = ('.launch.xml', '.launch.yaml', '.launch.yml', '.launch.py',
                        '.xml', '.yaml', '.yml', '.py')


def find_node():
    """Return the node executable, or raise a LaunchError saying how to get one."""
    node = shutil.which(os.environ.get('COLCON_WASM_NODE', 'node'))
    if node is None:
        raise LaunchError('Node.js was not found on PATH: install Node.js 20 or newer '
                          '(e.g. apt-get install nodejs), or set COLCON_WASM_NODE')
    return node


def find_launch_file(install_space, package, file_name):
    """
    Find a launch file in a package's share folder, as ``ros2 launch PKG FILE`` does.

    :raises LaunchError: when there is none or more than one
    """
    try:
        share = install_space.package(package).share
    except InstallSpaceError as e:
        raise LaunchError(str(e)) from None
    matches = sorted(p for p in share.rglob(file_name) if p.is_file())
    if not matches:
        raise LaunchError("package '{}' has no launch file '{}' in {}".format(
            package, file_name, share))
    if len(matches) > 1:
        raise LaunchError("package '{}' has several launch files named '{}': {}".format(
            package, file_name, ', '.join(str(m) for m in matches)))
    return matches[0]


def host_plan(plan, install_space, *, duration=None, echo=(), stdin=False):
    """
    Describe a plan for ``launch_host.mjs``: absolute paths, no lookups left.

    With ``stdin`` the (single) process reads this command's standard input,
    as with ``ros2 run``; launched processes get none, as with ``ros2 launch``.

    :raises LaunchError: for an executable that is not in the install space
    """
    processes = []
    for process in plan.processes:
        try:
            executable = install_space.executable(process.package, process.executable)
        except InstallSpaceError as e:
            file, line = process.where
            raise LaunchError(str(e), file, line) from None
        entry = process.to_json()
        entry['js'] = str(executable.js)
        entry['pthread'] = executable.pthread
        entry['uses_bus'] = executable.uses_bus
        processes.append(entry)
    return {
        'processes': processes,
        'duration': duration,
        'echo': list(echo),
        'stdin': bool(stdin) and len(processes) == 1,
        'types': [str(p) for p in install_space.type_description_files()],
    }


def run_host(description, runtime_module, host_dir, *, node=None, stdout=None, stderr=None):
    """
    Run the Node host on a plan description and return its exit status.

    The host script comes with colcon-wasm (``host_dir``, it reads this
    plan); the Runtime it imports is the install space's (``runtime_module``,
    it matches the executables). Ctrl-C reaches the host (same process
    group); this process waits for it to stop its nodes, so the host's status
    is the command's status.
    """
    script = Path(host_dir) / HOST_SCRIPT
    if not script.is_file():
        raise LaunchError("'{}' is missing: reinstall colcon-wasm".format(script))
    description = dict(description, runtime=Path(runtime_module).as_uri())
    command = [node or find_node(), str(script), json.dumps(description)]
    main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if main_thread else None
    try:
        process = subprocess.Popen(command, stdout=stdout, stderr=stderr,
                                   preexec_fn=_default_sigint if main_thread else None)
        return process.wait()
    finally:
        if main_thread:
            signal.signal(signal.SIGINT, previous)


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)
