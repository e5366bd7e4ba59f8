# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Switch colcon's default build and install bases when `--wasm` is given."""

from colcon_core.argument_default import is_default_value
from colcon_core.argument_default import wrap_default_value
from colcon_core.argument_parser import ArgumentParserDecorator
from colcon_core.argument_parser import ArgumentParserDecoratorExtensionPoint
from colcon_core.logging import colcon_logger
from colcon_core.plugin_system import satisfies_version
from colcon_wasm.verb_start import wrap_verb_main

logger = colcon_logger.getChild(__name__)

"""(argument destination, colcon's default, the default with --wasm)."""
WASM_BASES = (
    ('build_base', 'build', 'build_wasm'),
    ('install_base', 'install', 'install_wasm'),
)


def apply_wasm_default_bases(args):
    """
    Use `build_wasm/` and `install_wasm/` when `--wasm` is given.

    A base the user chose (on the command line, in a mixin or in a defaults
    file) is kept: only colcon's own default value is replaced.

    :param args: the parsed arguments (changed in place)
    """
    if not getattr(args, 'wasm', False):
        return
    for dest, native, wasm in WASM_BASES:
        value = getattr(args, dest, None)
        if value is None or not is_default_value(value):
            continue
        if str(value).rstrip('/').split('/')[-1] != native:
            continue  # a default from colcon-defaults: the user chose it
        new_value = str(value)[:-len(native)] + wasm \
            if str(value).endswith(native) else wasm
        logger.debug(f"--wasm: default '{dest}' is '{new_value}'")
        setattr(args, dest, wrap_default_value(new_value))


class WasmArgumentParserDecorator(ArgumentParserDecoratorExtensionPoint):
    """Default build and install bases of `--wasm` builds."""

    # lowest priority: applied last, so it wraps the other decorators and sees
    # the values of mixins and defaults files
    PRIORITY = 10

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            ArgumentParserDecoratorExtensionPoint.EXTENSION_POINT_VERSION,
            '^1.0')

    def decorate_argument_parser(self, *, parser):  # noqa: D102
        return WasmArgumentDecorator(parser)


class WasmArgumentDecorator(ArgumentParserDecorator):
    """Apply the `--wasm` default bases after parsing, and start verbs with the wasm steps."""

    def parse_args(self, *args, **kwargs):
        """Parse, then switch default bases for `--wasm` and wrap the verb's main."""
        parsed = self._parser.parse_args(*args, **kwargs)
        apply_wasm_default_bases(parsed)
        # the build and test verbs find Emscripten and set the environment
        # when they start, not in package selection
        wrap_verb_main(parsed)
        return parsed
