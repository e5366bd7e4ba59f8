# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm run`."""

import argparse
import sys

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.cli.launch import add_runtime_arguments
from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch import NodeProcess
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.foxglove import foxglove_plan
from colcon_wasm.launch.rosbridge import bridge_plan
from colcon_wasm.launch.zenoh import zenoh_plan
from colcon_wasm.record.session import bag_plan


class RunCommand(CliExtensionPoint):
    """Run one executable of the install space in Node.js, like ros2 run."""

    def add_arguments(self, *, parser):  # noqa: D102
        add_runtime_arguments(parser)
        parser.add_argument('package', metavar='PKG', nargs='?',
                            help='The package name (none with --python FILE only)')
        parser.add_argument('executable', metavar='EXE', nargs='?', help='The executable name')
        parser.add_argument(
            'arguments', nargs=argparse.REMAINDER, metavar='ARGS',
            help='Arguments of the executable, e.g. --ros-args -r chatter:=news -p rate:=5 '
                 '(everything after EXE goes to the executable: give the options of run '
                 'before PKG)')

    def main(self, *, args):  # noqa: D102
        if args.package is None and args.python:
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
                       stdin=True, bridges=bridges, python=args.python, pyodide=args.pyodide,
                       bags=bags)
