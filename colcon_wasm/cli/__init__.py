# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The `colcon-wasm` command.

Each subcommand is one thin module registered as an entry point in the group
`colcon_wasm.cli` (like pyodide-build's `pyodide.cli`); the work is done in
library modules. A :class:`colcon_wasm.error.ColconWasmError` a subcommand
raises becomes one line (`colcon-wasm SUBCOMMAND: what failed, where, what
to do`) and exit code 1 (:func:`colcon_wasm.error.exit_on_error`).
"""

import argparse
import sys

from colcon_core.plugin_system import instantiate_extensions
from colcon_core.plugin_system import order_extensions_by_name
from colcon_wasm import __version__
from colcon_wasm.error import exit_on_error


class CliExtensionPoint:
    """
    The interface of a `colcon-wasm` subcommand.

    The entry point name is the subcommand name; the first line of the class
    docstring is its help text.
    """

    """The version of the subcommand interface."""
    EXTENSION_POINT_VERSION = '1.0'

    def add_arguments(self, *, parser):
        """
        Add the subcommand's arguments.

        :param parser: the subcommand's argument parser
        """
        pass

    def main(self, *, args):
        """
        Run the subcommand.

        This method must be overridden in a subclass. It may raise a
        :class:`colcon_wasm.error.ColconWasmError`: :func:`main` prints it as
        one line and exits with 1.

        :param args: the parsed arguments
        :returns: the exit code
        """
        raise NotImplementedError()


def get_subcommands():
    """Get the installed subcommands, ordered by name."""
    return order_extensions_by_name(instantiate_extensions('colcon_wasm.cli'))


def create_parser(subcommands):
    """Create the argument parser with one subparser per subcommand."""
    parser = argparse.ArgumentParser(
        prog='colcon-wasm',
        description='Tools around `colcon build --wasm`.')
    parser.add_argument(
        '--version', action='version', version=f'%(prog)s {__version__}')
    subparsers = parser.add_subparsers(
        dest='subcommand', metavar='SUBCOMMAND')
    for name, extension in subcommands.items():
        doc = (extension.__doc__ or '').strip().splitlines()
        subparser = subparsers.add_parser(
            name, help=doc[0] if doc else None,
            description=doc[0] if doc else None)
        extension.add_arguments(parser=subparser)
    return parser


def main(argv=None):
    """Run `colcon-wasm`."""
    subcommands = get_subcommands()
    parser = create_parser(subcommands)
    args = parser.parse_args(argv)
    if not args.subcommand:
        parser.print_help()
        return 2
    # the one edge: an error of the library becomes one line and exit code 1
    with exit_on_error(f'colcon-wasm {args.subcommand}'):
        return subcommands[args.subcommand].main(args=args)


if __name__ == '__main__':
    sys.exit(main())
