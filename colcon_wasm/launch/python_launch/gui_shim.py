# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The host process of a GUI program a launch file starts (``gui_programs.py``).

It says what was left out and why, then waits until the launch stops it,
as the program's window would stay open; it exits cleanly on SIGINT or
SIGTERM. Standard library only.

Usage::

    python3 gui_shim.py PKG/EXE REASON [ARGS ...]
"""

import os
import signal
import sys


def package_uri(path):
    """Return ``package://PKG/REL`` for a file ``.../share/PKG/REL`` of a share folder, or None."""
    parts = str(path).split('/')
    for i in range(len(parts) - 2, 0, -1):
        if parts[i - 1] == 'share' and parts[i] and i + 1 < len(parts):
            return f"package://{parts[i]}/{'/'.join(parts[i + 1:])}"
    return None


def note(item, reason, args):
    """Return the line that says the program is not started, and what its file was."""
    text = (f'[colcon-wasm] {item} is not started: {reason}, with no WebAssembly build; '
            'the launch goes on without it')
    if '-d' in args[:-1]:
        display = args[args.index('-d') + 1]
        uri = package_uri(display)
        if uri:
            # the page's 3D view reads .rviz files (docs/launcher.md)
            text += (f' (its display file {uri}: the page shows it, colcon-wasm serve '
                     f'then /?rviz={uri}, with ?rosbridge= of launch --rosbridge)')
        else:
            text += f' (its display file {display} is not shown headless)'
    return text


def main(argv=None):
    """Print the note, then wait for SIGINT or SIGTERM; exit 0."""
    # at once: launch's SIGINT and the terminal's may both come, the second while the first
    # ends the interpreter, when Python's own handler would be back and kill it with -2
    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, _end)
    argv = sys.argv[1:] if argv is None else argv
    item, reason, args = argv[0], argv[1], argv[2:]
    print(note(item, reason, args), file=sys.stderr, flush=True)
    while True:
        signal.pause()


def _end(*_):
    """End cleanly now, as the window would close; later signals change nothing."""
    os._exit(0)


if __name__ == '__main__':
    sys.exit(main())
