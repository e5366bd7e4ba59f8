# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The README, followed as a new user would, on a fresh copy of the repository.

A wheel of colcon-wasm goes into a fresh virtual environment with its
dependencies from the package index and without the test extras (a green
test venv once hid a missing dependency). `scripts/demo.sh --build-only`
then builds the demo on a fresh copy of the repository with that venv, and
every command of the README that needs no ROS source runs there with only
that venv on PATH: what the README promises must work with what `pip
install colcon-wasm` brings.
"""

import json
import os
from pathlib import Path
import re
import shutil
import socket
import subprocess
import sys
import time
import urllib.request

from colcon_helpers import REPO
import pytest

"""README commands this test runs (a README line starting with one of
these prefixes must be listed here, or in NOT_RUN with the reason)."""
RUN = (
    'scripts/demo.sh',
    'pip install /path/to/colcon-wasm',
    'colcon-wasm doctor',
    'colcon build --wasm',
    'colcon list --wasm',
    'colcon build',
    'node install_wasm/<pkg>/lib/<pkg>/<exe>.js ARGS',
    'colcon-wasm serve',
    'colcon-wasm run demo_nodes talker --ros-args -p rate:=2',
    'colcon-wasm launch demo_nodes/talker demo_nodes/listener --duration 5',
    'colcon-wasm launch my_pkg bringup.launch.xml robot:=r2 --echo /chatter',
    'colcon test --wasm',
    'colcon test-result',
)

"""README commands not run here, and why."""
NOT_RUN = {
    'sudo apt-get install': 'system packages: .ci/run installs them',
    'python3 -m venv': 'done by this test (the fresh venv)',
    'vcs import': 'needs the network: tests/test_humble*.py build the snapshot',
    'colcon build --wasm --packages-up-to': 'Humble packages: tests/test_humble*.py',
    'bash .ci/run': 'this is what runs the tests',
    'scripts/test.sh': 'this is what runs the tests',
    'source ': 'underlays: tests/test_colcon_underlay.py',
    'colcon build --wasm --wasm-underlay': 'underlays: tests/test_colcon_underlay.py',
    'colcon test --wasm --packages-select': 'Humble tests: tests/test_colcon_test.py',
    'colcon-wasm launch my_pkg robot.launch.xml --rosbridge':
        'rosbridge server on Humble nodes: tests/test_rosbridge_server.py',
    'colcon-wasm launch demo_nodes/talker --rosbridge-connect':
        'needs a rosbridge server: tests/test_rosbridge_client.py',
    'colcon-wasm launch my_pkg robot.launch.xml --foxglove':
        'Foxglove server: tests/test_foxglove_server.py (demo), tests/test_foxglove_rclcpp.py',
    'colcon-wasm launch my_pkg robot.launch.xml --record':
        'recording: tests/test_record.py (the demo talker and camera)',
    'colcon-wasm run demo_nodes talker --record':
        'recording a topic: tests/test_record.py (run --record --record-topic)',
    'colcon-wasm play ': 'replay into nodes: tests/test_record.py (bags written by rosbags)',
    'colcon-wasm launch my_pkg robot.launch.xml --play':
        'launch --play --clock: tests/test_record.py',
    'colcon-wasm serve --foxglove':
        'a Foxglove server on the served pages: tests/test_foxglove_serve.py',
    'colcon-wasm launch my_robot_description display.launch.py':
        "Python launch files need Humble's launch and launch_ros: tests/test_python_launch.py",
    'colcon-wasm bag-info ':
        'what a bag holds: tests/test_record.py (a recording, a rosbags bag, a cut file)',
    'colcon-wasm record ':
        'recording a rosbridge server (serve --rosbridge): tests/test_record_remote.py',
    'colcon-wasm launch demo_nodes/talker --zenoh':
        'needs a Zenoh router (eclipse-zenoh, a test extra): tests/test_zenoh_gateway.py',
}

COMMAND_PREFIXES = ('colcon', 'colcon-wasm', 'blasm', 'scripts/', 'node ', 'pip ',
                    'bash ', 'sudo ', 'python3 ', 'vcs ', 'source ')

_COPY_IGNORE = shutil.ignore_patterns(
    '.git', '.venv', 'build', 'install', 'log', 'build_wasm', 'install_wasm',
    '*.egg-info', '__pycache__', 'node_modules', 'artifacts', '.pytest_cache')


def readme_commands():
    """Get the command lines of the README's indented code blocks."""
    commands = []
    for line in (REPO / 'README.md').read_text(encoding='utf-8').splitlines():
        if not line.startswith('    '):
            continue
        text = line.strip().split('  #')[0].strip()
        if text.startswith(COMMAND_PREFIXES):
            commands.append(text)
    return commands


