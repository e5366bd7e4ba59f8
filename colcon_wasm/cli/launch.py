# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm launch`."""

import sys

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.command import make_plan
from colcon_wasm.launch.foxglove import add_foxglove_arguments
from colcon_wasm.launch.foxglove import foxglove_plan
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.python_launch import HostLaunch
from colcon_wasm.launch.rosbridge import add_rosbridge_arguments
from colcon_wasm.launch.rosbridge import bridge_plan
from colcon_wasm.launch.runner import DEFAULT_LOAD_TIMEOUT
from colcon_wasm.launch.zenoh import add_zenoh_arguments
from colcon_wasm.launch.zenoh import zenoh_plan
from colcon_wasm.record.session import add_play_arguments
from colcon_wasm.record.session import add_record_arguments
from colcon_wasm.record.session import bag_plan


def _positive(text):
    value = float(text)
    if value <= 0:
        raise ValueError(text)
    return value


def add_runtime_arguments(parser):
    """Add the options shared by run and launch."""
    parser.add_argument(
        '--install-base', default='install_wasm', metavar='DIR',
        help='The install space of colcon build --wasm (default: install_wasm)')
    parser.add_argument(
        '--duration', type=_positive, metavar='S',
        help='Stop every node after S seconds (default: run until they exit or Ctrl-C)')
    parser.add_argument(
        '--echo', action='append', default=[], metavar='TOPIC',
        help='Print the decoded messages of a topic (repeatable)')
    parser.add_argument(
        '--print-plan', action='store_true',
        help='Print each process with its arguments and exit without running it')
    parser.add_argument(
        '--python', action='append', default=[], metavar='FILE',
        help='Run a Python script as a node (rclpy in Pyodide) next to the others '
             "(repeatable); its arguments go in the same word: --python 'talker.py "
             "--ros-args -p rate:=2' (docs/python.md)")
    parser.add_argument(
        '--pyodide', metavar='DIR',
        help='The Pyodide npm package folder for --python (default: $COLCON_WASM_PYODIDE, '
             'else the one colcon-wasm doctor names)')
    add_rosbridge_arguments(parser)
    add_foxglove_arguments(parser)
    add_zenoh_arguments(parser)
    add_record_arguments(parser)


class LaunchCommand(CliExtensionPoint):
    """Run several nodes on one bus in Node.js, from PKG/EXE items or a launch file."""

    def add_arguments(self, *, parser):  # noqa: D102
        add_runtime_arguments(parser)
        add_play_arguments(parser, option=True)
        parser.add_argument(
            '--load-timeout', type=_positive, default=DEFAULT_LOAD_TIMEOUT, metavar='S',
            help="How long to wait for a container's load_node service, and for each "
                 'answer, before a composable node counts as failed (default: %(default)s)')
        parser.add_argument(
            '--show-args', '--show-arguments', '-s', action='store_true',
            help='Show the arguments of a Python launch file and exit, as ros2 launch -s')
        parser.add_argument(
            'what', nargs='*', metavar='ITEM',
            help='A launch file (.launch.py/.launch.xml/.launch.yaml) with name:=value '
                 'arguments, PKG FILE for a launch file of a package, or PKG/EXE items')

    def main(self, *, args):  # noqa: D102
        try:
            plan = make_plan(args.what, args.install_base, show_args=args.show_args) \
                if args.what or not args.python else LaunchPlan()
            if args.show_args and not isinstance(plan, HostLaunch):
                raise LaunchError(
                    "--show-args shows the arguments of a launch file that Humble's launch "
                    'runs: a .launch.py file, or an XML or YAML one in an install space with '
                    'launch_ros')
            bridges = bridge_plan(args, err=sys.stderr)
            bridges.update(foxglove_plan(args, err=sys.stderr))
            bridges.update(zenoh_plan(args))
            bags = bag_plan(args)
        except (LaunchError, InstallSpaceError) as e:
            print(f'colcon-wasm launch: {e}', file=sys.stderr)
            return 1
        return execute(plan, install_base=args.install_base, duration=args.duration,
                       echo=args.echo, print_plan=args.print_plan,
                       command='colcon-wasm launch', load_timeout=args.load_timeout,
                       bridges=bridges, python=args.python, pyodide=args.pyodide, bags=bags)
