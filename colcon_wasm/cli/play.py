# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm play`."""

import sys

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.cli.launch import add_runtime_arguments
from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import LaunchPlan
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.command import make_plan
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.rosbridge import bridge_plan
from colcon_wasm.record.session import add_play_arguments
from colcon_wasm.record.session import bag_plan


class PlayCommand(CliExtensionPoint):
    """Play a bag (rosbag2 MCAP) on a bus, into nodes started with it, like ros2 bag play."""

    def add_arguments(self, *, parser):  # noqa: D102
        add_runtime_arguments(parser)
        add_play_arguments(parser, option=False)
        parser.add_argument(
            'bag', metavar='BAG', help='A .mcap file or a rosbag2 directory')
        parser.add_argument(
            'what', nargs='*', metavar='ITEM',
            help='Nodes to play into, as for launch: PKG/EXE items or a launch file; they '
                 'are stopped when the bag has played (default: none, e.g. with --rosbridge)')

    def main(self, *, args):  # noqa: D102
        try:
            plan = make_plan(args.what, args.install_base) if args.what else LaunchPlan([])
            bridges = bridge_plan(args, err=sys.stderr)
            bags = bag_plan(args, play=args.bag, stop_after_play=not args.loop)
        except (LaunchError, InstallSpaceError) as e:
            print(f'colcon-wasm play: {e}', file=sys.stderr)
            return 1
        return execute(plan, install_base=args.install_base, duration=args.duration,
                       echo=args.echo, print_plan=args.print_plan, command='colcon-wasm play',
                       bridges=bridges, python=getattr(args, 'python', ()),
                       pyodide=getattr(args, 'pyodide', None), bags=bags)
