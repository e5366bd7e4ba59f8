# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python launch files, as ``ros2 launch`` runs them: Humble's own ``launch`` on the build host.

``colcon-wasm launch FILE.launch.py`` (or ``PKG FILE.launch.py``) starts the
Node.js host of the bus first, with its bridges and recorder as for any
launch, listening on a socket of the launch's private folder. Then it runs
``front.py`` with this Python: Humble's ``launch`` and ``launch_ros`` from
the install space, unmodified, evaluate the file. Every process they start
is a host process; a ``Node`` of the install space is a shim
(``node_shim.py``, found through the host prefix, ``host_prefix.py``) that
runs its executable on the bus. When the launch ends, the host is told to
end too, and the command's status is launch's, or 1 when a node died.
"""

import json
import os
from pathlib import Path
import signal
import socket
import subprocess
import sys
import tempfile

from colcon_wasm.launch.launch_plan import LaunchPlan
from colcon_wasm.launch.launch_plan import NodeProcess
from colcon_wasm.launch.python_launch.host_prefix import HostPrefix
from colcon_wasm.launch.runner import host_plan

FRONT_MODULE = 'colcon_wasm.launch.python_launch.front'
SOCKET_NAME = 'bus.sock'


"""The package of Humble's launch that reads each kind of launch file."""
FRONTEND_PACKAGES = (('.py', 'launch_ros'), ('.xml', 'launch_xml'), ('.yaml', 'launch_yaml'),
                     ('.yml', 'launch_yaml'))


def runs_on_host_launch(path, install_space):
    """
    Tell whether Humble's launch runs a launch file, rather than colcon-wasm's own reader.

    Python files always do. XML and YAML files do when the install space has
    launch_ros and the file's frontend (``launch_xml``, ``launch_yaml``): one
    launch path, with includes of every kind. Without them, colcon-wasm's
    reader (``colcon_wasm.launch.loader``) reads them.
    """
    name = str(path).lower()
    if name.endswith('.py'):
        return True
    if install_space is None:
        return False
    packages = install_space.packages()
    frontend = next((p for suffix, p in FRONTEND_PACKAGES if name.endswith(suffix)), None)
    return frontend is not None and frontend in packages and 'launch_ros' in packages


class HostLaunch:
    """One launch file that Humble's launch runs, its arguments and the launch's private folder."""

    def __init__(self, path, arguments, *, show_args=False):
        """
        Describe the launch of ``path`` with ``name:=value`` ``arguments``.

        :param show_args: print the file's arguments and run nothing (``--show-args``)
        """
        self.path = Path(path).absolute()
        self.arguments = [f'{k}:={v}' for k, v in arguments.items()]
        self.show_args = show_args
        self.folder = None
        self.prefix = None

    # the empty plan the host starts with: launch starts the processes
    plan = LaunchPlan()

    def prepare(self, description, install_space, bases, *, runtime_python, ready_pipe=True):
        """
        Make the host prefix, and give the host plan its socket.

        :param description: the host plan (``runner.host_plan``), changed in place
        :param runtime_python: the folder of colcon-wasm's ``rclpy`` (the runtime's ``python/``)
        :param ready_pipe: make the pipe the Node host says 'ready' on (``serve`` listens
          on the socket itself: none)
        """
        self.folder = Path(tempfile.mkdtemp(prefix='colcon-wasm-launch-'))
        socket_path = self.folder / SOCKET_NAME
        processes = _executable_entries(install_space, bases)
        self.prefix = HostPrefix(self.folder, install_space, processes, socket=socket_path,
                                 bases=bases or install_space.bases)
        self.runtime_python = Path(runtime_python)
        self.types = description.get('types', [])
        description['control'] = {'socket': str(socket_path)}
        if ready_pipe:
            # the host writes 'ready' on this pipe once it listens (or ends, closing it)
            self.ready, self.ready_for_host = os.pipe()
            description['control']['ready_fd'] = self.ready_for_host

    def front_command(self, *, command, print_only=False, as_json=False):
        """Return the command line of ``front.py`` (``as_json``: the arguments as JSON)."""
        options = {'file': str(self.path), 'arguments': self.arguments, 'types': self.types,
                   'show_args': self.show_args, 'print': print_only, 'command': command,
                   'json': as_json,
                   'socket': None if print_only else self.prefix.config['socket']}
        return [sys.executable, '-m', FRONT_MODULE, json.dumps(options)]

    def front_environment(self):
        """Return the environment of ``front.py``: the host prefix's, rclpy after the install's."""
        env = self.prefix.environment(os.environ)
        env['PYTHONPATH'] = os.pathsep.join(
            [env['PYTHONPATH'], str(self.runtime_python), str(_colcon_wasm_root())])
        env['COLCON_WASM_LAUNCH_CONFIG'] = str(self.prefix.config_path)
        self.prefix.write_config(env)
        return env

    def describe(self, *, command, out):
        """Run ``front.py`` to print the description (``--print-plan``) or its arguments."""
        completed = subprocess.run(self.front_command(command=command, print_only=True),
                                   env=self.front_environment(), stdout=out, stderr=sys.stderr)
        return completed.returncode

    def run(self, host, register, *, command, duration=None):
        """
        Run the launch beside the started Node host, then tell the host to end.

        :param host: the host's Popen
        :param register: called with the launch's Popen, which SIGTERM then reaches
        :param duration: seconds after which the launch gets SIGINT, as Ctrl-C
        :returns: launch's exit status (the host's comes from the caller's wait)
        """
        os.close(self.ready_for_host)  # the host has its copy
        if not _wait_until_ready(self.ready):
            return 1  # the host ended first and said why
        front = subprocess.Popen(self.front_command(command=command),
                                 env=self.front_environment(), preexec_fn=_default_sigint)
        register(front)
        try:
            status = front.wait(timeout=duration)
        except subprocess.TimeoutExpired:
            print(f'[INFO] [launch]: stopping the launch after {duration:g} s (--duration)',
                  flush=True)
            front.send_signal(signal.SIGINT)
            status = front.wait()
        _tell_host_to_end(self.prefix.config['socket'])
        return status

    def cleanup(self):
        """Remove the launch's private folder."""
        if self.folder is not None:
            import shutil
            shutil.rmtree(self.folder, ignore_errors=True)


def _colcon_wasm_root():
    """Return the folder holding the ``colcon_wasm`` package (for ``-m`` of front.py)."""
    return Path(__file__).resolve().parents[3]


def _executable_entries(install_space, bases):
    """Return ``{'pkg/exe': host plan entry}`` of every executable of the install space."""
    executables = install_space.executables()
    plan = LaunchPlan([NodeProcess(e.package_name, e.name) for e in executables])
    entries = host_plan(plan, install_space, bases=bases)['processes']
    found = {}
    for executable, entry in zip(executables, entries):
        entry['label'] = executable.name
        found[executable.label] = entry
    return found


def _wait_until_ready(ready):
    """Read the host's 'ready' line on its pipe; False when it ended before listening."""
    with os.fdopen(ready, 'rb') as pipe:
        return pipe.readline().strip() == b'ready'


def _tell_host_to_end(path):
    try:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as connection:
            connection.connect(str(path))
            connection.sendall(b'{"op": "end"}\n')
    except OSError:
        pass  # the host has ended already


def _default_sigint():
    signal.signal(signal.SIGINT, signal.SIG_DFL)
