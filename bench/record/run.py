# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Benchmark record and replay (docs/record.md).

    python bench/record/run.py INSTALL_WASM [--seconds S]

INSTALL_WASM: a ``colcon build --wasm`` of demo/src. Three measures:

- replay speed of small messages: a bag of 1 kHz ``Chatter`` messages,
  written by ``rosbags``, played as fast as it goes (``--rate 100000``) while
  the replay is recorded; speed = bag length / time from first to last
  message on the bus;
- record CPU overhead: the talker at 1 kHz and the camera at 30 Hz
  640x480 rgb8 for S seconds, CPU time (user + system of the command and
  its children) with and without ``--record``, in ``--pairs`` interleaved
  pairs (the machine's speed drifts: each pair is compared on its own,
  the median of the pairs is reported with the range), and messages lost;
- a naive writer of that recording, in each pair: the CPU time of a
  process that writes as many bytes as the bag has into a new file, at the
  bag's rate, 4 MiB at a time, for as long, and leaves them in the page
  cache (as rosbag2 does). On this machine (a VM whose balloon takes freed
  memory back) the kernel's cost of that moves tenfold with the state of
  the host's memory: memory handed back is faulted in again as the page
  cache grows (0.2 s of CPU per GB written into pages still there, 2.4 s
  per GB into pages handed back). The recorder lets go of the bag's pages
  behind it (colcon_wasm/record/page_cache.py) and does not pay that.

The commands' output goes to files, read once they ended (a live pipe
would have this script compete with them for the CPU), and every file it
wrote is removed at the end (``--keep`` keeps them: 1.7 GB per minute
recorded).

Prints a Markdown table.
"""

import argparse
from pathlib import Path
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

CHATTER = 'demo_interfaces/msg/Chatter'


def children_times():
    """Return (CPU seconds, of which system) of the ended children so far."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime, usage.ru_stime


def colcon_wasm(*args):
    """Run colcon-wasm; return (exit status, stdout, stderr, CPU s, wall s, system CPU s)."""
    tool = Path(sys.executable).parent / 'colcon-wasm'
    with tempfile.TemporaryFile('w+') as out, tempfile.TemporaryFile('w+') as err:
        cpu, system = children_times()
        started = time.monotonic()
        code = subprocess.run([str(tool), *map(str, args)], stdout=out, stderr=err,
                              timeout=900).returncode
        wall = time.monotonic() - started
        cpu_after, system_after = children_times()
        out.seek(0)
        err.seek(0)
        return code, out.read(), err.read(), cpu_after - cpu, wall, system_after - system


def paced_write(path, size, seconds):
    """CPU seconds of a child process writing `size` bytes into new file `path` in `seconds`."""
    code = (
        'import os, sys, time\n'
        'path, size, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])\n'
        'block = bytes(range(256)) * (4 << 12)\n'
        'fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)\n'
        'start, written = time.monotonic(), 0\n'
        'while written < size:\n'
        '    written += os.write(fd, block[:min(len(block), size - written)])\n'
        '    ahead = start + seconds * written / size - time.monotonic()\n'
        '    if ahead > 0:\n'
        '        time.sleep(ahead)\n'
        'os.close(fd)\n')
    cpu, _ = children_times()
    subprocess.run([sys.executable, '-c', code, str(path), str(size), str(seconds)],
                   check=True, timeout=seconds + 300)
    return children_times()[0] - cpu


def small_bag(path, install, count, period_ns):
    """Write `count` Chatter messages `period_ns` apart with rosbags."""
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import get_typestore, get_types_from_msg, Stores
    typestore = get_typestore(Stores.EMPTY)
    msgdef = (Path(install).parent / 'src' / 'demo_interfaces' / 'msg' / 'Chatter.msg')
    typestore.register(get_types_from_msg(msgdef.read_text(), CHATTER))
    Chatter = typestore.types[CHATTER]
    with Writer(path, version=8, storage_plugin=StoragePlugin.MCAP) as writer:
        c = writer.add_connection('/chatter', CHATTER, typestore=typestore)
        for i in range(count):
            writer.write(c, 1_700_000_000_000_000_000 + i * period_ns, typestore.serialize_cdr(
                Chatter(data=f'Hello World: {i}', count=i), CHATTER))


def times(path, topic):
    """Log times of a topic's messages (mcap)."""
    from mcap.reader import make_reader
    with open(path, 'rb') as f:
        return [m.log_time for _, c, m in make_reader(f).iter_messages(log_time_order=False)
                if c.topic == topic]


