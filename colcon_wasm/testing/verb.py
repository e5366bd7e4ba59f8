# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon test --wasm`: the install base as `colcon build --wasm` left it.

The test verb has the same package selection as `colcon build`, so the
`wasm.*` package types (and the `colcon test` task of
:mod:`colcon_wasm.task.test`) are chosen the same way. What differs: the
install base is read, not written. Its marker says which underlays it was
built on (:func:`colcon_wasm.underlay.get_underlays`); the tests run on
them, with their build variables, unless `--wasm-underlay` or
`COLCON_WASM_PREFIX_PATH` name others.
"""

import os
from pathlib import Path

from colcon_wasm.error import ColconWasmError
from colcon_wasm.error import exit_on_error
from colcon_wasm.underlay import get_underlays
from colcon_wasm.underlay import read_marker
from colcon_wasm.underlay import split_native_prefixes
from colcon_wasm.underlay import underlay_environment

COMMAND = 'colcon test --wasm'


def is_test_verb(args):
    """Check if the command is `colcon test`."""
    return getattr(args, 'verb_name', None) == 'test'


def prepare_test_verb(args):
    """
    Make the underlays the install base was built on visible to the tests.

    :raises SystemExit: when the install base was not built with `--wasm`
    """
    install_base = Path(getattr(args, 'install_base', None) or 'install_wasm').absolute()
    with exit_on_error(COMMAND):
        marker = read_marker(install_base)
        if marker is None:
            raise ColconWasmError(
                f"'{install_base}' was not built with colcon build --wasm: build the "
                'packages and their tests first (colcon build --wasm --wasm-tests PKG...), '
                'or pass the --install-base of that build')
    # the underlays it was built on (colcon_wasm.underlay.get_underlays)
    underlays = get_underlays(args)
    kept, removed = split_native_prefixes(os.environ)
    if removed:
        os.environ.update(kept)
    with exit_on_error(COMMAND):
        os.environ.update(underlay_environment(underlays, os.environ))
    return underlays
