# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Run one Python fuzz target (tests/fuzz/py_targets.py) under atheris, coverage-guided.

    python tests/fuzz/py_fuzz.py relay --runs 2000 --seed 1
    python tests/fuzz/py_fuzz.py mcap --seconds 60
    python tests/fuzz/py_fuzz.py relay --capture        # (re)write the seed corpus

libFuzzer (inside atheris) mutates the seed corpus (copied, so the
committed one stays as it is), follows the coverage of the instrumented
colcon_wasm modules, and bounds each input's time (``--timeout``). An
exception out of ``one()``, or a failed ``check()`` (run every
``--check-every`` inputs on the same instance), is a finding: the input
goes to ``--findings`` with its traceback (once per kind of failure) and
the run goes on; a hang (past ``--timeout``) stops it. The last line printed is JSON: ``{target,
seed, inputs, seconds, coverage: {unit, edges, features}, findings:
[{kind, message, file}]}``; the exit status is 0 without findings.
"""

import argparse
import hashlib
import json
import os
from pathlib import Path
import re
import shutil
import subprocess
import sys
import tempfile
import time
import traceback

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import py_targets  # noqa: E402

# the modules each target's coverage follows (atheris instruments them at import)
MODULES = {
    'relay': ('colcon_wasm.server.relay', 'colcon_wasm.server.relay_forms',
              'colcon_wasm.server.relay_topics', 'colcon_wasm.server.relay_rosapi',
              'colcon_wasm.server.relay_parameters'),
    'mcap': ('colcon_wasm.record.bag_reader', 'colcon_wasm.record.paced_player',
             'colcon_wasm.record.qos', 'colcon_wasm.record.bag_info', 'mcap.stream_reader',
             'mcap.records'),
    'launch_xml': ('colcon_wasm.launch.loader', 'colcon_wasm.launch.frontends',
                   'colcon_wasm.launch.substitutions', 'colcon_wasm.launch.launch_plan',
                   'colcon_wasm.launch.composable'),
    'launch_yaml': ('colcon_wasm.launch.loader', 'colcon_wasm.launch.frontends',
                    'colcon_wasm.launch.substitutions', 'colcon_wasm.launch.launch_plan',
                    'colcon_wasm.launch.composable'),
    'params': ('colcon_wasm.launch.loader', 'colcon_wasm.record.qos'),
}


def _fuzz(args):
    """Run inside the atheris process: instrument, then hand over to libFuzzer."""
    import atheris
    with atheris.instrument_imports(include=['colcon_wasm', 'mcap']):
        import importlib
        for module in MODULES[args.target]:
            importlib.import_module(module)
    target = py_targets.make(args.target)
    target.check()
    count = [0]

    seen = set()

    def record(kind, data):
        # one file per kind of failure (its type and where it was raised), and go on
        error = traceback.format_exc()
        frames = [f for f in traceback.extract_tb(sys.exc_info()[2])
                  if 'colcon_wasm' in f.filename]
        where = f'{frames[-1].filename}:{frames[-1].lineno}' if frames else ''
        signature = f'{kind} {sys.exc_info()[0].__name__} {where}'
        if signature in seen:
            return
        seen.add(signature)
        name = f'{kind}-{hashlib.sha1(data).hexdigest()[:12]}'
        Path(args.findings, name).write_bytes(data)
        Path(args.findings, f'{name}.txt').write_text(f'{signature}\n{error}', encoding='utf-8')

    def one(data):
        count[0] += 1
        try:
            target.one(data)
        except Exception:  # noqa: B902 (anything out of the handler is a finding)
            record('exception', data)
        if count[0] % args.check_every == 0:
            try:
                target.check()
            except Exception:  # noqa: B902
                record('state', data)
    corpus = Path(args.work) / 'corpus'
    argv = [sys.argv[0], str(corpus), str(py_targets.corpus_dir(args.target)),
            f'-seed={args.seed}', f'-timeout={args.timeout}', '-rss_limit_mb=4096',
            f'-artifact_prefix={args.findings}/', '-print_final_stats=1', '-max_len=65536']
    if args.runs is not None:
        argv.append(f'-runs={args.runs}')
    if args.seconds is not None:
        argv.append(f'-max_total_time={args.seconds}')
    atheris.Setup(argv, one)
    atheris.Fuzz()


def _summary(target, seed, stderr, seconds, findings_dir, returncode):
    """Read libFuzzer's report into the JSON line."""
    runs = re.findall(r'stat::number_of_executed_units:\s*(\d+)', stderr)
    inputs = int(runs[-1]) if runs else 0
    cov = re.findall(r'#\d+\s+\w+\s+cov: (\d+) ft: (\d+)', stderr)
    coverage = {'unit': 'atheris edges', 'edges': int(cov[-1][0]), 'features': int(cov[-1][1])} \
        if cov else None
    findings = []
    for path in sorted(Path(findings_dir).glob('*')):
        if path.suffix == '.txt':
            continue
        kind = path.name.split('-')[0]
        text = path.with_name(f'{path.name}.txt')
        message = text.read_text(encoding='utf-8') if text.is_file() else stderr[-3000:]
        findings.append({'kind': {'crash': 'exception', 'timeout': 'hang', 'oom': 'memory',
                                  'slow': 'slow'}.get(kind, kind), 'file': str(path),
                         'message': message[-3000:]})
    if not findings and returncode not in (0, None):
        findings.append({'kind': 'exception', 'file': None, 'message': stderr[-3000:]})
    return {'target': target, 'seed': seed, 'inputs': inputs, 'seconds': seconds,
            'coverage': coverage, 'findings': findings}


