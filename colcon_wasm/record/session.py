# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Record and replay beside a launch: the options, and the launcher's side.

The launcher opens pipes for the Node host (``pass_fds``). To record, it
creates the bag and writes its header, then the host's recording worker
writes the chunks into it (its descriptor goes to the host too) and reports
each write through a pipe; a thread here answers each topic the host finds
with the Schema and Channel records to write first (a pipe back), indexes
the chunks and writes the summary at the end
(:class:`colcon_wasm.record.bag_writer.BagWriter`). Compressed bags get
their chunks through the pipe and are written here. Another thread streams
a bag to play into the host (:mod:`colcon_wasm.record.bag_reader`), which
keeps the timing and publishes (packages/wasm_js/src/bridges/record/).
"""

import argparse
import contextlib
import json
import os
import re
import threading

from colcon_wasm.launch.errors import LaunchError
from colcon_wasm.record import BagError
from colcon_wasm.record import frames
from colcon_wasm.record.bag_reader import bag_files
from colcon_wasm.record.bag_reader import read_messages
from colcon_wasm.record.bag_reader import unplayable
from colcon_wasm.record.bag_writer import BagWriter
from colcon_wasm.record.mcap_file import COMPRESSIONS
from colcon_wasm.record.qos import player_qos
from colcon_wasm.record.qos import QosOverrideError
from colcon_wasm.record.qos import read_overrides
from colcon_wasm.ros2msg import SchemaError

DEFAULT_CLOCK_HZ = 40.0


def _positive(text):
    value = float(text)
    if value <= 0:
        raise ValueError(text)
    return value


_TOPIC = re.compile(r'^(/[A-Za-z_][A-Za-z0-9_]*)+$')


def _seconds(text):
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not 0 <= value < float('inf'):
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds (0 or more)")
    return value


def add_record_arguments(parser):
    """Add ``--record`` and its options (run and launch)."""
    parser.add_argument(
        '--record', metavar='FILE.mcap',
        help="Record the bus into FILE.mcap (rosbag2's MCAP layout), as it goes")
    parser.add_argument(
        '--record-topic', action='append', default=[], metavar='TOPIC',
        help='Record only this topic (repeatable; default: every topic)')
    parser.add_argument(
        '--record-regex', metavar='REGEX',
        help='Record the topics whose name this regular expression finds (ECMAScript, '
             'searched as ros2 bag record -e does), besides any --record-topic')
    parser.add_argument(
        '--record-exclude', metavar='REGEX',
        help='Record no topic whose name this regular expression finds (as ros2 bag '
             'record -x)')
    parser.add_argument(
        '--record-compression', choices=sorted(COMPRESSIONS), default='none',
        help='Compression of the chunks (default: %(default)s, as ros2 bag record; zstd: '
             'smaller files for more CPU)')


def add_play_arguments(parser, *, option):
    """
    Add the replay options.

    :param option: True for ``launch --play FILE``; False for ``play``, whose
      bag is its first positional argument (added by the caller)
    """
    if option:
        parser.add_argument(
            '--play', metavar='BAG',
            help='Play a bag (.mcap file or rosbag2 directory) into the nodes once they run')
    parser.add_argument(
        '--rate', type=_positive, default=1.0, metavar='R',
        help='Play R times as fast as recorded (default: 1)')
    parser.add_argument(
        '--loop', action='store_true', help='Play the bag again and again')
    parser.add_argument(
        '--qos-profile-overrides-path', metavar='FILE',
        help="A YAML file of topics' QoS for the player's publishers, as ros2 bag play "
             '(e.g. "/chatter: {reliability: best_effort, depth: 5}"); other topics get '
             'the QoS their recorded publishers offered')
    parser.add_argument(
        '--remap', '-m', action='append', default=[], metavar='FROM:=TO',
        help='Play topic FROM on topic TO, as ros2 bag play --remap (one rule per --remap, '
             'repeat it for more)')
    parser.add_argument(
        '--start-offset', type=_seconds, default=0.0, metavar='S',
        help='Start S seconds into the bag, as ros2 bag play --start-offset (each loop '
             'starts there too)')
    parser.add_argument(
        '--topics', nargs='+', default=None, metavar='TOPIC',
        help='Play only these topics')
    parser.add_argument(
        '--clock', nargs='?', type=_positive, const=DEFAULT_CLOCK_HZ, default=None, metavar='HZ',
        help='Publish /clock (rosgraph_msgs/msg/Clock) with the bag time at HZ (default '
             f'{DEFAULT_CLOCK_HZ}) for use_sim_time nodes')


def _remaps(rules):
    """
    Read ``--remap FROM:=TO`` rules into ``{from: to}`` (names made absolute).

    :raises LaunchError: naming a rule that is no FROM:=TO of two topic names
    """
    remaps = {}
    for rule in rules:
        source, sep, target = rule.partition(':=')
        names = [n if n.startswith('/') else f'/{n}' for n in (source, target)]
        if not sep or not all(_TOPIC.match(n) for n in names):
            raise LaunchError(f"--remap '{rule}' is not FROM:=TO of two topic names "
                              '(e.g. /chatter:=/news)')
        remaps[names[0]] = names[1]
    return remaps


def _pattern(args, option):
    """
    Check a regular expression option (Python's re reads what ECMAScript does, mostly).

    :raises LaunchError: naming the option and where the expression is wrong
    """
    pattern = getattr(args, option, None)
    if pattern is None:
        return None
    try:
        re.compile(pattern)
    except re.error as e:
        raise LaunchError(f"--{option.replace('_', '-')} '{pattern}' is not a regular "
                          f'expression: {e}') from None
    return pattern


def bag_plan(args, *, play=None, stop_after_play=False):
    """
    Check the record and replay options.

    :param play: the bag to play (``play``'s argument), else ``args.play``
    :returns: ``{'record': {...}, 'play': {...}}`` (either may be missing)
    :raises LaunchError: for a bag that is not there
    """
    plan = {}
    if getattr(args, 'record', None):
        directory = os.path.dirname(os.path.abspath(args.record)) or '.'
        if not os.path.isdir(directory):
            raise LaunchError(f"--record '{args.record}': the folder '{directory}' does not exist")
        plan['record'] = {'path': args.record, 'topics': list(args.record_topic) or None,
                          'regex': _pattern(args, 'record_regex'),
                          'exclude': _pattern(args, 'record_exclude'),
                          'compression': args.record_compression}
    else:
        for option in ('record_topic', 'record_regex', 'record_exclude'):
            if getattr(args, option, None):
                raise LaunchError(f"--{option.replace('_', '-')} selects what --record "
                                  'records: add --record FILE.mcap')
    play = play or getattr(args, 'play', None)
    if getattr(args, 'remap', None) and not play:
        raise LaunchError('--remap renames topics of the bag --play plays: add --play BAG')
    if play:
        try:
            files = bag_files(play)
        except BagError as e:
            raise LaunchError(str(e)) from None
        overrides = {}
        if args.qos_profile_overrides_path:
            try:
                overrides = read_overrides(args.qos_profile_overrides_path)
            except QosOverrideError as e:
                raise LaunchError(f'--qos-profile-overrides-path: {e}') from None
        remaps = _remaps(getattr(args, 'remap', None) or [])
        plan['play'] = {'path': play, 'files': [str(f) for f in files], 'rate': args.rate,
                        'loop': args.loop, 'topics': args.topics, 'clock': args.clock,
                        'start_offset': args.start_offset, 'qos_overrides': overrides,
                        'remaps': remaps, 'stop_after': stop_after_play}
    return plan


_PIPE_BYTES = 1024 * 1024


def _widen_pipe(fd):
    """
    Give the recording pipe room for a whole chunk (Linux; else left as it is).

    A chunk of images is a megabyte: with the default 64 KiB the host and
    the launcher would wake each other 16 times per chunk.
    """
    try:
        import fcntl
        fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, _PIPE_BYTES)
    except (ImportError, AttributeError, OSError):
        pass


class BagSession:
    """The launcher's side of recording and replay for one run of the host."""

    def __init__(self, plan, install_space, err):
        """Prepare (nothing runs before ``start``)."""
        self.plan = plan
        self.install_space = install_space
        self.err = err
        self.fds = []
        self.host_plan = {}
        self._threads = []
        self._close_after_start = []
        self.failed = False

    def start(self):
        """Open the pipes and start the threads; ``host_plan`` then holds the host's entries."""
        if 'record' in self.plan:
            spec = self.plan['record']
            try:
                # uncompressed chunks go into the file from the host's recording worker
                writer = BagWriter(spec['path'], self.install_space.ros2msg_schemas(),
                                   compression=spec['compression'], host_writes=True)
            except (BagError, SchemaError) as e:
                raise LaunchError(str(e)) from None
            read_end, write_end = os.pipe()
            _widen_pipe(read_end)
            answers_read, answers_write = os.pipe()
            self.fds += [write_end, answers_read]
            self._close_after_start += [write_end, answers_read]
            self.host_plan['record'] = {'fd': write_end, 'replies': answers_read,
                                        'topics': spec['topics'], 'regex': spec.get('regex'),
                                        'exclude': spec.get('exclude'), 'file': None}
            if spec['compression'] == 'none':
                self.fds.append(writer.fileno())
                self.host_plan['record']['file'] = {'fd': writer.fileno(),
                                                    'offset': writer.host_offset}
            # unbuffered: chunks are read straight into the frame buffer
            self._thread(self._record, writer, os.fdopen(read_end, 'rb', buffering=0),
                         os.fdopen(answers_write, 'wb', buffering=0))
        if 'play' in self.plan:
            spec = self.plan['play']
            read_end, write_end = os.pipe()
            self.fds.append(read_end)
            self._close_after_start.append(read_end)
            self.host_plan['play'] = {k: spec[k] for k in ('rate', 'clock', 'stop_after')}
            self.host_plan['play']['fd'] = read_end
            self._thread(self._play, spec, os.fdopen(write_end, 'wb'))

    def host_started(self):
        """Close this process' copies of the host's pipe ends."""
        for fd in self._close_after_start:
            os.close(fd)
        self._close_after_start = []

    def finish(self, status):
        """Wait for the threads; the command's status."""
        self.host_started()
        for t in self._threads:
            t.join()
        return 1 if self.failed and status == 0 else status

    def _thread(self, target, *args):
        t = threading.Thread(target=target, args=args, daemon=True)
        t.start()
        self._threads.append(t)

    def _say(self, level, text):
        print(f'[{level}] [rosbag2]: {text}', file=self.err, flush=True)

    def _record(self, writer, stream, answers):
        dropped = lost = 0
        try:
            # the chunk is written before the next frame is read: one buffer for all
            for kind, body in frames.read_frames(stream):
                if kind == frames.CHANNEL:
                    self._answer(writer, json.loads(bytes(body)), answers)
                elif kind == frames.WRITTEN:
                    writer.host_wrote(json.loads(bytes(body)))
                elif kind == frames.FAILED:
                    writer.host_failed(json.loads(bytes(body)))
                elif kind == frames.CHUNK:
                    writer.write_chunk(*frames.decode_chunk(body))
                elif kind == frames.NOTE:
                    note = json.loads(bytes(body))
                    dropped = note.get('dropped', dropped)
                    lost = note.get('lost', lost)
                if writer.failed and not self.failed:
                    self.failed = True
                    self._say('ERROR', writer.failed)
        finally:
            stream.close()
            with contextlib.suppress(OSError):
                answers.close()
            writer.close()
            if writer.failed and not self.failed:
                self.failed = True
                self._say('ERROR', writer.failed)
            if not writer.failed:
                missed = [f'{dropped} dropped: the disk did not keep up'] if dropped else []
                if lost:
                    missed.append(f"{lost} lost before the recorder took them: the publishers' "
                                  'history was overwritten')
                missed = f" ({'; '.join(missed)})" if missed else ''
                self._say('INFO',
                          f"recorded {writer.messages} messages into '{writer.path}'{missed}")

    def _answer(self, writer, c, answers):
        """Add a topic the host found; tell the host to record it (with its records) or not."""
        reason = None
        try:
            channel = writer.add_topic(c['topic'], c['type'], c['qos'], channel=c['id'])
            if channel is None:
                reason = writer.failed or 'the bag failed'
        except SchemaError as e:
            reason = str(e)
            self._say('WARNING', f"not recording topic '{c['topic']}': {e}")
        if reason is None:
            self._say('INFO', f"recording topic '{c['topic']}' ({c['type']})")
            answer = frames.encode_ready(c['id'], writer.records_for_host())
        else:
            answer = frames.encode_json(frames.REFUSED, {'id': c['id'], 'reason': reason})
        with contextlib.suppress(BrokenPipeError, OSError):
            answers.write(answer)

    def _play(self, spec, stream):
        schemas = self.install_space.ros2msg_schemas()
        wanted_topics = set(spec['topics']) if spec['topics'] else None
        sent = 0
        announced = {}
        # --start-offset: what comes before it in the bag is skipped, in every round
        skip_ns = round(spec.get('start_offset', 0) * 1e9)
        try:
            loop = 0
            base = None
            span = 0
            while True:
                first = last = seen = None
                round_count = 0
                for path in spec['files']:
                    def on_topic(topic):
                        return self._announce(topic, announced, schemas, wanted_topics, stream,
                                              spec.get('qos_overrides') or {},
                                              spec.get('remaps') or {})
                    try:
                        for topic, log_time, _, data in read_messages(path, on_topic):
                            if base is None:
                                base = log_time
                            seen = log_time
                            if log_time - base < skip_ns:
                                continue
                            if first is None:
                                first = log_time
                            last = log_time
                            offset = log_time - base + loop * span
                            stream.write(frames.encode_played(
                                announced[topic.name][0], log_time, offset, data))
                            sent += 1
                            round_count += 1
                    except BagError as e:
                        self.failed = True
                        self._say('ERROR', f'{e}; played {sent} messages')
                        return
                if last is None and seen is not None and skip_ns:
                    self._say('WARNING', f"--start-offset {spec['start_offset']:g} s is past "
                                         f"the bag's last message ({(seen - base) / 1e9:.3f} s "
                                         'in): nothing played')
                if not spec['loop'] or last is None:
                    break
                if loop == 0:
                    # the next round starts one mean gap after the last message
                    length = last - first
                    span = length + (length // (round_count - 1) if round_count > 1
                                     else 1000000000)
                loop += 1
        except BrokenPipeError:
            return  # the host stopped (Ctrl-C, --duration): nothing more to play
        finally:
            with contextlib.suppress(BrokenPipeError, OSError):
                stream.write(frames.encode_json(frames.END, {'messages': sent}))
                stream.close()

    def _announce(self, topic, announced, schemas, wanted_topics, stream, overrides, remaps):
        """Send a topic's channel to the host, or say why it is skipped."""
        if wanted_topics is not None and topic.name not in wanted_topics:
            return False
        if topic.name in announced:
            # the same topic in a later file of the bag, or again on a loop
            return announced[topic.name][1] == topic.type
        problem = unplayable(topic, schemas)
        if problem:
            self._say('WARNING', f"skipping topic '{topic.name}': {problem}")
            announced[topic.name] = (None, None)
            return False
        channel = len(announced) + 1
        announced[topic.name] = (channel, topic.type)
        qos = overrides.get(topic.name)
        if qos is not None:
            self._say('INFO', f"topic '{topic.name}' plays with the QoS of the override file: "
                              + ', '.join(f'{k} {v:g}' if isinstance(v, float) else f'{k} {v}'
                                          for k, v in qos.items()))
        name = remaps.get(topic.name, topic.name)
        if name != topic.name:
            self._say('INFO', f"topic '{topic.name}' plays on '{name}' (--remap)")
        stream.write(frames.encode_json(frames.CHANNEL, {
            'id': channel, 'topic': name, 'type': schemas.resolve(topic.type),
            'qos': qos or player_qos(topic.qos)}))
        return True


@contextlib.contextmanager
def bag_session(plan, install_space, err):
    """Start a :class:`BagSession` (or None without record and play entries)."""
    if not plan:
        yield None
        return
    session = BagSession(plan, install_space, err)
    session.start()
    try:
        yield session
    finally:
        session.host_started()