def test_every_readme_command_is_run_or_excused():
    commands = readme_commands()
    assert commands, 'no commands found in README.md'
    unknown = [c for c in commands
               if not any(c.startswith(p) for p in RUN + tuple(NOT_RUN))]
    assert not unknown, (
        'README commands that tests/test_install_fresh.py neither runs nor '
        f'excuses: {unknown}')


@pytest.fixture(scope='module')
def fresh(tmp_path_factory):
    """Copy the repository, build its wheel, install it into a fresh venv."""
    root = tmp_path_factory.mktemp('fresh')
    clone = root / 'colcon-wasm'
    shutil.copytree(REPO, clone, ignore=_COPY_IGNORE)
    dist = root / 'dist'
    subprocess.run(
        [sys.executable, '-m', 'pip', 'wheel', '--no-deps', '--no-build-isolation',
         '-w', str(dist), str(clone)], check=True, capture_output=True, text=True)
    wheel = next(dist.glob('colcon_wasm-*.whl'))
    venv = root / 'venv'
    subprocess.run([sys.executable, '-m', 'venv', str(venv)], check=True)
    # dependencies from the package index, as `pip install colcon-wasm` gets them
    completed = subprocess.run(
        [str(venv / 'bin' / 'pip'), 'install', '-q', str(wheel)],
        capture_output=True, text=True, timeout=900)
    assert completed.returncode == 0, completed.stdout[-3000:] + completed.stderr[-3000:]
    env = {
        'PATH': f"{venv / 'bin'}:/usr/local/bin:/usr/bin:/bin",
        'HOME': str(root / 'home'), 'COLCON_HOME': str(root / 'colcon_home'),
        'LANG': 'C.UTF-8', 'COLCON_WASM_VENV': str(venv),
    }
    for name in ('EMSDK', 'EM_CONFIG', 'EM_CACHE', 'NODE_PATH', 'TMPDIR', 'CI'):
        if name in os.environ:
            env[name] = os.environ[name]
    (root / 'home').mkdir()
    return {'root': root, 'clone': clone, 'venv': venv, 'env': env}


def run(fresh, *command, cwd=None, timeout=900, check=True, env=None):
    """Run a command with only the fresh venv on PATH."""
    completed = subprocess.run(
        [str(c) for c in command], cwd=str(cwd or fresh['clone']),
        env=dict(fresh['env'], **(env or {})), capture_output=True, text=True,
        timeout=timeout)
    if check:
        assert completed.returncode == 0, (
            f'{command} failed ({completed.returncode}):\n'
            + completed.stdout[-6000:] + '\n' + completed.stderr[-4000:])
    return completed


def test_fresh_venv_has_no_test_extras(fresh):
    # (pytest itself comes with colcon-core, for `colcon test`)
    for module in ('flake8', 'pytest_timeout'):
        completed = run(fresh, 'python', '-c', f'import {module}', check=False)
        assert completed.returncode != 0, f'{module} (a test extra) is in the fresh venv'


