# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The one exception type colcon-wasm raises for bad input."""


class ColconWasmError(RuntimeError):
    """
    A problem the user can fix: the message says what, where, and how.

    colcon extensions turn it into a one-line `SystemExit` (see
    :func:`exit_on_error`); library functions raise it.
    """


def exit_message(error, *, command='colcon build --wasm'):
    """
    Format an error as the one line printed before exiting.

    :param error: the :class:`ColconWasmError`
    :param str command: the command the user ran
    :returns: the message
    :rtype: str
    """
    return f'{command}: {error}'