def counted(path):
    """(count, log time) of the Chatter messages of a bag (mcap + mcap-ros2-support)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    with open(path, 'rb') as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        return [(d.count, m.log_time) for _, c, m, d in
                reader.iter_decoded_messages(log_time_order=False) if c.topic == '/chatter']


def main():
    """Run the benchmark."""
    parser = argparse.ArgumentParser()
    parser.add_argument('install')
    parser.add_argument('--seconds', type=float, default=20)
    parser.add_argument('--messages', type=int, default=20000)
    parser.add_argument('--pairs', type=int, default=3)
    parser.add_argument('--keep', action='store_true', help='keep the bags written')
    args = parser.parse_args()
    work = Path(tempfile.mkdtemp(prefix='bench-record-'))
    try:
        measure(args, work)
    finally:
        if args.keep:
            print(f'the bags are in {work}')
        else:
            shutil.rmtree(work, ignore_errors=True)


def measure(args, work):
    """Measure, print the table."""
    rows = []

    bag = work / 'small'
    small_bag(bag, args.install, args.messages, 1_000_000)
    length = (args.messages - 1) / 1000
    for rate in ('20', '100000'):
        replay = work / f'replay{rate}.mcap'
        code, out, err, cpu, wall, _ = colcon_wasm(
            'play', '--install-base', args.install, '--record', replay, '--rate', rate, bag)
        assert code == 0, out + err
        # the speed between the first and the last message the recorder kept (their
        # counts say how much bag time lies between them)
        seen = counted(replay)
        (first, t0), (last, t1) = seen[0], seen[-1]
        span = (t1 - t0) / 1e9
        played = re.search(r'played (\d+) messages', out + err)
        count = played.group(1) if played else '?'
        rows.append((
            f'replay, {args.messages} small messages (a 1 kHz bag of {length:.0f} s), '
            f'--rate {rate}',
            f'{(last - first) / 1000 / span:.0f}x real time ({count} published in {span:.2f} s; '
            f'{wall:.1f} s for the command; the recorder kept {len(seen)})',
            '>= 20x'))

    launch = work / 'load.launch.yaml'
    launch.write_text(
        'launch:\n'
        '- node: {pkg: demo_nodes, exec: talker, param: [{name: rate, value: 1000.0}]}\n'
        '- node:\n    pkg: demo_nodes\n    exec: camera\n    param:\n'
        '    - {name: rate, value: 30.0}\n    - {name: width, value: 640.0}\n'
        '    - {name: height, value: 480.0}\n')
    pairs = []
    for i in range(args.pairs):
        code, out, err, base_cpu, _, base_system = colcon_wasm(
            'launch', '--install-base', args.install, '--duration', args.seconds, launch)
        assert code == 0, out + err
        recorded = work / f'load{i}.mcap'
        code, out, err, rec_cpu, _, rec_system = colcon_wasm(
            'launch', '--install-base', args.install, '--duration', args.seconds, '--record',
            recorded, launch)
        assert code == 0, out + err
        chatter = times(recorded, '/chatter')
        frames = times(recorded, '/camera/image')
        published = len([1 for line in out.splitlines() if 'Publishing:' in line])
        said = re.search(r'(\d+) lost before the recorder took them', err)
        lost = int(said.group(1)) if said else 0
        overhead = (rec_cpu - base_cpu) / args.seconds * 100
        kernel = (rec_system - base_system) / args.seconds * 100
        # the naive writer: the bag's bytes written at its rate into a new file; the bag is
        # kept meanwhile, so that both draw on memory in the same state
        floor_file = work / f'floor{i}.bin'
        floor = paced_write(floor_file, recorded.stat().st_size, args.seconds) / args.seconds * 100
        floor_file.unlink()
        pairs.append((overhead, base_cpu, rec_cpu, len(chatter), published, len(frames), lost,
                      floor, kernel))
        if not args.keep:
            recorded.unlink()
    overhead = statistics.median(p[0] for p in pairs)
    # the other figures of the pair nearest the median
    _, base_cpu, rec_cpu, chatter, published, frames, lost, _, _ = min(
        pairs, key=lambda p: abs(p[0] - overhead))
    spread = ', '.join(f'{p[0]:+.1f}' for p in sorted(pairs))
    losses = ', '.join(str(p[6]) for p in pairs)
    floors = ', '.join(f'{p[7]:.1f}' for p in pairs)
    kernels = ', '.join(f'{p[8]:+.1f}' for p in pairs)
    rows.append((f'record 1 kHz talker + 30 Hz 640x480 rgb8 for {args.seconds:.0f} s '
                 f'(median of {len(pairs)} interleaved pairs)',
                 f'{overhead:+.1f} % of one core ({base_cpu:.1f} s CPU without, {rec_cpu:.1f} s '
                 f'with --record; the pairs: {spread} %); {chatter} chatter messages recorded '
                 f'of {published} logged, {frames} frames ({frames / args.seconds:.1f} Hz); '
                 f'lost before the recorder took them, per pair: {losses}',
                 'no loss, <= 5 % CPU'))
    rows.append(('of which the kernel (system time), and a naive writer of the same bytes',
                 f"kernel, per pair: {kernels} % of one core; a process writing the bag's bytes "
                 f'at its rate into a new file, keeping its pages: {floors} % (the pairs in the '
                 'order of the losses)',
                 ''))
    print('| measure | result | goal |')
    print('|---|---|---|')
    for r in rows:
        print(f'| {r[0]} | {r[1]} | {r[2]} |')


if __name__ == '__main__':
    main()
