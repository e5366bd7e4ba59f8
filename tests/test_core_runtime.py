# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Test the wasm_js runtime around the nodes.

The non-isolated page message, the Node.js runner (cli.mjs) and executables
run alone (private bus).
"""

import os
from pathlib import Path
import shutil
import subprocess
import time

from core import harness
import pytest


def _cli(*args, env=None, timeout=120):
    core = harness.get_build()
    full = dict(os.environ, **(env or {}))
    return subprocess.run(
        ['node', str(core.src / 'cli.mjs')] + [str(a) for a in args],
        capture_output=True, text=True, timeout=timeout, env=full)


def test_page_without_isolation_says_which_headers_to_serve():
    reason = harness.browser_skip_reason()
    if reason:
        pytest.skip(reason)
    page = harness.get_browser().evaluate('/plain/page.html')
    assert page['isolated'] is False
    status = page['status']
    assert status.startswith('IsolationError: '), status
    assert 'Cross-Origin-Opener-Policy: same-origin' in status
    assert 'Cross-Origin-Embedder-Policy: require-corp' in status


def test_node_runner_starts_executables_on_one_bus():
    exe = harness.get_build().core_node
    done = _cli('--timeout', '60', '--name', 'listener', exe, 'sub',
                '--count', '50', '--qos', 'keep_all', '---', '--name',
                'talker', exe, 'pub', '--count', '50', '--qos', 'keep_all')
    assert done.returncode == 0, done.stdout + done.stderr
    lines = done.stdout.splitlines()
    assert '[talker] RESULT matched=1' in lines, done.stdout
    assert any(line.startswith('[listener] RESULT received=50 bad=0 '
                               'out_of_order=0') for line in lines), done.stdout


def test_node_runner_reports_a_failing_executable():
    exe = harness.get_build().core_node
    done = _cli('--name', 'lonely', exe, 'pub', '--match-timeout-ms', '300')
    assert done.returncode == 4, done.stdout + done.stderr
    assert '[lonely] ERROR only 0 of 1 subscriptions matched' in done.stdout
    assert '[lonely] exited with code 4' in done.stderr


def test_node_runner_usage_errors():
    done = _cli()
    assert done.returncode == 2
    assert 'no executable given' in done.stderr and 'usage:' in done.stderr
    done = _cli('--timeout', 'soon', 'x.js')
    assert done.returncode == 2
    assert '--timeout needs a non-negative number, got "soon"' in done.stderr
    done = _cli('missing.js')
    assert done.returncode == 1
    assert 'missing' in (done.stdout + done.stderr)


def test_executable_alone_creates_a_private_bus():
    # `node exe.js` without the runtime: the JS library finds wasm_js next
    # to the install space and creates a bus for this one process.
    exe = harness.get_build().core_node
    env = {k: v for k, v in os.environ.items()
           if k not in ('WASM_JS_DIR', 'AMENT_PREFIX_PATH', 'CMAKE_PREFIX_PATH',
                        'COLCON_PREFIX_PATH')}
    done = subprocess.run(['node', str(exe), 'errors'], capture_output=True,
                          text=True, timeout=120, env=env)
    assert done.returncode == 0, done.stdout + done.stderr
    assert 'RESULT after_errors_ok=1 max_ok=1' in done.stdout


def test_executable_alone_without_wasm_js_gets_a_clear_error(tmp_path):
    core = harness.get_build()
    for suffix in ('.js', '.wasm', '.worker.js'):
        shutil.copy(core.bin / f'core_node{suffix}', tmp_path)
    env = {k: v for k, v in os.environ.items()
           if k not in ('WASM_JS_DIR', 'AMENT_PREFIX_PATH', 'CMAKE_PREFIX_PATH',
                        'COLCON_PREFIX_PATH')}
    done = subprocess.run(['node', str(tmp_path / 'core_node.js'), 'errors'],
                          capture_output=True, text=True, timeout=120,
                          env=env, cwd=tmp_path)
    assert done.returncode == 3, done.stdout + done.stderr
    assert 'ERROR context: wasm_cpp: no bus is attached' in done.stdout
    assert 'WASM_JS_DIR' in done.stdout
    # With WASM_JS_DIR it works from anywhere.
    env['WASM_JS_DIR'] = str(core.share)
    done = subprocess.run(['node', str(tmp_path / 'core_node.js'), 'errors'],
                          capture_output=True, text=True, timeout=120,
                          env=env, cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    assert Path(tmp_path / 'core_node.js').is_file()


def test_log_severity_is_read_through_ansi_colours():
    # rcutils colours console lines because isatty() is true under Emscripten
    runtime = Path(__file__).resolve().parent.parent / 'packages' / \
        'wasm_js' / 'src' / 'runtime.mjs'
    script = (
        'import("' + runtime.as_uri() + '").then((m) => {'
        ' for (const line of ["\\x1b[33m[WARN] [1.5] [n]: careful\\x1b[0m",'
        ' "\\x1b[0m[INFO] [1.5] [n]: hello\\x1b[0m", "plain"]) {'
        ' const text = m.stripAnsi(line);'
        ' console.log(JSON.stringify([text, m.severityOf("stderr", text)]));'
        ' } });')
    done = subprocess.run(['node', '--input-type=module', '-e', script],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        '["[WARN] [1.5] [n]: careful","WARN"]',
        '["[INFO] [1.5] [n]: hello","INFO"]',
        '["plain","ERROR"]',
    ]


def _lines(run, name):
    """Get the log lines of process `name` without their severity."""
    assert run['ok'], harness.explain(run)
    return [line.split(' ', 1)[1]
            for line in run['processes'][name]['lines']]


@pytest.mark.parametrize('platform', ['node', 'chromium'])
def test_stdin_files_and_ros_namespace_reach_the_executable(platform):
    run = harness.run(platform, 'io')
    why = harness.explain(run)
    io = _lines(run, 'io')
    assert 'STDIN 2|3|q|' in io, why
    assert 'FILE talker:|  ros__parameters:|    greeting: hi|' in io, why
    # ROS_NAMESPACE becomes a namespace remap (a leading '/' added) ...
    assert io[-5:-2] == ['ARG 2 --ros-args', 'ARG 3 -r',
                         'ARG 4 __ns:=/robot1'], why
    ns = _lines(run, 'io_ns')
    assert 'ARG 4 __ns:=/robot2' in ns, why
    # ... unless the arguments remap __ns themselves; no stdin: end of file
    own = _lines(run, 'io_own_ns')
    assert [line for line in own if '__ns:=' in line] == [
        'ARG 4 __ns:=/mine'], why
    assert 'STDIN ' in own, why
    for name in ('io', 'io_ns', 'io_own_ns'):
        assert harness.exit_of(run, name)['code'] == 0, why


@pytest.mark.parametrize('platform', ['node', 'chromium'])
def test_open_stdin_is_read_line_by_line_like_a_terminal(platform):
    """spawn(stdin: true): writeStdin() lines arrive while the node runs."""
    run = harness.run(platform, 'stdin_pipe')
    why = harness.explain(run)
    extra = run['extra']
    # the first line was read before the pipe was closed (not at exit)
    assert extra['before_close'] is True, why
    # the default build has threads: one printed while main() was in read()
    assert extra['threads'] is True, why
    assert 'THREAD 2' in _lines(run, 'lines'), why
    # 3000 lines (twice the pipe) + 'last': all, in order, then end of file
    assert extra['line_count'] == 3003, why
    assert extra['in_order'] is True, why
    assert extra['tail'] == ['LINE 3002 last', 'EOF 3002'], why
    assert harness.exit_of(run, 'lines')['code'] == 0, why
    assert 'has ended' in extra['late_write'] or 'closed' in extra['late_write'], why


def test_colcon_wasm_run_gives_the_node_its_standard_input():
    """`colcon-wasm run` forwards its stdin line by line, as `ros2 run` does."""
    import select
    import sys
    core = harness.get_build()
    command = [str(Path(sys.executable).parent / 'colcon-wasm'), 'run',
               '--install-base', str(core.workspace / 'install_wasm'),
               'core_test_nodes', 'core_node', 'lines']
    process = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True, bufsize=1)
    seen = []

    def read_until(text, seconds=60):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            ready, _, _ = select.select([process.stdout], [], [], 0.5)
            if ready:
                line = process.stdout.readline()
                if not line:
                    break
                seen.append(line.rstrip('\n'))
                if text in line:
                    return
        raise AssertionError(f'no {text!r} from colcon-wasm run:\n' + '\n'.join(seen))

    try:
        read_until('READY')
        process.stdin.write('typed while it runs\n')
        process.stdin.flush()
        # the line arrives while stdin is still open: the node reads like a terminal's
        read_until('LINE 1 typed while it runs')
        process.stdin.write('second\n')
        process.stdin.close()  # end of file
        read_until('EOF 2')
        assert process.wait(timeout=60) == 0, '\n'.join(seen)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait()
    assert '[core_node-1] LINE 2 second' in seen


@pytest.mark.parametrize('platform', ['node', 'chromium'])
def test_warm_host_boots_the_pthread_pool_ahead(platform):
    """A pthread program on a warm worker gets its pool workers booted ahead."""
    run = harness.run(platform, 'prestarted_pthreads')
    why = harness.explain(run)
    extra = run['extra']
    for name in ('ready', 'settled', 'warming', 'none'):
        # the program's thread ran and woke main() through the bus
        assert harness.results(run, name)['guard_ready'] == '1', why
        assert harness.exit_of(run, name)['code'] == 0, why
    # the toolchain's default pool is 4 workers; all came from the warm worker,
    # also when spawn() took the host before it had finished warming up
    assert extra['ready_prestarted'] == 4, why
    # 'settled' first waited 300 ms on the bus: that was its settling (its
    # host thread is blocked until the program exits, so only the wait can
    # have told), and the pool then loaded the program before its thread
    # started; the NodeProcess says when, after the glue was loaded
    assert extra['settled_prestarted'] == 4, why
    assert extra['settled_settled_ms'] is not None, why
    assert extra['settled_started_ms'] <= extra['settled_settled_ms'], why
    assert extra['warming_prestarted'] == 4, why
    # warmPthreadWorkers: 0 -> Emscripten booted its own
    assert extra['none_prestarted'] == 0, why
    # in a browser the host (and the pthread workers) loaded the glue from
    # the script the Runtime prefetched; Node.js hosts read the file
    for name in ('ready', 'settled', 'warming', 'none'):
        assert extra[f'{name}_glue_from_memory'] is (platform == 'chromium'), why
    assert 'thread line 49' in _lines(run, 'ready'), why


def test_page_whose_policy_refuses_eval_loads_the_scripts_by_url():
    """
    Load the scripts by URL where the page's policy refuses eval.

    A Content-Security-Policy without 'unsafe-eval' refuses the indirect eval
    that runs the prefetched glue: the host and the pthread workers load the
    glue and Emscripten's worker script by URL instead, and work the same.
    """
    reason = harness.browser_skip_reason()
    if reason:
        pytest.skip(reason)
    run = harness.get_browser().run('prestarted_pthreads',
                                    wasm_js='/no-eval/wasm_js/')
    why = harness.explain(run)
    extra = run['extra']
    for name in ('ready', 'settled', 'warming', 'none'):
        # the thread ran in a worker that loaded the program by URL
        assert harness.results(run, name)['guard_ready'] == '1', why
        assert harness.exit_of(run, name)['code'] == 0, why
        assert extra[f'{name}_glue_from_memory'] is False, why
    assert extra['ready_prestarted'] == 4, why
    assert 'thread line 49' in _lines(run, 'ready'), why
