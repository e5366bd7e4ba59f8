# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm bag-info`."""

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.record.bag_info import bag_info
from colcon_wasm.record.bag_info import format_info


class BagInfoCommand(CliExtensionPoint):
    """Print what a bag (rosbag2 MCAP) holds, like ros2 bag info."""

    def add_arguments(self, *, parser):  # noqa: D102
        parser.add_argument(
            'bag', metavar='BAG', help='A .mcap file or a rosbag2 directory')

    def main(self, *, args):  # noqa: D102
        print(format_info(bag_info(args.bag)))
        return 0
