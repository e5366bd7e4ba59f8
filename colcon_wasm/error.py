# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The error family of colcon-wasm: one base class and one way out."""


class ColconWasmError(RuntimeError):
    """
    A problem the user can fix: the message says what failed, where, and what to do.

    Every exception class of colcon-wasm subclasses it. Library functions
    raise it; the edges (colcon's extensions and the `colcon-wasm` commands
    of :mod:`colcon_wasm.cli`) turn it into one line and an exit with
    :func:`exit_on_error`. It is a `RuntimeError`, which colcon reports as a
    one-line message without a traceback.
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


class exit_on_error:  # noqa: N801 a context manager, named like contextlib's
    """
    Turn a :class:`ColconWasmError` raised inside into a one-line `SystemExit`.

    Use it where a command starts: `with exit_on_error('colcon-wasm serve'):`.
    The exit code is 1 and the line is :func:`exit_message`'s. (A class, not
    `contextlib.contextmanager`: the compile launcher imports this module once
    per compile, and contextlib would be one more module to load.)
    """

    def __init__(self, command='colcon build --wasm'):
        """:param str command: the command the user ran (starts the line)."""
        self.command = command

    def __enter__(self):  # noqa: D105
        return self

    def __exit__(self, kind, error, traceback):  # noqa: D105
        if isinstance(error, ColconWasmError):
            raise SystemExit(exit_message(error, command=self.command)) from error
        return False
