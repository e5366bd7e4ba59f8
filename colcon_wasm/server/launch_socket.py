# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's launch files: the ``/launch`` WebSocket of ``colcon-wasm serve``.

The page has the bus, serve has the build host. A launch file started from
the page is evaluated here, as ``colcon-wasm launch`` evaluates it:

* a file Humble's launch runs (Python, or XML/YAML in an install with
  launch_ros; ``python_launch.runs_on_host_launch``): the real ``launch``
  runs on the host (``python_launch/front.py``) with its host prefix, and
  each host program it starts (``node_shim.py``) connects to a Unix socket
  that this module listens on. Each such connection is a channel of the
  page's WebSocket: the page runs the program on its bus and answers as the
  Node.js host of ``colcon-wasm launch`` does
  (``packages/wasm_js/src/launch/process_protocol.mjs``). So launch's
  process events, ``respawn``, ``TimerAction``, lifecycle transitions and
  ``LoadComposableNodes`` (launch_ros' node, linked to the page's bus) are
  launch's own;
* an XML or YAML file of an install without launch_ros: colcon-wasm's own
  reader (``colcon_wasm.launch.loader``) makes the plan, which the page starts.

One connection is one launch. Page to serve (JSON, ``op`` first):

* ``arguments {package, file}``: answered ``arguments {package, file,
  arguments: [{name, default, description, choices, conditional}]}``;