def test_installed_colcon_has_what_ros_users_expect(fresh):
    verbs = run(fresh, 'colcon', '--help').stdout
    for verb in ('build', 'list', 'info', 'test', 'test-result', 'mixin', 'graph'):
        assert re.search(rf'^\s+{verb}\s', verbs, re.M), (verb, verbs)
    build_help = run(fresh, 'colcon', 'build', '--help').stdout
    for option in ('--parallel-workers', '--event-handlers', '--mixin', '--wasm'):
        assert option in build_help, option
    # the parallel executor is the default, as with colcon-common-extensions
    assert re.search(r'--executor \{[^}]*parallel', build_help), build_help[:2000]
    assert re.search(r'\(default:\s+parallel\)', build_help), build_help[:2000]


@pytest.fixture(scope='module')
def demo(fresh):
    """Run `scripts/demo.sh --build-only` on the fresh copy with the fresh venv."""
    completed = run(fresh, 'bash', 'scripts/demo.sh', '--build-only', timeout=1800)
    assert 'Built:' in completed.stdout, completed.stdout[-3000:]
    workspace = fresh['clone'] / 'demo'
    assert (workspace / 'install_wasm' / 'demo_nodes' / 'share' / 'demo_nodes' /
            'colcon_wasm' / 'manifest.json').is_file()
    return workspace


def test_demo_build_was_parallel_with_console_cohesion(demo, fresh):
    log = (demo / 'log' / 'latest_build' / 'logger_all.log').read_text()
    assert 'parallel' in log and "'console_cohesion+'" in log, log[:3000]


def test_doctor(fresh):
    completed = run(fresh, 'colcon-wasm', 'doctor', check=False)
    assert 'emscripten' in completed.stdout.lower(), completed.stdout
    assert completed.returncode == 0, completed.stdout + completed.stderr


def test_list_and_info(demo, fresh):
    listed = run(fresh, 'colcon', 'list', '--wasm', cwd=demo).stdout
    assert 'demo_nodes' in listed and 'demo_interfaces' in listed, listed
    info = run(fresh, 'colcon', 'info', 'demo_nodes', cwd=demo).stdout
    assert 'demo_interfaces' in info, info


def test_rebuild_with_colcon_options(demo, fresh, tmp_path):
    defaults = tmp_path / 'defaults.yaml'
    defaults.write_text('build:\n  parallel-workers: 2\n')
    mixin_dir = Path(fresh['env']['COLCON_HOME']) / 'mixin' / 'local'
    mixin_dir.mkdir(parents=True, exist_ok=True)
    (mixin_dir / 'wasm.mixin').write_text(json.dumps(
        {'build': {'quiet': {'event-handlers': ['console_direct-']}}}))
    index = Path(fresh['env']['COLCON_HOME']) / 'mixin_repositories.yaml'
    index.write_text('local: file://' + str(mixin_dir / 'index.yaml') + '\n')
    (mixin_dir / 'index.yaml').write_text('mixin:\n  - wasm.mixin\n')
    (Path(fresh['env']['COLCON_HOME']) / 'mixin' / 'local.yaml').write_text(
        'mixin:\n  - wasm.mixin\n')
    completed = run(
        fresh, 'colcon', 'build', '--wasm', '--mixin', 'quiet',
        '--event-handlers', 'console_cohesion+', cwd=demo,
        env={'COLCON_DEFAULTS_FILE': str(defaults)})
    assert 'up to date' in completed.stdout or 'Finished' in completed.stdout, \
        completed.stdout[-3000:]
    log = (demo / 'log' / 'latest_build' / 'logger_all.log').read_text()
    assert 'parallel_workers=2' in log, log[:3000]


def test_native_build_leaves_the_wasm_spaces_alone(demo, fresh, tmp_path):
    # `colcon build` (native) in the same workspace: never touches build_wasm/
    before = sorted(p.name for p in (demo / 'build_wasm').iterdir())
    run(fresh, 'colcon', 'build', '--packages-select', 'no_such_package', cwd=demo,
        check=False)
    assert sorted(p.name for p in (demo / 'build_wasm').iterdir()) == before


def test_node_runs_an_executable(demo, fresh):
    exe = demo / 'install_wasm' / 'demo_nodes' / 'lib' / 'demo_nodes' / 'talker.js'
    completed = run(fresh, 'timeout', '-s', 'INT', '3', 'node', exe, '--ros-args', '-p',
                    'rate:=5', cwd=demo, timeout=60, check=False)
    assert "Publishing: 'Hello World: 2'" in completed.stdout, \
        completed.stdout + completed.stderr


