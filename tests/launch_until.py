# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Run ``colcon-wasm launch|run`` until what a test waits for is in its output.

A launch of nodes that never end (a C++ talker, a service server) runs to
its ``--duration``. A test that has seen what it checks stops it sooner,
with SIGINT as Ctrl-C: the launch then stops its nodes as at the end of
``--duration`` (same output, same exit status), so the test's assertions
on the whole output hold as before::

    code, out = run_until(command, until=finished('client-2'))

``--duration`` still bounds a run whose awaited line never comes, and the
process group is killed once ``timeout`` seconds have passed.
"""

import os
import re
import signal
import subprocess
import threading


def run_until(command, *, until=None, timeout=180, env=None, cwd=None):
    """
    Run ``command`` (stdout and stderr together); stop it once ``until(output)`` is true.

    :param command: the colcon-wasm command line
    :param until: ``until(output so far)``; None waits for the command's own end
    :param timeout: seconds after which the command's process group is killed
    :param env: its environment (default: this process')
    :param cwd: its working directory (default: this process')
    :returns: (exit status, output)
    """
    # its own process group: SIGINT reaches the Node host as Ctrl-C does
    process = subprocess.Popen([str(c) for c in command], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, env=env, cwd=cwd,
                               start_new_session=True)
    killer = threading.Timer(timeout, _signal, (process, signal.SIGKILL))
    killer.start()
    out = ''
    try:
        for line in process.stdout:
            out += line
            if until is not None and until(out):
                _signal(process, signal.SIGINT)
                until = None
        return process.wait(), out
    finally:
        killer.cancel()
        _signal(process, signal.SIGKILL)  # whatever of its group is left


def finished(label):
    """Return an ``until``: the launch's process ``label`` (``name-N``) ended, cleanly or not."""
    return lambda out: f'[{label}]: process has' in out


def line_indexes(out, pattern):
    """Return the indexes of the lines of ``out`` that ``pattern`` matches (from their start)."""
    regex = re.compile(pattern)
    return [i for i, line in enumerate(out.splitlines()) if regex.match(line)]


def went_on_after(crash, *heard):
    """
    Return an ``until``: a line matched ``crash``, and each of ``heard`` matched a line after it.

    For a launch where one process crashes on purpose and the others must go on.
    """
    def until(out):
        died = line_indexes(out, crash)
        return bool(died) and all(any(i > died[0] for i in line_indexes(out, pattern))
                                  for pattern in heard)
    return until


def _signal(process, number):
    try:
        os.killpg(process.pid, number)
    except (ProcessLookupError, PermissionError):
        pass