def main():
    """Parse the options; run the target in a child process (atheris exits when done)."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('target', choices=sorted(py_targets.TARGETS))
    parser.add_argument('--seed', type=int, default=1)
    parser.add_argument('--runs', type=int)
    parser.add_argument('--seconds', type=int)
    parser.add_argument('--timeout', type=int, default=10, help='seconds one input may take')
    parser.add_argument('--check-every', type=int, default=200)
    parser.add_argument('--findings')
    parser.add_argument('--capture', action='store_true')
    parser.add_argument('--child', action='store_true', help=argparse.SUPPRESS)
    parser.add_argument('--work', help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.capture:
        print(json.dumps({'target': args.target, 'captured': py_targets.capture(args.target)}))
        return 0
    if args.child:
        _fuzz(args)
        return 0
    if args.runs is None and args.seconds is None:
        args.runs = 1000
    work = tempfile.mkdtemp(prefix=f'fuzz-{args.target}-')
    findings = Path(args.findings or Path(work) / 'findings')
    findings.mkdir(parents=True, exist_ok=True)
    (Path(work) / 'corpus').mkdir()
    command = [sys.executable, str(Path(__file__).resolve()), args.target, '--child',
               '--work', work, '--findings', str(findings), '--seed', str(args.seed),
               '--timeout', str(args.timeout), '--check-every', str(args.check_every)]
    if args.runs is not None:
        command += ['--runs', str(args.runs)]
    if args.seconds is not None:
        command += ['--seconds', str(args.seconds)]
    started = time.monotonic()
    limit = (args.seconds or 0) + 60 + (args.runs or 0) * args.timeout
    try:
        completed = subprocess.run(command, capture_output=True, text=True, timeout=limit,
                                   env=dict(os.environ, PYTHONHASHSEED='0'))
        stderr, returncode = completed.stderr, completed.returncode
    except subprocess.TimeoutExpired as e:
        stderr, returncode = (e.stderr or b'').decode('utf-8', 'replace'), -1
    result = _summary(args.target, args.seed, stderr, round(time.monotonic() - started, 3),
                      findings, returncode)
    shutil.rmtree(Path(work) / 'corpus', ignore_errors=True)
    print(json.dumps(result))
    return 1 if result['findings'] else 0


if __name__ == '__main__':
    sys.exit(main())
