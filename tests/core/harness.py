# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Build and run the middleware-core test nodes (tests/test_core_*.py).

The test executable (tests/core/nodes, one program with many roles) is built
with the real `colcon build --wasm`, which also builds the bundled wasm_js and
wasm_cpp packages. The build is cached under COLCON_WASM_CACHE (default
~/.cache/colcon-wasm), keyed by a hash of everything that shapes it, so a
session compiles at most once and later sessions reuse it. Scenarios
(tests/core/scenarios.mjs) run in Node.js worker_threads (run_scenario.mjs)
and in headless Chromium (browser_driver.mjs, one browser per session).
"""

import atexit
import fcntl
import hashlib
import json
import os
from pathlib import Path
import shutil
import subprocess
import sys

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO / 'tests'))

from colcon_helpers import colcon  # noqa: E402
from colcon_helpers import tree_digest  # noqa: E402

CHROMIUM = os.environ.get('COLCON_WASM_CHROMIUM', '/usr/bin/chromium')
PLAYWRIGHT = REPO / 'tests' / 'js' / 'node_modules' / 'playwright-core'

# Everything that changes what the build produces.
_INPUTS = ['packages/wasm_cpp', 'packages/wasm_js', 'toolchains',
           'templates/glue', 'colcon_wasm']


def _emcc_version():
    try:
        out = subprocess.run(['emcc', '--version'], capture_output=True,
                             text=True, env=_env()).stdout
    except OSError:
        return 'no emcc'
    return out.splitlines()[0] if out else 'unknown'


def _env():
    env = dict(os.environ)
    # Debian's emcc runs acorn from Node.js' own module folder.
    env.setdefault('NODE_PATH', '/usr/share/nodejs')
    return env


def _cache_root():
    root = os.environ.get('COLCON_WASM_CACHE', '~/.cache/colcon-wasm')
    return Path(root).expanduser() / 'core-tests'


class CoreBuild:
    """A built package of test executables and the installed wasm_js runtime."""

    def __init__(self, workspace, package='core_test_nodes'):
        """Describe the install space of a finished build."""
        install = Path(workspace) / 'install_wasm'
        self.workspace = Path(workspace)
        self.share = install / 'wasm_js' / 'share' / 'wasm_js'
        self.src = self.share / 'src'
        self.bin = install / package / 'bin'
        self.core_node = self.bin / 'core_node.js'


def build(source=HERE / 'nodes', package='core_test_nodes', colcon_args=()):
    """
    Build (or reuse) a package of wasm_cpp executables with colcon build --wasm.

    :param source: the package folder (a plain CMake project)
    :param package: its project() name
    :param colcon_args: more `colcon build` arguments (e.g. --wasm-no-pthread)
    :returns: a CoreBuild
    """
    digest = hashlib.sha256()
    digest.update(repr(list(colcon_args)).encode())
    for rel in _INPUTS:
        digest.update(rel.encode())
        digest.update(tree_digest(REPO / rel).encode())
    digest.update(str(source).encode())
    digest.update(tree_digest(source).encode())
    digest.update(_emcc_version().encode())
    key = digest.hexdigest()[:20]
    root = _cache_root()
    root.mkdir(parents=True, exist_ok=True)
    target = root / key
    with open(root / '.lock', 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (target / 'done').exists():
            shutil.rmtree(target, ignore_errors=True)
            shutil.copytree(source, target / 'src' / package)
            colcon(target, 'build', '--wasm', *colcon_args, env=_env(),
                   timeout=1800)
            (target / 'done').write_text(key)
    result = CoreBuild(target, package)
    assert result.bin.is_dir(), f'{result.bin} was not built'
    return result


_BUILD = None
_BROWSER = None


def get_build():
    """Get the session's build (built on first use)."""
    global _BUILD
    if _BUILD is None:
        _BUILD = build()
    return _BUILD


def get_browser():
    """Get the session's browser (started on first use, stopped at exit)."""
    global _BROWSER
    if _BROWSER is None:
        core = get_build()
        _BROWSER = Browser(
            [('/wasm_js/', core.share), ('/nodes/', core.bin),
             ('/core/', HERE)], plain=[('/plain/', HERE)],
            no_eval=[('/no-eval/wasm_js/', core.share)])
        atexit.register(_BROWSER.close)
    return _BROWSER


def run(platform, scenario):
    """Run a scenario on 'node' or 'chromium' (skips when Chromium is missing)."""
    if platform == 'node':
        return run_node(get_build(), scenario)
    reason = browser_skip_reason()
    if reason:
        import pytest
        pytest.skip(reason)
    return get_browser().run(scenario)


