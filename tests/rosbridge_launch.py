# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`colcon-wasm launch` running in the background for the rosbridge tests.

    with BackgroundLaunch(install, launch_file, '--rosbridge', '127.0.0.1:0') as run:
        run.url            # ws://127.0.0.1:PORT, read from the server's first line
        run.wait_for('HEARD from roslibjs')
        run.output()       # everything printed so far

Every wait is bounded; the launch is stopped with SIGINT (as Ctrl-C) and
killed if it does not stop.
"""

import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import threading
import time

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402

JS = Path(__file__).resolve().parent / 'js'
URL = re.compile(r'rosbridge server listening on (ws://\S+)')


class BackgroundLaunch:
    """A `colcon-wasm launch` process and its output, read by a thread."""

    def __init__(self, install, *args, duration=300, wait_url=True, url_pattern=URL,
                 command='launch', after=()):
        """
        Start it; with ``wait_url`` wait for the server's URL (``url_pattern``'s group 1).

        ``command='run'`` runs ``colcon-wasm run``, whose PKG EXE and arguments go
        last (``after``).
        """
        self.lines = []
        self._lock = threading.Lock()
        command = [str(demo_build.venv_tool('colcon-wasm')), command, '--install-base',
                   str(install), '--duration', str(duration), *map(str, args),
                   *map(str, after)]
        # its own process group: SIGINT reaches the Node host as Ctrl-C does
        self.process = subprocess.Popen(command, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True,
                                        start_new_session=True)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        self.url = None
        if wait_url:
            match = self.wait_for(url_pattern, timeout=90)
            self.url = match.group(1)

    def _read(self):
        for line in self.process.stdout:
            with self._lock:
                self.lines.append(line.rstrip('\n'))

    @property
    def port(self):
        """The server's port."""
        return int(self.url.rsplit(':', 1)[1])

    def output(self):
        """Everything printed so far."""
        with self._lock:
            return '\n'.join(self.lines)

    def wait_for(self, pattern, timeout=30):
        """Wait for a line matching ``pattern`` (text or regex); return the match."""
        regex = re.compile(re.escape(pattern)) if isinstance(pattern, str) else pattern
        deadline = time.monotonic() + timeout
        seen = 0
        while time.monotonic() < deadline:
            with self._lock:
                lines = self.lines[seen:]
            for line in lines:
                match = regex.search(line)
                if match:
                    return match
            seen += len(lines)
            if self.process.poll() is not None and not self._reader.is_alive():
                break
            time.sleep(0.05)
        raise AssertionError(f'no line matched {regex.pattern!r} within {timeout} s; '
                             f'output:\n{self.output()[-6000:]}')

    def count(self, text):
        """How many lines contain ``text``."""
        with self._lock:
            return sum(text in line for line in self.lines)

    def stop(self):
        """Stop the launch (SIGINT, then kill); return its exit status."""
        if self.process.poll() is None:
            self._signal(signal.SIGINT)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self._signal(signal.SIGKILL)
                self.process.wait(timeout=10)
        self._signal(signal.SIGKILL)  # anything of the group left behind
        self._reader.join(timeout=5)
        return self.process.returncode

    def _signal(self, number):
        try:
            os.killpg(self.process.pid, number)
        except ProcessLookupError:
            pass

    def __enter__(self):  # noqa: D105
        return self

    def __exit__(self, *exc):  # noqa: D105
        self.stop()


def node_script(script, *args, timeout=90):
    """Run a Node script of tests/js; return its last stdout line as JSON."""
    import json
    result = subprocess.run(['node', str(JS / script), *map(str, args)], capture_output=True,
                            text=True, timeout=timeout, cwd=str(JS))
    lines = [line for line in result.stdout.splitlines() if line.startswith('{')]
    command = f"node {script} {' '.join(map(str, args))}"
    assert lines, (f'{command} printed no result (exit {result.returncode}):\n'
                   f'{result.stdout[-3000:]}\n{result.stderr[-3000:]}')
    data = json.loads(lines[-1])
    assert data.get('ok'), f"{command} failed: {data.get('error')}\n{result.stderr[-3000:]}"
    return data
