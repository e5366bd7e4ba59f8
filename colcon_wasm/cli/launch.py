# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm launch`."""

from pathlib import Path
import sys

from colcon_wasm import resources
from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import load_launch_file
from colcon_wasm.launch import plan_items
from colcon_wasm.launch import split_launch_arguments
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.runner import find_launch_file
from colcon_wasm.launch.runner import host_plan
from colcon_wasm.launch.runner import LAUNCH_FILE_SUFFIXES
from colcon_wasm.launch.runner import run_host
from colcon_wasm.server import find_runtime
from colcon_wasm.server import ServeError


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
        help='Stop every node cleanly after S seconds (default: run until they exit or '
             'Ctrl-C)')
    parser.add_argument(
        '--echo', action='append', default=[], metavar='TOPIC',
        help='Print the decoded messages of a topic (repeatable)')
    parser.add_argument(
        '--print-plan', action='store_true',
        help='Print each process with its arguments and exit without running it')


def run_plan(plan, args, *, command, out):
    """Resolve a plan against the install space and run it (or print it)."""
    try:
        install_space = InstallSpace(args.install_base)
        description = host_plan(plan, install_space, duration=args.duration, echo=args.echo)
        if args.print_plan:
            for process in description['processes']:
                print('[{}] {} {}'.format(process['label'], process['js'],
                                          ' '.join(process['args'])).rstrip(), file=out)
            return 0
        runtime_dir, _ = find_runtime(
            install_space, resources.path('packages') / 'wasm_js' / 'src')
        return run_host(description, runtime_dir)
    except (LaunchError, InstallSpaceError, ServeError) as e:
        print('{}: {}'.format(command, e), file=sys.stderr)
        return 1


def make_plan(values, install_base):
    """
    Make a plan from the positional arguments of launch.

    ``FILE [name:=value ...]``, ``PKG FILE [name:=value ...]`` (a launch file
    in the package's share folder) or ``PKG/EXE [PKG/EXE ...]``.
    """
    others, arguments = split_launch_arguments(values)
    if not others:
        raise LaunchError('name a launch file or PKG/EXE items, e.g. '
                          'colcon-wasm launch demo_nodes/talker demo_nodes/listener')
    install_space = None
    if Path(install_base).is_dir():
        install_space = InstallSpace(install_base)
    first = Path(others[0])
    if len(others) == 1 and (first.is_file() or first.name.endswith(LAUNCH_FILE_SUFFIXES)):
        if not first.is_file():
            raise LaunchError("launch file '{}' does not exist".format(first))
        return load_launch_file(first, arguments, install_space=install_space)
    if len(others) == 2 and '/' not in others[0] and \
            others[1].endswith(LAUNCH_FILE_SUFFIXES):
        if install_space is None:
            raise LaunchError("no install space at '{}'".format(install_base))
        path = find_launch_file(install_space, others[0], others[1])
        return load_launch_file(path, arguments, install_space=install_space)
    if arguments:
        raise LaunchError('launch arguments ({}) need a launch file'.format(
            ', '.join('{}:={}'.format(k, v) for k, v in arguments.items())))
    return plan_items(others)


class LaunchCommand(CliExtensionPoint):
    """Run several nodes on one bus in Node.js, from PKG/EXE items or a launch file."""

    def add_arguments(self, *, parser):  # noqa: D102
        add_runtime_arguments(parser)
        parser.add_argument(
            'what', nargs='+', metavar='ITEM',
            help='A launch file (.launch.xml/.launch.yaml) with name:=value arguments, '
                 'PKG FILE for a launch file of a package, or PKG/EXE items')

    def main(self, *, args):  # noqa: D102
        try:
            plan = make_plan(args.what, args.install_base)
        except (LaunchError, InstallSpaceError) as e:
            print('colcon-wasm launch: {}'.format(e), file=sys.stderr)
            return 1
        return run_plan(plan, args, command='colcon-wasm launch', out=sys.stdout)