* ``start {package, file, arguments: {name: value}}``: answered ``started
  {package, file, runner}`` and then, for launch: ``output {stream, text}``
  (launch's own output), ``open {ch}``, ``to {ch, msg}`` (a host program's
  request), ``closed {ch}``, ``rviz {uri}`` (rviz2 was asked to show this
  display file: the page's 3D view shows it), ``ended {code}``; for the own
  reader: ``plan {processes, loads, load_timeout}``;
* ``from {ch, msg}``: the bus' answer to a host program; ``close {ch}``;
* ``stop``: SIGINT to the launch, as Ctrl-C. Closing the connection does the same.

Serve to page, for a request it refuses: ``error {msg}`` (the connection stays up).
"""

import json
import os
from pathlib import Path
import re
import signal
import socket
import subprocess
import threading

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.server.websocket import Connection

logger = colcon_logger.getChild(__name__)

LAUNCH_PATH = '/launch'
MAX_MESSAGE_BYTES = 64 * 1024 * 1024  # a spawn carries --params-file contents
MAX_QUEUED_BYTES = 64 * 1024 * 1024
COMMAND = 'colcon-wasm serve'
#: what ros2launch takes for a launch file (its ``is_launch_file``), by the end of its name
LAUNCH_FILE_ENDINGS = ('launch.py', 'launch.xml', 'launch.yaml', 'launch.yml')
#: how long a launch has to end after SIGINT, then after SIGTERM
STOP_TIMEOUTS = (10.0, 5.0)
ARGUMENTS_TIMEOUT = 60.0
_RVIZ_FILE = re.compile(r'its display file (package://\S+?\.rviz)\b')


class LaunchRequestError(ColconWasmError):
    """A launch request of the page that cannot be done; the text says why."""


def launch_files(install_space):
    """
    List the launch files of the install space's packages, for the page.

    Each is ``{package, file, path, runner, problem}``: ``path`` relative to
    the package's share folder, ``runner`` 'launch' (Humble's launch) or
    'reader' (colcon-wasm's own), ``problem`` why it cannot run, or None.
    """
    from colcon_wasm.launch.python_launch import runs_on_host_launch
    packages = install_space.packages()
    has_launch = 'launch_ros' in packages and 'launch' in packages
    listed = []
    for name in sorted(packages):
        share = packages[name].share
        if not share.is_dir():
            continue
        for path in sorted(share.rglob('*')):
            if not path.name.lower().endswith(LAUNCH_FILE_ENDINGS) or not path.is_file():
                continue
            python = path.name.lower().endswith('.py')
            problem = None
            if python and not has_launch:
                problem = ("Python launch files run with Humble's launch and launch_ros, which "
                           "this install space lacks: build them with 'colcon build --wasm "
                           "--packages-up-to launch launch_ros launch_xml launch_yaml'")
            listed.append({
                'package': name, 'file': path.name,
                'path': path.relative_to(share).as_posix(),
                'runner': 'launch' if runs_on_host_launch(path, install_space) else 'reader',
                'problem': problem,
            })
    return listed


class LaunchService:
    """The launches the pages of one serve started; each ends with its page's connection."""

    def __init__(self, install_space, runtime_python):
        """
        Keep what a launch needs.

        :param runtime_python: the folder of colcon-wasm's ``rclpy`` (the runtime's ``python/``)
        """
        self.install_space = install_space
        self.runtime_python = Path(runtime_python)
        self._lock = threading.Lock()
        self._sessions = set()

    def serve(self, sock, peer):
        """Run one page connection until it closes; its launch is stopped then."""
        session = _PageLaunchSession(self, peer)
        connection = Connection(sock, max_message_bytes=MAX_MESSAGE_BYTES,
                                max_queued_bytes=MAX_QUEUED_BYTES)
        session.connection = connection
        with self._lock:
            self._sessions.add(session)
        try:
            connection.run(session.on_message)
        finally:
            with self._lock:
                self._sessions.discard(session)
            session.close()

    def close(self):
        """Stop every launch (serve stops)."""
        with self._lock:
            sessions = list(self._sessions)
        for session in sessions:
            session.close()

    def find(self, package, file):
        """
        Return the path of a listed launch file.

        :raises LaunchRequestError: when the package has no such launch file
        """
        for entry in launch_files(self.install_space):
            if entry['package'] == package and file in (entry['file'], entry['path']):
                if entry['problem']:
                    raise LaunchRequestError(f"{package} {file}: {entry['problem']}")
                share = self.install_space.package(package).share
                return share / entry['path'], entry['runner']
        raise LaunchRequestError(
            f"package '{package}' has no launch file '{file}' in the install space "
            f'{self.install_space.base}')


class _PageLaunchSession:
    """One page connection: at most one launch."""

    def __init__(self, service, peer):
        self.service = service
        self.peer = peer
        self.connection = None
        self.run = None
        self.started = False

    def send(self, op, **fields):
        self.connection.send(json.dumps(dict({'op': op}, **fields)))

    def on_message(self, data, binary):
        try:
            if binary:
                raise LaunchRequestError('/launch takes JSON text messages only')
            self._request(json.loads(data))
        except (ValueError, KeyError, TypeError) as e:
            self.send('error', msg=f'bad request ({type(e).__name__}: {e})')
        except ColconWasmError as e:
            self.send('error', msg=str(e))

    def _request(self, request):
        op = request.get('op') if isinstance(request, dict) else None
        if op == 'arguments':
            self._arguments(request)
        elif op == 'start':
            self._start(request)
        elif op in ('from', 'close'):
            if self.run is not None:
                self.run.to_channel(int(request['ch']), request.get('msg'), op == 'close')
        elif op == 'stop':
            if self.run is not None:
                self.run.stop()
        else:
            self.send('error', msg=f'unknown op {op!r}: arguments, start, from, close, stop')

    def _arguments(self, request):
        package, file = str(request['package']), str(request['file'])
        path, runner = self.service.find(package, file)
        if runner == 'reader':
            from colcon_wasm.launch.loader import declared_arguments
            listed = declared_arguments(path, install_space=self.service.install_space)
        else:
            listed = _host_arguments(path, self.service)
        self.send('arguments', package=package, file=file, arguments=listed)

    def _start(self, request):
        if self.started:
            raise LaunchRequestError('this connection has started a launch already: one launch '
                                     'per connection')
        package, file = str(request['package']), str(request['file'])
        arguments = {str(k): str(v) for k, v in (request.get('arguments') or {}).items()}
        path, runner = self.service.find(package, file)
        if runner == 'reader':
            self._start_plan(path, arguments, package, file)
            self.started = True
            return
        self.started = True
        self.run = _HostLaunchRun(self, path, arguments)
        self.send('started', package=package, file=file, runner=runner)
        self.run.start()

    def _start_plan(self, path, arguments, package, file):
        from colcon_wasm.launch.loader import load_launch_file
        from colcon_wasm.launch.runner import host_plan
        install_space = self.service.install_space
        plan = load_launch_file(path, arguments, install_space=install_space)
        description = host_plan(plan, install_space)
        self.send('started', package=package, file=file, runner='reader')
        self.send('plan', processes=description['processes'], loads=description['loads'],
                  load_timeout=description['load_timeout'])

    def close(self):
        if self.run is not None:
            self.run.stop(wait=True)


def _host_arguments(path, service):
    """Return a launch file's arguments as Humble's launch reads them (front.py, as JSON)."""
    from colcon_wasm.launch.python_launch import HostLaunch
    launch = HostLaunch(path, {}, show_args=True)
    try:
        types = [str(p) for p in service.install_space.type_description_files()]
        launch.prepare({'types': types}, service.install_space, None,
                       runtime_python=service.runtime_python, ready_pipe=False)
        completed = subprocess.run(
            launch.front_command(command=COMMAND, print_only=True, as_json=True),
            env=launch.front_environment(), stdin=subprocess.DEVNULL, capture_output=True,
            text=True, timeout=ARGUMENTS_TIMEOUT)
    except subprocess.TimeoutExpired:
        raise LaunchRequestError(f'{path}: reading its arguments took over '
                                 f'{ARGUMENTS_TIMEOUT:g} s') from None
    finally:
        launch.cleanup()
    if completed.returncode != 0:
        raise LaunchRequestError(completed.stderr.strip() or
                                 f'{path}: reading its arguments failed (exit status '
                                 f'{completed.returncode})')
    lines = completed.stdout.strip().splitlines()
    return json.loads(lines[-1]) if lines else []


class _HostLaunchRun:
    """One launch file run by Humble's launch on the host, its programs on the page's bus."""

    def __init__(self, session, path, arguments):
        from colcon_wasm.launch.python_launch import HostLaunch
        self.session = session
        self.launch = HostLaunch(path, arguments)
        self.front = None
        self.listener = None
        self.channels = {}
        self.next_channel = 1
        self.lock = threading.Lock()
        self.ended = threading.Event()

    def start(self):
        service = self.session.service
        install_space = service.install_space
        description = {'types': [str(p) for p in install_space.type_description_files()]}
        self.launch.prepare(description, install_space, None,
                            runtime_python=service.runtime_python, ready_pipe=False)
        self.listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.listener.bind(self.launch.prefix.config['socket'])
        self.listener.listen(64)
        env = self.launch.front_environment()
        env['PYTHONUNBUFFERED'] = '1'  # launch's lines reach the page as they are written
        try:
            self.front = subprocess.Popen(
                self.launch.front_command(command=COMMAND), env=env, stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
        except OSError as e:
            self._finish()
            raise LaunchRequestError(f'cannot start the launch of {self.launch.path}: {e}') \
                from None
        for target, args in ((self._accept, ()), (self._output, ('stdout',)),
                             (self._output, ('stderr',)), (self._wait, ())):
            threading.Thread(target=target, args=args, daemon=True).start()

    def _send(self, op, **fields):
        try:
            self.session.send(op, **fields)
        except Exception:  # the page has gone: the launch is being stopped
            logger.debug('a launch message did not reach the page', exc_info=True)

    def _accept(self):
        while True:
            try:
                connection, _ = self.listener.accept()
            except OSError:
                return  # the launch ended
            with self.lock:
                channel = self.next_channel
                self.next_channel += 1
                self.channels[channel] = connection
            self._send('open', ch=channel)
            threading.Thread(target=self._read_channel, args=(channel, connection),
                             daemon=True).start()

    def _read_channel(self, channel, connection):
        with connection.makefile('r', encoding='utf-8') as lines:
            try:
                for line in lines:
                    if line.strip():
                        self._send('to', ch=channel, msg=json.loads(line))
            except (OSError, ValueError) as e:
                logger.debug(f'launch channel {channel} broke: {e}')
        with self.lock:
            self.channels.pop(channel, None)
        connection.close()
        self._send('closed', ch=channel)

    def to_channel(self, channel, message, close):
        """Write the bus' message to a host program (or close its connection)."""
        with self.lock:
            connection = self.channels.get(channel)
        if connection is None:
            return  # it has gone: its closed message is on the way
        try:
            if message is not None:
                connection.sendall((json.dumps(message) + '\n').encode())
            if close:
                connection.shutdown(socket.SHUT_WR)
        except OSError:
            pass  # the program was killed: its reader closes the channel

    def _output(self, stream):
        pipe = getattr(self.front, stream)
        for raw in pipe:
            text = raw.decode('utf-8', 'replace').rstrip('\n')
            self._send('output', stream=stream, text=text)
            match = _RVIZ_FILE.search(text)
            if match:
                self._send('rviz', uri=match.group(1))

    def _wait(self):
        status = self.front.wait()
        self._finish()
        self._send('ended', code=status)

    def _finish(self):
        if self.ended.is_set():
            return
        self.ended.set()
        if self.listener is not None:
            try:
                self.listener.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
            self.listener.close()
        self.launch.cleanup()

    def stop(self, wait=False):
        """Send the launch SIGINT, as Ctrl-C; with ``wait``, SIGTERM and SIGKILL follow."""
        if self.front is None or self.front.poll() is not None:
            return
        _signal_group(self.front, signal.SIGINT)
        if not wait:
            return
        for timeout, then in zip(STOP_TIMEOUTS, (signal.SIGTERM, signal.SIGKILL)):
            try:
                self.front.wait(timeout=timeout)
                return
            except subprocess.TimeoutExpired:
                logger.warning(f'the launch of {self.launch.path} did not stop within '
                               f'{timeout:g} s: sending {then.name}')
                _signal_group(self.front, then)
        self.front.wait()


def _signal_group(process, number):
    """Signal the launch alone at first (it stops its programs); SIGKILL reaches them all."""
    try:
        if number == signal.SIGKILL:
            os.killpg(process.pid, number)
        else:
            process.send_signal(number)
    except (ProcessLookupError, PermissionError):
        pass
