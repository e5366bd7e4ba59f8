# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon test-result --wasm`: the results of `colcon test --wasm` (in build_wasm/)."""

import os

from colcon_core.argument_parser import ArgumentParserDecorator
from colcon_core.argument_parser import ArgumentParserDecoratorExtensionPoint
from colcon_core.plugin_system import satisfies_version

"""colcon test-result's option and its default (a folder that must exist)."""
OPTION = '--test-result-base'
NATIVE_DEFAULT = 'build'
WASM_DEFAULT = 'build_wasm'


class _Default(str):
    """The default value of --test-result-base, told apart from a given one."""


def _lenient(value):
    """Keep the value as given: existence is checked after parsing."""
    return value if isinstance(value, _Default) else str(value)


def _check_existing_dir(parser, path):
    if not os.path.exists(path):
        parser.error(f"argument {OPTION}: Path '{path}' does not exist")
    if not os.path.isdir(path):
        parser.error(f"argument {OPTION}: Path '{path}' is not a directory")


class WasmTestResultArgumentParserDecorator(ArgumentParserDecoratorExtensionPoint):
    """Add `--wasm` to `colcon test-result`."""

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            ArgumentParserDecoratorExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    def decorate_argument_parser(self, *, parser):  # noqa: D102
        return WasmTestResultDecorator(parser)


class WasmTestResultDecorator(ArgumentParserDecorator):
    """
    Give a parser whose `--test-result-base` defaults to `build` a `--wasm` option.

    That is `colcon test-result`'s parser: with `--wasm` the default is
    `build_wasm`, where `colcon test --wasm` leaves the results.
    """

    def add_argument(self, *args, **kwargs):
        """Add an argument; `--test-result-base` of test-result gets `--wasm` too."""
        if args == (OPTION,) and kwargs.get('default') == NATIVE_DEFAULT and \
                callable(kwargs.get('type')):
            self._parser.add_argument(
                '--wasm', action='store_true',
                help=f'Show the results of colcon test --wasm (default {OPTION}: '
                     f'{WASM_DEFAULT})')
            kwargs = dict(kwargs, default=_Default(NATIVE_DEFAULT), type=_lenient)
            self._parser.set_defaults(_colcon_wasm_test_result=True)
        return self._parser.add_argument(*args, **kwargs)

    def parse_args(self, *args, **kwargs):
        """Parse, then choose and check the test result base."""
        parsed = self._parser.parse_args(*args, **kwargs)
        if getattr(parsed, '_colcon_wasm_test_result', False):
            base = parsed.test_result_base
            if isinstance(base, _Default) and getattr(parsed, 'wasm', False):
                base = WASM_DEFAULT
            parsed.test_result_base = str(base)
            _check_existing_dir(self._parser, parsed.test_result_base)
        return parsed
