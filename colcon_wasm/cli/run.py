# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm run`."""

import argparse
import shlex
import sys

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.cli.launch import add_runtime_arguments
from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch import NodeProcess
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.foxglove import foxglove_plan
from colcon_wasm.launch.python_nodes import split_python_value
from colcon_wasm.launch.rosbridge import bridge_plan
from colcon_wasm.launch.zenoh import zenoh_plan
from colcon_wasm.record.session import bag_plan


class RunCommand(CliExtensionPoint):
    """Run one executable of the install space in Node.js, like ros2 run."""

    def add_arguments(self, *, parser):  # noqa: D102
        add_runtime_arguments(parser)
        parser.add_argument(
            '--ros-args', nargs=argparse.REMAINDER, dest='script_ros_args',
            metavar='ARGS',
            help='With --python FILE and no PKG EXE: --ros-args and everything after it '
                 'go to the script, as in python3 FILE --ros-args -p rate:=2 (after PKG EXE '
                 'they go to the executable)')
        parser.add_argument('package', metavar='PKG', nargs='?',
                            help='The package name (none with --python FILE only)')
        parser.add_argument('executable', metavar='EXE', nargs='?', help='The executable name')
        parser.add_argument(
            'arguments', nargs=argparse.REMAINDER, metavar='ARGS',
            help='Arguments of the executable, e.g. --ros-args -r chatter:=news -p rate:=5 '
                 '(everything after EXE goes to the executable: give the options of run '
                 'before PKG); with --python FILE and no PKG EXE, the arguments of the '
                 'script after --, e.g. -- --ros-args -p rate:=2')

    def main(self, *, args):  # noqa: D102
        try:
            python, script_only = python_scripts(args)
        except LaunchError as e:
            print(f'colcon-wasm run: {e}', file=sys.stderr)
            return 1
        if script_only:
            plan = LaunchPlan()
        elif args.executable is None:
            print('colcon-wasm run: name PKG EXE (or a Python node with --python FILE, '
                  'given before PKG)', file=sys.stderr)
            return 1
        else:
            plan = LaunchPlan([NodeProcess(args.package, args.executable,
                                           arguments=args.arguments)])
        try:
            bridges = bridge_plan(args, err=sys.stderr)
            bridges.update(foxglove_plan(args, err=sys.stderr))
            bridges.update(zenoh_plan(args))
            bags = bag_plan(args)
        except LaunchError as e:
            print(f'colcon-wasm run: {e}', file=sys.stderr)
            return 1
        return execute(plan, install_base=args.install_base, duration=args.duration,
                       echo=args.echo, print_plan=args.print_plan, command='colcon-wasm run',
                       stdin=True, bridges=bridges, python=python, pyodide=args.pyodide,
                       bags=bags)


def python_scripts(args):
    """
    Return the Python nodes of ``run`` and whether they are all it runs.

    Each ``--python`` value is the script and maybe its arguments
    (``split_python_value``). Without PKG EXE, the words after ``--`` (the
    first begins with ``-``: a package name cannot) and ``--ros-args ...``
    go to the script too, as in ``python3 FILE ARGS``.

    :returns: ``([--python value, or (script, [arguments])], script_only)``
    :raises LaunchError: for trailing arguments with several scripts, or none
    """
    scripts = [split_python_value(value) for value in args.python]  # quotes checked here
    words = [w for w in (args.package, args.executable) if w is not None] + \
        list(args.arguments or [])
    trailing = None
    if scripts and words and (words[0] == '--' or words[0].startswith('-')):
        trailing = words[1:] if words[0] == '--' else words
    if args.script_ros_args is not None:
        if words and trailing is None:
            raise LaunchError('--ros-args goes after EXE (the arguments of PKG EXE), or with '
                              '--python FILE alone (the arguments of the script)')
        trailing = (trailing or []) + ['--ros-args'] + list(args.script_ros_args)
    if trailing is None:
        return list(args.python), bool(scripts) and args.package is None
    if not scripts:
        raise LaunchError('--ros-args before PKG EXE: the arguments of an executable go '
                          'after it (colcon-wasm run PKG EXE --ros-args ...), those of a '
                          'Python script after --python FILE')
    if len(scripts) != 1:
        given = ' '.join(shlex.quote(w) for w in trailing)
        raise LaunchError(f'the arguments {given} go to a Python script, and there are '
                          f'{len(scripts)} (--python): give each script its arguments in '
                          "its own value, e.g. --python 'talker.py --ros-args -p rate:=2'")
    file, arguments = scripts[0]
    return [(file, arguments + trailing)], True