def run_node(core, scenario, timeout=240):
    """Run one scenario in Node.js worker_threads; return its result dict."""
    completed = subprocess.run(
        ['node', str(HERE / 'run_scenario.mjs'), str(core.src),
         str(core.core_node), scenario],
        capture_output=True, text=True, timeout=timeout, env=_env())
    assert completed.returncode == 0, (
        f'run_scenario.mjs {scenario} failed ({completed.returncode}):\n'
        f'{completed.stdout[-3000:]}\n{completed.stderr[-3000:]}')
    lines = [line for line in completed.stdout.splitlines() if line]
    return json.loads(lines[-1])


class Browser:
    """One headless Chromium (via browser_driver.mjs) for a test session."""

    def __init__(self, routes, plain=(), no_eval=(), log=False):
        """
        Start the driver serving (prefix, folder) routes.

        `plain` routes are served without cross-origin isolation, `no_eval`
        ones with a Content-Security-Policy that refuses eval (to the
        workers whose scripts they serve); log: page console to stderr.
        """
        args = []
        for kind, pairs in (('--route', routes), ('--plain', plain),
                            ('--no-eval', no_eval)):
            for prefix, folder in pairs:
                args += [kind, f'{prefix}={folder}']
        self.process = subprocess.Popen(
            ['node', str(HERE / 'browser_driver.mjs')] + args,
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True,
            env=dict(_env(), BROWSER_DRIVER_LOG='1' if log else ''))
        hello = self.process.stdout.readline()
        assert hello, 'browser_driver.mjs exited at start-up'
        self.info = json.loads(hello)
        self._next = 0

    def evaluate(self, url, expr=None):
        """Open `url` in a fresh page, evaluate `expr`; return the reply."""
        self._next += 1
        message = {'id': self._next, 'cmd': 'evaluate', 'url': url,
                   'expr': expr}
        self.process.stdin.write(json.dumps(message) + '\n')
        self.process.stdin.flush()
        line = self.process.stdout.readline()
        assert line, 'browser_driver.mjs exited'
        reply = json.loads(line)
        assert 'error' not in reply, reply['error']
        return reply['result']

    def run(self, scenario, wasm_js=None):
        """
        Run one core scenario in a fresh page; return its result dict.

        wasm_js: the URL prefix to load the runtime from (its workers come
        from there too), instead of /wasm_js/.
        """
        page = '/core/page.html'
        if wasm_js:
            page += '?wasm_js=' + wasm_js
        reply = self.evaluate(page,
                              f'window.runScenario({json.dumps(scenario)})')
        assert reply['status'] == 'ready', reply
        return dict(reply['value'], console=reply['console'])

    def close(self):
        """Stop the driver (and Chromium)."""
        try:
            self.process.stdin.close()
            self.process.wait(timeout=30)
        except (OSError, subprocess.TimeoutExpired):
            self.process.kill()
            self.process.wait()


def browser_skip_reason():
    """
    Tell why browser tests cannot run here, or return None.

    Under CI (CI set) a missing Chromium or playwright-core is an error, so
    that the browser half of the tests is never skipped silently.
    """
    reason = None
    if not Path(CHROMIUM).is_file() and not shutil.which(CHROMIUM):
        reason = f'no Chromium at {CHROMIUM} (set COLCON_WASM_CHROMIUM)'
    elif not PLAYWRIGHT.is_dir():
        reason = 'playwright-core is not installed: run `npm ci` in tests/js'
    if reason and os.environ.get('CI'):
        raise AssertionError(f'browser tests cannot run under CI: {reason}')
    return reason


def results(run, name):
    """Get the RESULT key=values of process `name` of a scenario run."""
    assert run['ok'], f'scenario failed: {run["error"]}\n{_dump(run)}'
    return run['processes'][name]['results']


def exit_of(run, name):
    """Get the exit record of process `name`."""
    return run['processes'][name]['exit']


def assert_trap_reported(run):
    """Check a 'trap' scenario run: the victim crashed, the others went on."""
    why = explain(run)
    victim = exit_of(run, 'victim')
    assert victim['crashed'] and victim['code'] != 0, why
    assert 'unreachable' in victim['reason'], why
    assert run['extra']['graph_after'] == ['other', 'survivor'], why
    assert int(results(run, 'survivor')['continued']) >= 2000, why


def _dump(run):
    out = []
    for name, proc in run.get('processes', {}).items():
        out.append(f'--- {name}: {proc["exit"]}')
        out.extend(proc['lines'][-15:])
    out.extend(run.get('console', [])[-15:])
    return '\n'.join(out)


def explain(run):
    """Dump a run readably, for assertion messages."""
    return _dump(run)
