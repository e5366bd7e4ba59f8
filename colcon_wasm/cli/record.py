# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm record`."""

import os
import signal
import sys
import threading

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.record import BagError
from colcon_wasm.record.bag_writer import BagWriter
from colcon_wasm.record.mcap_file import COMPRESSIONS
from colcon_wasm.record.remote import RemoteRecorder
from colcon_wasm.ros2msg import SchemaError


class RecordCommand(CliExtensionPoint):
    """Record a rosbridge server's topics (serve --rosbridge, or any) into a rosbag2 MCAP file."""

    def add_arguments(self, *, parser):  # noqa: D102
        parser.add_argument('bag', metavar='FILE.mcap', help='The bag to write')
        parser.add_argument(
            '--url', default='ws://127.0.0.1:9090', metavar='ws://HOST:PORT',
            help='The rosbridge server: serve --rosbridge, run/launch --rosbridge, or a '
                 "robot's rosbridge_server (default: %(default)s; add ?token=T if it wants one)")
        parser.add_argument(
            '--install-base', default='install_wasm', metavar='DIR',
            help='The install space whose type descriptions give the schemas (default: '
                 '%(default)s)')
        parser.add_argument(
            '--record-topic', action='append', default=[], metavar='TOPIC',
            help='Record only this topic (repeatable; default: every topic)')
        parser.add_argument(
            '--record-compression', choices=sorted(COMPRESSIONS), default='none',
            help='Compression of the chunks (default: %(default)s)')
        parser.add_argument(
            '--duration', type=float, default=None, metavar='SECONDS',
            help='Stop after SECONDS (default: until Ctrl-C or the server goes)')

    def main(self, *, args):  # noqa: D102
        directory = os.path.dirname(os.path.abspath(args.bag))
        if not os.path.isdir(directory):
            raise BagError(f"'{args.bag}': the folder '{directory}' does not exist")
        try:
            schemas = InstallSpace(args.install_base).ros2msg_schemas()
        except SchemaError as e:
            raise BagError(f'{e} (install base {args.install_base})') from None
        recorder = RemoteRecorder(args.url, topics=args.record_topic or None, err=sys.stderr)
        recorder.connect()
        writer = BagWriter(args.bag, schemas, compression=args.record_compression)
        stop = threading.Event()
        previous = signal.signal(signal.SIGINT, lambda *_: stop.set())
        try:
            print(f'colcon-wasm record: recording {args.url} into {args.bag} (Ctrl-C stops)',
                  file=sys.stderr, flush=True)
            summary = recorder.run(writer, duration=args.duration, stop=stop)
        finally:
            signal.signal(signal.SIGINT, previous)
        print(f"colcon-wasm record: {summary['messages']} messages on "
              f"{len(summary['topics'])} topics into {args.bag}"
              + (f"; skipped (type not in the install): {', '.join(summary['skipped'])}"
                 if summary['skipped'] else ''), file=sys.stderr)
        if summary['lost_connection']:
            print(f"colcon-wasm record: {summary['lost_connection']}; the bag ends there and "
                  'is complete', file=sys.stderr)
        if summary['failed']:
            print(f"colcon-wasm record: {summary['failed']}", file=sys.stderr)
            return 1
        return 0
