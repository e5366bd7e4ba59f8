# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
colcon-wasm run/launch on Node.js with the demo built by real Emscripten.

XML and YAML launch files, --duration, the exit status when a node crashes,
--echo: each through the real `colcon-wasm` command.
"""

import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import time

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100
import pytest  # noqa: E402, I100, I202


@pytest.fixture(scope='module')
def install():
    """Build the demo workspace (once per test run)."""
    return demo_build.demo_install()


def colcon_wasm(*args, timeout=120):
    """Run the colcon-wasm command; return (exit status, stdout, stderr, seconds)."""
    started = time.monotonic()
    result = subprocess.run([str(demo_build.venv_tool('colcon-wasm')), *map(str, args)],
                            capture_output=True, text=True, timeout=timeout)
    return result.returncode, result.stdout, result.stderr, time.monotonic() - started


def test_items_share_one_bus_and_output_is_prefixed(install):
    code, out, err, seconds = colcon_wasm(
        'launch', '--install-base', install, '--duration', '3',
        'demo_nodes/talker', 'demo_nodes/listener')
    assert code == 0, out + err
    assert '[INFO] [talker-1]: process started' in out
    assert '[INFO] [listener-2]: process started' in out
    assert re.search(r'^\[talker-1\] \[INFO\] \[[\d.]+\] \[talker\]: '
                     r"Publishing: 'Hello World: 2'$", out, re.MULTILINE), out
    assert re.search(r'^\[listener-2\] \[INFO\] \[[\d.]+\] \[listener\]: I heard: '
                     r'\[Hello World: \d+\]$', out, re.MULTILINE), out
    assert '[INFO] [launch]: stopping every process after 3 s (--duration)' in out
    assert '[INFO] [talker-1]: process stopped' in out
    assert 3 <= seconds < 20


def test_xml_launch_file_with_arguments(install):
    code, out, err, _ = colcon_wasm(
        'launch', '--install-base', install, '--duration', '3',
        'demo_nodes', 'talker_listener.launch.xml', 'topic:=news')
    assert code == 0, out + err
    # the launch file sets rate:=2 and remaps chatter to the argument
    assert len(re.findall(r'\[talker-1\] .*Publishing:', out)) >= 4, out
    assert re.search(r'\[listener-2\] .*I heard: \[Hello World: \d+\]', out), out


def test_yaml_launch_file_with_namespace_group_and_parameters(install):
    launch = Path(install).parent / 'src' / 'demo_nodes' / 'launch' / 'demo.launch.yaml'
    code, out, err, _ = colcon_wasm('launch', '--install-base', install, '--duration', '4',
                                    launch, 'ns:=robot1')
    assert code == 0, out + err
    assert 'Publishing a 1.00 Hz wave on /robot1/wave' in out, out
    assert 'Ready to add two ints on /robot1/add_two_ints' in out, out
    assert re.search(r'\[add_two_ints_client-4\] .*Result of add_two_ints: for 1 \+ 2 = 3',
                     out), out
    assert re.search(r'\[listener-2\] .*I heard: \[Hello World: \d+\]', out), out


def test_a_crash_makes_the_exit_status_non_zero(install):
    code, out, err, _ = colcon_wasm(
        'launch', '--install-base', install, '--duration', '4',
        'demo_nodes/talker', 'demo_nodes/crasher')
    assert code == 1, out + err
    assert re.search(r'^\[ERROR\] \[crasher-2\]: process has died \[exit code 1, .*crasher\.js',
                     err, re.MULTILINE), err
    # the crasher dies after 2 s; the talker (1 Hz) goes on until --duration stops it
    assert '[talker-1] [INFO]' in out and "Publishing: 'Hello World: 4'" in out, out


def test_run_with_arguments_and_echo(install):
    code, out, err, _ = colcon_wasm(
        'run', '--install-base', install, '--duration', '2.5', '--echo', '/wave',
        'demo_nodes', 'oscillator', '--ros-args', '-p', 'rate:=4', '-p', 'frequency:=1')
    assert code == 0, out + err
    samples = re.findall(r'^\[echo /wave\]\ntime: ([\d.]+)\nsine: (\S+)\ncosine: (\S+)\n'
                         r'step: (\d+)\n---$', out, re.MULTILINE)
    assert len(samples) >= 5, out
    for t, sine, cosine, _ in samples:
        assert abs(float(sine) ** 2 + float(cosine) ** 2 - 1) < 1e-9


def test_a_missing_executable_is_a_clear_error(install):
    code, out, err, _ = colcon_wasm('run', '--install-base', install, 'demo_nodes', 'nope')
    assert code == 1 and out == ''
    assert err.startswith("colcon-wasm run: package 'demo_nodes' has no executable 'nope' "
                          '(it has: '), err
    for name in ('talker', 'listener', 'add_two_ints_server', 'oscillator', 'crasher'):
        assert name in err


def test_sigterm_to_the_command_stops_the_nodes(install):
    # a supervisor (systemd, a test harness, `kill PID`) signals colcon-wasm alone, not its
    # process group: the Node host must not be left running the nodes
    process = subprocess.Popen(
        [str(demo_build.venv_tool('colcon-wasm')), 'launch', '--install-base', str(install),
         'demo_nodes/talker'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
        start_new_session=True)
    try:
        for line in process.stdout:
            if "Publishing: 'Hello World: 1'" in line:
                break
        process.send_signal(signal.SIGTERM)
        # the pipe ends only when the host, which holds it too, has ended
        rest, _ = process.communicate(timeout=30)
        assert process.returncode == 0, rest
    finally:
        try:  # the command's process group: the host too, should it have outlived the command
            os.killpg(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
    assert '[INFO] [launch]: terminated (SIGTERM)' in rest, rest
    assert '[INFO] [talker-1]: process stopped' in rest, rest
