# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The `wasm.*` test task: the stock colcon test task, with tests in Node.js."""

import os
from pathlib import Path
import shutil
import time

from colcon_cmake.task.cmake import CTEST_EXECUTABLE
from colcon_cmake.task.cmake import get_variable_from_cmake_cache
from colcon_core.logging import colcon_logger
from colcon_core.plugin_system import satisfies_version
from colcon_core.shell import get_command_environment
from colcon_core.subprocess import check_output
from colcon_core.task import get_task_extension
from colcon_core.task import TaskExtensionPoint
from colcon_wasm.build_plan import PLAN_KEY
from colcon_wasm.testing import results

logger = colcon_logger.getChild(__name__)

"""Environment variable: the Node.js that runs the tests (default: node on PATH)."""
NODE_ENV = 'COLCON_WASM_NODE'


def find_node():
    """Get the Node.js executable ($COLCON_WASM_NODE, then node on PATH), or None."""
    return os.environ.get(NODE_ENV) or shutil.which('node') or shutil.which('nodejs')


def find_wasm_js(bases):
    """Get the `share/wasm_js` folder of the first base that has it, or None."""
    for base in bases:
        for candidate in (Path(base) / 'wasm_js' / 'share' / 'wasm_js',
                          Path(base) / 'share' / 'wasm_js'):
            if (candidate / 'src' / 'bus_client.mjs').is_file():
                return candidate
    return None


class WasmTestTask(TaskExtensionPoint):
    """
    Test CMake, ros.cmake and ament_cmake packages built with `--wasm`.

    The stock colcon task of the package's original type runs CTest in the
    package's `--wasm` build folder. CTest runs each test as it would
    natively: gtest and gmock executables are Node.js programs
    (:mod:`colcon_wasm.link.test_link`). Around it this task puts Node.js
    on `PATH` (the tests' `#!/usr/bin/env node`), gives tests without a
    time limit `--wasm-test-timeout`, leaves out the tests the recipe says
    are not applicable, and writes the results `colcon test-result` would
    not see otherwise (:mod:`colcon_wasm.testing.results`).
    """

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(TaskExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    async def test(self, *, additional_hooks=None):  # noqa: D102
        pkg = self.context.pkg
        args = self.context.args
        plan = pkg.metadata.get(PLAN_KEY)
        if plan is None:
            logger.error(
                f"Package '{pkg.name}' has type '{pkg.type}' but no --wasm plan: "
                'test it with `colcon test --wasm`')
            return 1
        if plan.host_tool:
            logger.info(
                f"Not testing host tool '{pkg.name}' with colcon test --wasm: it is "
                'Python for the build host; its tests run with a native colcon test')
            return 0
        if getattr(plan, 'python_package', False):
            logger.info(
                f"Not testing Python package '{pkg.name}' with colcon test --wasm: its "
                "tests are pytest modules for the host's CPython (linters, mostly); run "
                'them with a native colcon test')
            return 0
        stock = get_task_extension('colcon_core.task.test', plan.original_type)
        if stock is None:
            logger.error(
                f"No task extension to test a '{plan.original_type}' package "
                f"('{pkg.name}'); is colcon-cmake / colcon-ros installed?")
            return 1
        if not self._built_with_tests(pkg.name, args):
            return 0
        node = find_node()
        if node is None:
            logger.error(
                f"Cannot test '{pkg.name}': no Node.js found (node on PATH, or "
                f'${NODE_ENV}); install Node.js 20 or later')
            return 1
        self._prepare_environment(node, args, plan)

        settings = plan.settings.testing
        if CTEST_EXECUTABLE is None:
            logger.error(f"Cannot test '{pkg.name}': no 'ctest' found (install CMake)")
            return 1
        try:
            env = await get_command_environment(
                'test', args.build_base, self.context.dependencies)
        except RuntimeError as e:
            logger.error(str(e))
            return 1
        tests = results.parse_test_list(await check_output(
            [CTEST_EXECUTABLE, '--show-only=json-v1'], cwd=args.build_base, env=env))
        not_applicable = {}
        for test in tests:
            reason = plan.rule.tests.not_applicable_reason(test.name)
            if reason:
                not_applicable[test.name] = reason
                logger.info(
                    f"Not running '{test.name}' of '{pkg.name}': not applicable in "
                    f'WebAssembly ({reason})')
        # tests the build left out (e.g. rcl's tests that need mimick) are reported too
        not_built = plan.rule.tests.unlisted_not_applicable({t.name for t in tests})
        ctest_args = list(args.ctest_args or [])
        if '--timeout' not in ctest_args:
            ctest_args += ['--timeout', f'{settings.timeout:g}']
        if not_applicable:
            ctest_args += ['-E', results.exclude_regex(not_applicable)]
        args.ctest_args = ctest_args

        result_base = Path(args.test_result_base or args.build_base)
        results.clear_results(result_base)
        started = time.time()
        stock.set_context(context=self.context)
        rc = await stock.test()
        results.read_ctest_record(args.build_base, tests)
        results.write_results(
            package=pkg.name, tests=tests, result_base=result_base,
            default_timeout=f'{settings.timeout:g}', run_started=started,
            not_applicable=dict(not_built, **not_applicable),
            linters=results.package_linters(pkg))
        return rc

    def _built_with_tests(self, pkg_name, args):
        """Check that the package's build folder has its tests, or say why not."""
        build_base = Path(args.build_base)
        if not (build_base / 'CMakeCache.txt').is_file():
            logger.warning(
                f"'{pkg_name}' has no --wasm build in '{build_base}': build it with "
                f'colcon build --wasm --wasm-tests {pkg_name}')
            return False
        testing = get_variable_from_cmake_cache(str(build_base), 'BUILD_TESTING')
        if (testing or '').upper() not in ('ON', 'TRUE', '1', 'YES'):
            logger.info(
                f"'{pkg_name}' was built without its tests: build them with "
                f'colcon build --wasm --wasm-tests {pkg_name}')
            return False
        return True

    def _prepare_environment(self, node, args, plan):
        """
        Put Node.js on PATH and tell standalone executables where wasm_js is.

        Every package gets the same values, so the process environment (which
        colcon's command environment starts from) is set once for all.
        """
        node_dir = str(Path(node).resolve().parent)
        path = os.environ.get('PATH', '')
        if node_dir not in path.split(os.pathsep):
            os.environ['PATH'] = node_dir + (os.pathsep + path if path else '')
        if 'WASM_JS_DIR' not in os.environ:
            # the package's prefix is in the install base (isolated) or is it (merged)
            install_prefix = Path(args.install_base)
            wasm_js = find_wasm_js(
                [install_prefix, install_prefix.parent] + list(plan.underlays))
            if wasm_js is not None:
                # a test that creates a context makes its own private bus
                os.environ['WASM_JS_DIR'] = str(wasm_js)
