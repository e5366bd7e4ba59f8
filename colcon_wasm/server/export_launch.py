# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
``colcon-wasm export --launch``: a launch file the exported page starts on load.

A static site has no host to run Humble's launch on, so the export plans
the launch file when it writes the site: colcon-wasm's own reader reads an
XML or YAML launch file with its arguments (``launch.loader``), and the plan
(the processes, their arguments, parameters, remappings and environment,
and the composable nodes to load) goes into the page, which starts it as it
starts a reader's plan under ``serve`` (``launch_run.mjs``). A Python launch
file needs launch itself, at run time (its event handlers, its
``OpaqueFunction`` code): it is refused, with what to do instead.
"""

from pathlib import Path
import shlex

from colcon_wasm.error import ColconWasmError
from colcon_wasm.launch import LaunchError


class LaunchExportError(ColconWasmError):
    """A ``--launch`` that cannot be planned; the text says why and what to do."""


def parse_launch_spec(spec):
    """
    Split a ``--launch`` value as ``ros2 launch`` takes its arguments.

    :returns: ``(package or None, file, {name: value})``: ``PKG FILE`` or a path,
      then ``NAME:=VALUE`` words
    :raises LaunchExportError: for a value with no file, or words that are no ``NAME:=VALUE``
    """
    try:
        words = shlex.split(spec)
    except ValueError as e:
        raise LaunchExportError(f'--launch {spec}: {e}; nothing was written') from None
    positional = [w for w in words if ':=' not in w]
    arguments = dict(w.split(':=', 1) for w in words if ':=' in w)
    if len(positional) == 1:
        return None, positional[0], arguments
    if len(positional) == 2:
        return positional[0], positional[1], arguments
    raise LaunchExportError(
        f"--launch {spec}: give 'PKG FILE [NAME:=VALUE ...]' or 'PATH [NAME:=VALUE ...]', "
        'as ros2 launch takes them; nothing was written')


def plan_launch(install_space, spec, find):
    """
    Plan one ``--launch`` for the page.

    :param find: ``(package, file) -> (path, runner)`` of the install space's launch
      files (``LaunchService.find``)
    :returns: ``{package, file, arguments, processes, loads, load_timeout}``
    :raises LaunchExportError: a Python launch file, a file not found, or the reader's
      error (its file and line)
    """
    from colcon_wasm.launch.loader import load_launch_file
    from colcon_wasm.launch.runner import host_plan
    package, file, arguments = parse_launch_spec(spec)
    if package is None:
        path = Path(file)
        if not path.is_file():
            raise LaunchExportError(f"--launch {spec}: no such file '{file}'; nothing was written")
    else:
        try:
            path, _ = find(package, file)
        except ColconWasmError as e:
            raise LaunchExportError(f'--launch {spec}: {e}; nothing was written') from None
    if path.name.lower().endswith('.py'):
        raise LaunchExportError(
            f"--launch {spec}: a Python launch file runs Humble's launch on a host at run time, "
            'which a static site has not; export its nodes with --run, or start it from an '
            'XML or YAML launch file (the export plans those); nothing was written')
    try:
        description = host_plan(load_launch_file(path, arguments, install_space=install_space),
                                install_space)
    except LaunchError as e:
        raise LaunchExportError(f'--launch {spec}: {e}; nothing was written') from None
    return {
        'package': package or '', 'file': str(file) if package else path.name,
        'arguments': arguments,
        'processes': [{k: p[k] for k in ('package', 'executable', 'args', 'env', 'label')
                       if k in p} for p in description['processes']],
        'loads': description['loads'],
        'load_timeout': description['load_timeout'],
    }
