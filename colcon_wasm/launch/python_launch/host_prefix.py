# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The install space as Humble's ``launch`` sees it on the build host.

launch and launch_ros find everything through ``AMENT_PREFIX_PATH``:
``FindPackageShare``, ``get_package_share_directory()`` and, for a ``Node``,
``ExecutableInPackage``, which wants ``<prefix>/lib/<pkg>/<exe>`` to be a
host program. The host prefix is one merged prefix in the launch's private
folder:

* ``share/ament_index/resource_index/packages/<pkg>``: every package of the
  install space (and of its underlays);
* ``share/<pkg>``: a link to the package's real share folder, so launch
  files, URDFs and parameter files read at load time are the installed ones;
* ``lib/<pkg>/<exe>``: for each executable, a shim that runs it on the
  launch's bus (``node_shim.py``); for GUI programs the install lacks
  (``gui_programs.py``), one that says so and waits;
* ``bin/<tool>``: the install's Python programs of ``bin/`` (``xacro``),
  run natively by this Python with the install's modules, for ``Command``
  and ``FindExecutable``.

Paths under the host prefix that reach a node (a ``FindPackageShare`` in
its arguments) are given back as the real paths by the shim.
"""

import json
import os
from pathlib import Path
import shlex
import sys

from colcon_wasm.launch.install_view import ament_prefixes
from colcon_wasm.launch.install_view import PACKAGES_INDEX
from colcon_wasm.launch.python_launch.gui_programs import gui_programs

_HERE = Path(__file__).resolve().parent
NODE_SHIM = _HERE / 'node_shim.py'
GUI_SHIM = _HERE / 'gui_shim.py'
CONFIG_NAME = 'launch.json'


def site_packages(prefixes):
    """Return the Python module folders of install prefixes, as a sourced setup.sh adds them."""
    version = f'python{sys.version_info[0]}.{sys.version_info[1]}'
    folders = []
    for prefix in prefixes:
        for sub in ('site-packages', 'dist-packages'):
            folder = Path(prefix) / 'lib' / version / sub
            if folder.is_dir() and str(folder) not in folders:
                folders.append(str(folder))
    return folders


def _write_program(path, command):
    """Write an executable ``sh`` script that execs ``command`` with its arguments."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text('#!/bin/sh\nexec ' + ' '.join(shlex.quote(str(c)) for c in command)
                    + ' "$@"\n', encoding='utf-8')
    path.chmod(0o755)


def _is_python_script(path):
    try:
        with open(path, 'rb') as f:
            first = f.readline(200)
    except OSError:
        return False
    return first.startswith(b'#!') and b'python' in first


class HostPrefix:
    """The host prefix of one launch, in a private folder (see the module)."""

    def __init__(self, folder, install_space, processes, *, socket, bases, python=None):
        """
        Write the prefix and the shims' configuration into ``folder``.

        :param processes: ``{'pkg/exe': entry}``, each a process of a host plan
          (``runner.host_plan``) with no arguments
        :param socket: the Node host's socket the shims ask for their programs
        :param bases: the install bases the nodes see, highest priority first
        """
        self.folder = Path(folder)
        self.root = self.folder / 'prefix'
        self.config_path = self.folder / CONFIG_NAME
        self.python = python or sys.executable
        self.real_prefixes = ament_prefixes(bases)
        self.python_path = site_packages(self.real_prefixes)
        packages = install_space.packages()
        self.shares = {name: str(p.share) for name, p in packages.items() if p.share.is_dir()}
        for name, share in self.shares.items():
            self._add_package(name, share)
        for item in processes:
            package, _, executable = item.partition('/')
            self._add_package(package, self.shares.get(package))
            _write_program(self.root / 'lib' / package / executable,
                           [self.python, '-S', '-E', NODE_SHIM, self.config_path, item])
        self.gui = gui_programs(set(packages))
        for package, (executables, reason) in self.gui.items():
            self._add_package(package, None)
            for executable in executables:
                _write_program(self.root / 'lib' / package / executable,
                               [self.python, '-S', '-E', GUI_SHIM, f'{package}/{executable}',
                                reason])
        self.tools = self._add_host_tools()
        self.config = {
            'socket': str(socket),
            'host_prefix': str(self.root),
            'shares': self.shares,
            'ament_prefix_path': os.pathsep.join(self.real_prefixes),
            'mounted': [str(b) for b in bases],
            'processes': processes,
        }

    def _add_package(self, name, share):
        marker = self.root / PACKAGES_INDEX / name
        if marker.exists():
            return
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text('', encoding='utf-8')
        if share is not None:
            link = self.root / 'share' / name
            link.parent.mkdir(parents=True, exist_ok=True)
            link.symlink_to(share, target_is_directory=True)

    def _add_host_tools(self):
        """Wrap the install's Python programs of ``bin/`` (highest priority first wins)."""
        tools = {}
        for prefix in self.real_prefixes:
            folder = Path(prefix) / 'bin'
            if not folder.is_dir():
                continue
            for program in sorted(folder.iterdir()):
                if program.name in tools or not program.is_file() \
                        or not _is_python_script(program):
                    continue
                tools[program.name] = str(program)
                _write_program(self.root / 'bin' / program.name, [self.python, program])
        return tools

    def environment(self, environ):
        """
        Return the environment of the host's launch process.

        ``AMENT_PREFIX_PATH`` is the host prefix alone, ``PATH`` starts with
        its ``bin/``, ``PYTHONPATH`` with the install's module folders.
        """
        env = dict(environ)
        env['AMENT_PREFIX_PATH'] = str(self.root)
        env['PATH'] = os.pathsep.join([str(self.root / 'bin'), env.get('PATH', os.defpath)])
        env['PYTHONPATH'] = os.pathsep.join(
            self.python_path + [p for p in env.get('PYTHONPATH', '').split(os.pathsep) if p])
        return env

    def write_config(self, base_environment):
        """Write the shims' configuration, with the launch process' own environment."""
        config = dict(self.config, base_environment=base_environment)
        self.config_path.write_text(json.dumps(config), encoding='utf-8')