def test_launch_and_run(demo, fresh):
    completed = run(fresh, 'colcon-wasm', 'launch', 'demo_nodes/talker',
                    'demo_nodes/listener', '--duration', '5', cwd=demo, timeout=120)
    assert '[listener-2]' in completed.stdout and 'I heard' in completed.stdout, \
        completed.stdout[-3000:]
    completed = run(fresh, 'timeout', '-s', 'INT', '4', 'colcon-wasm', 'run', 'demo_nodes',
                    'talker', '--ros-args', '-p', 'rate:=2', cwd=demo, timeout=60, check=False)
    assert "Publishing: 'Hello World: 2'" in completed.stdout, \
        completed.stdout + completed.stderr
    completed = run(fresh, 'colcon-wasm', 'launch', 'demo_nodes', 'talker_listener.launch.xml',
                    'topic:=chatter', '--duration', '4', '--echo', '/chatter', cwd=demo,
                    timeout=120)
    assert '[echo /chatter]' in completed.stdout, completed.stdout[-3000:]


def test_colcon_test_and_test_result(demo, fresh):
    # the README's test commands from the fresh venv: the demo is built without
    # tests, which colcon test --wasm says (Humble's tests: tests/test_colcon_test.py)
    completed = run(fresh, 'colcon', 'test', '--wasm', cwd=demo, timeout=600)
    assert 'Summary:' in completed.stdout, completed.stdout[-3000:]
    log = (demo / 'log' / 'latest_test' / 'logger_all.log').read_text()
    assert "'demo_nodes' was built without its tests: build them with colcon build " \
        '--wasm --wasm-tests demo_nodes' in log, log[-3000:]
    shown = run(fresh, 'colcon', 'test-result', '--wasm', '--verbose', cwd=demo, check=False)
    assert 'Summary: 0 tests' in shown.stdout, shown.stdout + shown.stderr
    assert shown.returncode == 0


def _free_port():
    with socket.socket() as s:
        s.bind(('127.0.0.1', 0))
        return s.getsockname()[1]


def test_serve(demo, fresh):
    port = _free_port()
    server = subprocess.Popen(
        ['colcon-wasm', 'serve', '--port', str(port)], cwd=str(demo),
        env=fresh['env'], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        deadline = time.monotonic() + 30
        while True:
            try:
                with urllib.request.urlopen(f'http://127.0.0.1:{port}/', timeout=5) as r:
                    page = r.read().decode()
                    headers = r.headers
                break
            except OSError:
                if time.monotonic() > deadline or server.poll() is not None:
                    raise
                time.sleep(0.2)
        assert 'talker' in page or '<html' in page.lower()
        assert headers['Cross-Origin-Opener-Policy'] == 'same-origin'
        assert headers['Cross-Origin-Embedder-Policy'] == 'require-corp'
    finally:
        server.terminate()
        server.wait(timeout=10)


def test_blasm_help(fresh):
    completed = run(fresh, 'blasm', '-h')
    assert '-u' in completed.stdout and '-s' in completed.stdout


def test_export_from_the_fresh_venv(demo, fresh, tmp_path):
    """`colcon-wasm export` of the installed wheel: its brotli dependency writes the .br forms."""
    site = tmp_path / 'site'
    completed = run(fresh, 'colcon-wasm', 'export', str(site), '--run', 'demo_nodes/talker',
                    cwd=demo, timeout=300)
    assert 'A first visit downloads' in completed.stdout, completed.stdout + completed.stderr
    manifest = json.loads((site / 'files.json').read_text())
    assert manifest['brotli'] is True
    talker = manifest['files']['ws/demo_nodes/lib/demo_nodes/talker.wasm']
    assert talker['br'] < talker['size'], talker
    assert (site / 'ws/demo_nodes/lib/demo_nodes/talker.wasm.br').is_file()
