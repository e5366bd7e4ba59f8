# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Run a launch plan headless in Node.js, all processes on one bus.

The plan goes to the runtime's ``launch/run_plan.mjs`` as JSON; the host
starts each process with the wasm_js ``Runtime``, prints its output prefixed
``[label]`` as ``ros2 launch`` does, loads composable nodes into their
containers, stops everything after ``duration`` seconds, and exits non-zero
when a process crashed or a composable node failed to load.
"""

import json
import os
from pathlib import Path
import shutil
import signal
import subprocess
import threading

from colcon_wasm.launch.composable import LOAD_NODE_TYPE
from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.install_view import ament_prefixes
from colcon_wasm.launch.install_view import program_environment
from colcon_wasm.launch.install_view import view_bases
from colcon_wasm.launch.install_view import view_mounts

HOST_SCRIPT = Path('launch') / 'run_plan.mjs'
DEFAULT_LOAD_TIMEOUT = 60.0
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
        raise LaunchError(f"package '{package}' has no launch file '{file_name}' in {share}")
    if len(matches) > 1:
        raise LaunchError(f"package '{package}' has several launch files named '{file_name}': "
                          f"{', '.join(str(m) for m in matches)}")
    return matches[0]


def _check_load_node_types(install_space, load):
    """Raise unless the install space describes LoadNode and rcl_interfaces' Parameter."""
    for package in ('composition_interfaces', 'rcl_interfaces'):
        try:
            found = install_space.package(package).types_path.is_file()
        except InstallSpaceError:
            found = False
        if not found:
            file, line = load.where
            raise LaunchError(
                f'loading composable nodes calls {LOAD_NODE_TYPE} and needs the type descriptions '
                f"of '{package}', "
                f"which the install space '{install_space.base}' lacks: build it with 'colcon "
                'build --wasm '
                f"--packages-up-to {package}'", file, line)


def host_plan(plan, install_space, *, duration=None, echo=(), stdin=False,
              load_timeout=DEFAULT_LOAD_TIMEOUT, bases=None):
    """
    Describe a plan for ``run_plan.mjs``: absolute paths, no lookups left.

    With ``stdin`` the (single) process reads this command's standard input,
    as with ``ros2 run``; launched processes get none, as with ``ros2 launch``.
    ``load_timeout`` bounds, in seconds, the wait for a container's load_node
    service and for each of its answers.
    Every process sees ``bases`` (default: the install space's base and
    underlays; highest priority first) read-only at their real paths, and ``AMENT_PREFIX_PATH``
    naming their packages unless its environment sets it.

    :raises LaunchError: for an executable that is not in the install space,
      or composable nodes without the composition_interfaces types
    """
    bases = view_bases(install_space) if bases is None else [Path(b) for b in bases]
    prefixes = ament_prefixes(bases)
    processes = []
    hosted = {}
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
        entry['env'] = program_environment(entry['env'], prefixes)
        if executable.python:
            # an entry point of a Python package, or a Python script a CMake package
            # installed (run as __main__): Pyodide runs it (python/spawn.mjs)
            entry['python'] = str(executable.js)
            if 'module' in executable.python:
                entry['python_entry'] = dict(executable.python)
            entry['python_path'] = [str(f) for f in install_space.python_path()]
        processes.append(entry)
        # the components the link launcher linked into a container (its manifest)
        hosted[entry['label']] = [
            f"{c['package']}/{c['class']}"
            for c in executable.entry.get('linked', {}).get('components', [])]
    if plan.loads:
        _check_load_node_types(install_space, plan.loads[0])
    loads = []
    for load in plan.loads:
        entry = load.to_json()
        entry['hosts'] = sorted(
            {c for label in entry['containers'] for c in hosted.get(label, [])})
        loads.append(entry)
    return {
        'processes': processes,
        'loads': loads,
        'load_timeout': load_timeout,
        'mounts': view_mounts(bases),
        'duration': duration,
        'echo': list(echo),
        'stdin': bool(stdin) and len(processes) == 1,
        'types': [str(p) for p in install_space.type_description_files()],
    }


def run_host(description, runtime_module, host_dir, *, node=None, stdout=None, stderr=None,
             pass_fds=(), started=None, alongside=None):
    """
    Run the Node host on a plan description and return its exit status.

    The host script comes with colcon-wasm (``host_dir``, it reads this
    plan); the Runtime it imports is the install space's (``runtime_module``,
    it matches the executables). Ctrl-C reaches the host (same process
    group); a SIGTERM sent to this process alone (a supervisor, ``kill``) is
    passed on to the host, which stops its nodes as for Ctrl-C. This process
    waits for the host, so the host's status is the command's status.
    ``pass_fds`` go to the host (record and replay pipes); ``started()`` is
    called once it runs.
    ``alongside(host, register)``, when given, runs in this thread once the
    host runs (a Python launch file: ``python_launch.HostLaunch.run``); a
    process it passes to ``register`` gets the SIGTERM instead of the host,
    and the status is its own unless the host's is an error.
    """
    script = Path(host_dir) / HOST_SCRIPT
    if not script.is_file():
        raise LaunchError(f"'{script}' is missing: reinstall colcon-wasm")
    description = dict(description, runtime=Path(runtime_module).as_uri())
    command = [node or find_node(), str(script), json.dumps(description)]
    main_thread = threading.current_thread() is threading.main_thread()
    targets = []
    if main_thread:
        previous_int = signal.signal(signal.SIGINT, signal.SIG_IGN)
        previous_term = signal.signal(signal.SIGTERM,
                                      lambda *_: _pass_on(targets, signal.SIGTERM))
    try:
        process = subprocess.Popen(command, stdout=stdout, stderr=stderr, pass_fds=pass_fds,
                                   preexec_fn=_default_sigint if main_thread else None)
        targets.append(process)
        if started:
            started()
        if alongside is None:
            return process.wait()
        status = alongside(process, targets.append)
        host_status = process.wait()
        return host_status or status
    finally:
        if main_thread:
            signal.signal(signal.SIGINT, previous_int)
            signal.signal(signal.SIGTERM, previous_term)


def _pass_on(targets, number):
    """Send the signal `number` to the newest target process still running."""
    for target in reversed(targets):
        if target.poll() is None:
            target.send_signal(number)
            return


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)
