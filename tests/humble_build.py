# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
A cached `colcon build --wasm` of the Humble snapshot, for tests.

The build lives in `$COLCON_WASM_CACHE/humble-<hash>` (default cache
`~/.cache/colcon-wasm`); the hash covers everything the build depends on:
the snapshot archive, colcon-wasm's code and data, the Emscripten version,
the package set and the extra packages. An unchanged build is reused; a
fresh machine builds it once (a few minutes). Extend the package set with
:func:`humble_build` (e.g. up to rclcpp once rmw_wasm_cpp exists).

Use from a test module::

    from humble_build import humble_build
    build = humble_build()          # skips when the snapshot is absent
    build.install / 'rcutils' ...
"""

import contextlib
import fcntl
import hashlib
import json
import os
from pathlib import Path
import shutil
import subprocess
import sys
import tarfile
import time

import pytest

REPO = Path(__file__).resolve().parents[1]

"""Packages up to (and without) rmw_implementation: no rmw needed."""
BELOW_RMW_UP_TO = (
    'rmw_implementation', 'rcl_yaml_param_parser', 'builtin_interfaces',
    'rcl_interfaces', 'rosidl_default_runtime', 'humble_probe')
BELOW_RMW_SKIP = ('rmw_implementation',)

"""Extra packages copied into the workspace (name: folder)."""
EXTRA_PACKAGES = {'humble_probe': REPO / 'tests' / 'fixtures' / 'humble_probe'}

_INPUT_FOLDERS = ('colcon_wasm', 'recipes', 'toolchains', 'patches',
                  'templates', 'packages')

"""colcon-wasm files that do not change what a build produces."""
_NOT_INPUTS = ('colcon_wasm/cli/', 'colcon_wasm/blasm.py',
               # the page's pinned libraries (three.js, urdf-loader): run time only
               'colcon_wasm/vendor',
               'colcon_wasm/doctor.py', 'colcon_wasm/launch/',
               'colcon_wasm/server/', 'templates/launcher/',
               # record and replay, Foxglove schemas: run time only
               'colcon_wasm/record/', 'colcon_wasm/ros2msg.py',
               'recipes/schema.md',
               'recipes/humble.repos',
               # colcon test --wasm: runs tests, builds nothing
               'colcon_wasm/task/test.py', 'colcon_wasm/testing/results.py',
               'colcon_wasm/testing/verb.py', 'colcon_wasm/argument_parser/test_result.py')

"""
The JS runtime (ES modules, the Python worker's rclpy): wasm_js installs these
files verbatim (its CMakeLists.txt), no other package reads them at build time.
So they are no input of a build: a cached build gets the current ones
(:func:`refresh_runtime`), the files `colcon build --packages-select wasm_js`
would install, and a change to the runtime rebuilds nothing. Its Emscripten JS
library (src/abi/), linked into every executable, stays an input.
"""
_RUNTIME = 'packages/wasm_js/src/'
_LINKED_RUNTIME = 'packages/wasm_js/src/abi/'
_RUNTIME_SUFFIXES = ('.mjs', '.js', '.html', '.py')  # wasm_js' install(FILES_MATCHING ...)


def humble_snapshot():
    """Get the Humble snapshot folder ($COLCON_WASM_HUMBLE)."""
    return Path(os.environ.get(
        'COLCON_WASM_HUMBLE', REPO.parent / 'shared' / 'humble')).resolve()


def corpus_snapshot():
    """Get the corpus snapshot folder ($COLCON_WASM_CORPUS): more Humble repositories."""
    return Path(os.environ.get(
        'COLCON_WASM_CORPUS', REPO.parent / 'shared' / 'corpus')).resolve()


def control_snapshot():
    """Get the control-stack snapshot ($COLCON_WASM_CORPUS_CONTROL): ros2_control, launch."""
    return Path(os.environ.get(
        'COLCON_WASM_CORPUS_CONTROL', REPO.parent / 'shared' / 'corpus-control')).resolve()


def cache_root():
    """Get the cache folder ($COLCON_WASM_CACHE)."""
    return Path(os.environ.get(
        'COLCON_WASM_CACHE', Path.home() / '.cache' / 'colcon-wasm'))


@contextlib.contextmanager
def cache_lock(name):
    """
    Hold the cache's lock of one entry (a file beside it) for the block.

    Two test runs on one machine (CI's and a developer's, or two pytest
    sessions) that need the same build wait for each other rather than
    remove or overwrite each other's workspace.
    """
    cache_root().mkdir(parents=True, exist_ok=True)
    with open(cache_root() / f'{name}.lock', 'w') as handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)


def unpacked_source(snapshot=None, name='humble-src'):
    """Get an unpacked copy of a snapshot's src/ (shared by all builds)."""
    snapshot = humble_snapshot() if snapshot is None else snapshot
    archive = snapshot / 'src.tar.xz'
    if not archive.is_file():
        return snapshot / 'src'  # missing: callers skip
    stamp = _file_digest(archive)[:16]
    target = cache_root() / f'{name}-{stamp}'
    with cache_lock(f'{name}-{stamp}'):
        _unpack(archive, target)
    return target / 'src'


def _unpack(archive, target):
    """Unpack a snapshot archive into target (whole or not at all), unless it is there."""
    if not (target / '.complete').is_file():
        staging = Path(str(target) + '.tmp')
        shutil.rmtree(staging, ignore_errors=True)
        staging.mkdir(parents=True)
        with tarfile.open(archive) as tar:
            tar.extractall(staging)
        (staging / '.complete').write_text('')
        shutil.rmtree(target, ignore_errors=True)
        staging.rename(target)


def _file_digest(path):
    digest = hashlib.sha256()
    with open(path, 'rb') as handle:
        for block in iter(lambda: handle.read(1 << 20), b''):
            digest.update(block)
    return digest.hexdigest()


def _tree_digest(digest, folder):
    for path in sorted(Path(folder).rglob('*')):
        if not path.is_file() or '__pycache__' in path.parts:
            continue
        name = path.relative_to(REPO).as_posix() \
            if REPO in path.parents else path.name
        if name.startswith(_NOT_INPUTS) or name.endswith('.md'):
            continue
        if name.startswith(_RUNTIME) and not name.startswith(_LINKED_RUNTIME):
            continue
        digest.update(name.encode())
        digest.update(path.read_bytes())


def _emscripten_version():
    from colcon_wasm.toolchain import find_emscripten
    return find_emscripten().version_string


def inputs_hash(up_to, skip, extra, colcon_args=(), corpus=(), underlay=None,
                snapshot=True, control=()):
    """Hash what the build depends on."""
    digest = hashlib.sha256()
    if control:
        digest.update(_file_digest(control_snapshot() / 'src.tar.xz').encode())
        digest.update(json.dumps(sorted(control)).encode())
    if snapshot:
        digest.update(_file_digest(humble_snapshot() / 'src.tar.xz').encode())
    if corpus:
        digest.update(_file_digest(corpus_snapshot() / 'src.tar.xz').encode())
        digest.update(json.dumps(sorted(corpus)).encode())
    if underlay is not None:
        digest.update(str(underlay.workspace).encode())
    for name in _INPUT_FOLDERS:
        if (REPO / name).is_dir():
            _tree_digest(digest, REPO / name)
    for folder in sorted(extra.values()):
        _tree_digest(digest, folder)
    digest.update(json.dumps(
        [sorted(up_to), sorted(skip), sorted(extra), list(colcon_args),
         _emscripten_version(), sys.version_info[:2]]).encode())
    return digest.hexdigest()[:16]


def source_digest(folder):
    """Hash every file below a source folder (path and bytes)."""
    digest = hashlib.sha256()
    for path in sorted(Path(folder).rglob('*')):
        if path.is_file() and not path.is_symlink():
            digest.update(path.relative_to(folder).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()


def refresh_runtime(install):
    """
    Give an install space the repository's JS runtime (share/wasm_js/src).

    Mirrors what wasm_js' CMakeLists.txt installs from packages/wasm_js/src/:
    changed and new files are written, files gone from the repository are
    removed; other files are left alone. Isolated and merged layouts both.
    """
    source = REPO / _RUNTIME
    wanted = {p.relative_to(source): p for p in source.rglob('*')
              if p.is_file() and p.name.endswith(_RUNTIME_SUFFIXES)}
    for share in (Path(install) / 'wasm_js' / 'share' / 'wasm_js',
                  Path(install) / 'share' / 'wasm_js'):
        target = share / 'src'
        if not target.is_dir():
            continue
        for path in list(target.rglob('*')):
            relative = path.relative_to(target)
            if path.is_file() and path.name.endswith(_RUNTIME_SUFFIXES) \
                    and relative not in wanted:
                path.unlink()
        for relative, path in wanted.items():
            destination = target / relative
            data = path.read_bytes()
            if not destination.is_file() or destination.read_bytes() != data:
                destination.parent.mkdir(parents=True, exist_ok=True)
                destination.write_bytes(data)


def prune_stale_builds(max_age_hours=24):
    """
    Remove cached builds nobody used for a day (each is gigabytes).

    A finished build counts as used when its `result.json` was touched (every
    reuse touches it); an unfinished one by its folder's age.
    """
    root = cache_root()
    if not root.is_dir():
        return
    limit = time.time() - max_age_hours * 3600
    for folder in root.glob('humble-*'):
        if not folder.is_dir() or folder.name.startswith(
                ('humble-src-', 'humble-corpus-src-', 'humble-control-src-')):
            continue  # the unpacked snapshots, shared by every build
        marker = folder / 'result.json'
        used = (marker if marker.is_file() else folder).stat().st_mtime
        if used < limit:
            shutil.rmtree(folder, ignore_errors=True)


"""Builds that failed in this process (key: message): never retried."""
_FAILED = {}


class HumbleBuild:
    """A finished build of the Humble snapshot."""

    def __init__(self, workspace, seconds, cached):
        """Describe a build in a workspace folder."""
        self.workspace = workspace
        self.install = workspace / 'install_wasm'
        self.build = workspace / 'build_wasm'
        self.seconds = seconds
        self.cached = cached
        result = json.loads((workspace / 'result.json').read_text())
        self.packages = result['packages']
        self.command = result['command']


def humble_build(up_to=BELOW_RMW_UP_TO, skip=BELOW_RMW_SKIP,
                 extra=EXTRA_PACKAGES, colcon_args=(), corpus=(), underlay=None,
                 snapshot=True, control=()):
    """
    Build (or reuse) the Humble snapshot with `colcon build --wasm`.

    :param up_to: `--packages-up-to` names
    :param skip: `--packages-skip` names
    :param extra: extra packages to add to the workspace (name: folder)
    :param colcon_args: more `colcon build` arguments (last on the command
      line, part of the cache key), e.g. `--cmake-args ...`
    :param corpus: repository folders of the corpus snapshot to add (e.g.
      'ros/pluginlib'), unmodified
    :param underlay: a :class:`HumbleBuild` to build on (`--wasm-underlay`)
    :param bool snapshot: add the Humble snapshot's sources (False for an
      overlay of an underlay that holds them)
    :param control: repository folders of the control-stack snapshot to add
      (e.g. 'ros2/launch_ros'), unmodified
    :returns: the :class:`HumbleBuild`
    :raises pytest.skip.Exception: when the snapshot is absent
    :raises AssertionError: when the build fails (with its log tail)
    """
    if not (humble_snapshot() / 'src.tar.xz').is_file():
        pytest.skip(f'Humble snapshot not found at {humble_snapshot()} '
                    '(set COLCON_WASM_HUMBLE)')
    if corpus and not (corpus_snapshot() / 'src.tar.xz').is_file():
        pytest.skip(f'Humble corpus snapshot not found at {corpus_snapshot()} '
                    '(set COLCON_WASM_CORPUS)')
    if control and not (control_snapshot() / 'src.tar.xz').is_file():
        pytest.skip(f'Humble control-stack snapshot not found at {control_snapshot()} '
                    '(set COLCON_WASM_CORPUS_CONTROL)')
    key = inputs_hash(up_to, skip, extra, colcon_args, corpus, underlay, snapshot, control)
    with cache_lock(f'humble-{key}'):
        return _build(key, up_to, skip, extra, colcon_args, corpus, underlay, snapshot, control)


def _build(key, up_to, skip, extra, colcon_args, corpus, underlay, snapshot, control=()):
    """Build into the cache entry of `key`, or reuse it (the caller holds its lock)."""
    workspace = cache_root() / f'humble-{key}'
    if key in _FAILED:
        # every test module asks; one failed build is reported, not redone
        raise AssertionError(_FAILED[key])
    if (workspace / 'result.json').is_file():
        os.utime(workspace / 'result.json')  # recently used: keep it
        refresh_runtime(workspace / 'install_wasm')
        return HumbleBuild(workspace, 0.0, cached=True)
    prune_stale_builds()
    shutil.rmtree(workspace, ignore_errors=True)
    workspace.mkdir(parents=True)
    if snapshot:
        shutil.copytree(unpacked_source(), workspace / 'src', symlinks=True)
    if corpus:
        corpus_source = unpacked_source(corpus_snapshot(), 'humble-corpus-src')
        for repository in corpus:
            shutil.copytree(corpus_source / repository,
                            workspace / 'src' / 'corpus' / repository, symlinks=True)
    if control:
        control_source = unpacked_source(control_snapshot(), 'humble-control-src')
        for repository in control:
            shutil.copytree(control_source / repository,
                            workspace / 'src' / 'control' / repository, symlinks=True)
    for name, folder in extra.items():
        shutil.copytree(folder, workspace / 'src' / 'extra' / name)
    src_digest_before = source_digest(workspace / 'src')
    command = [
        'nice', '-n', '10', str(Path(sys.executable).parent / 'colcon'),
        'build', '--wasm', '--parallel-workers', str(os.cpu_count() or 2),
        *(['--packages-skip', *skip] if skip else []), '--packages-up-to', *up_to,
        *(['--wasm-underlay', str(underlay.install)] if underlay else []),
        *colcon_args]
    start = time.monotonic()
    limit = float(os.environ.get('COLCON_WASM_HUMBLE_BUILD_TIMEOUT', 3600))
    try:
        completed = subprocess.run(
            command, cwd=workspace, stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT, text=True, timeout=limit,
            env=dict(os.environ,
                     COLCON_HOME=str(workspace / '.colcon_home')))
    except subprocess.TimeoutExpired as e:
        output = e.stdout if isinstance(e.stdout, str) else \
            (e.stdout or b'').decode(errors='replace')
        completed = subprocess.CompletedProcess(command, -1, output)
        completed.stdout += (
            f'\n[tests] stopped after {limit:.0f} s '
            '(COLCON_WASM_HUMBLE_BUILD_TIMEOUT)\n')
    seconds = time.monotonic() - start
    (workspace / 'src_digest.txt').write_text(src_digest_before)
    (workspace / 'build_output.txt').write_text(completed.stdout)
    if completed.returncode != 0:
        _FAILED[key] = (
            f'Humble --wasm build failed after {seconds:.0f} s in '
            f'{workspace} (full output: {workspace}/build_output.txt, '
            f'logs: {workspace}/log/latest_build):\n' +
            completed.stdout[-8000:])
        raise AssertionError(_FAILED[key])
    installed = sorted(
        p.name for p in (workspace / 'install_wasm').iterdir()
        if (p / 'share' / 'colcon-core' / 'packages' / p.name).is_file())
    (workspace / 'result.json').write_text(json.dumps({
        'command': command[3:], 'seconds': round(seconds, 1),
        'packages': installed}, indent=2) + '\n')
    return HumbleBuild(workspace, seconds, cached=False)
