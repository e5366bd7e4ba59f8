# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The test options of `--wasm` builds and the CMake arguments they give."""

from colcon_wasm import resources

"""The recipe overlay applied with `--wasm-tests` (before the user's)."""
TESTS_RECIPE = 'humble-tests.yaml'

"""ament's linters: Python tools that check sources, not WebAssembly code."""
AMENT_LINTERS = (
    'ament_cmake_clang_format', 'ament_cmake_clang_tidy', 'ament_cmake_copyright',
    'ament_cmake_cppcheck', 'ament_cmake_cpplint', 'ament_cmake_flake8',
    'ament_cmake_lint_cmake', 'ament_cmake_mypy', 'ament_cmake_pclint',
    'ament_cmake_pep257', 'ament_cmake_pycodestyle', 'ament_cmake_pyflakes',
    'ament_cmake_uncrustify', 'ament_cmake_xmllint')


def _default_timeout():
    """Get the time limit (s) of a test that sets none (ament tests set 60)."""
    # the one table of --wasm defaults (it adds these options: imported here)
    from colcon_wasm.options import DEFAULTS
    return DEFAULTS['wasm_test_timeout']


def add_wasm_test_arguments(parser):
    """Add the `--wasm-tests*` options to a colcon verb's parser."""
    default_timeout = _default_timeout()
    parser.add_argument(
        '--wasm-tests', nargs='*', metavar='PKG', default=None,
        help='Build tests (BUILD_TESTING=ON) for `colcon test --wasm`: of the '
             'named packages, or, without names, of every package built except '
             "those whose tests the recipe does not build ('tests: not-built'); gtest and "
             'gmock tests become Node.js programs')
    parser.add_argument(
        '--wasm-fault-injection', action='store_true',
        help='Compile every package with RCUTILS_ENABLE_FAULT_INJECTION, as '
             "rcutils' own test build makes its users do, for tests that inject "
             'failures (RCUTILS_FAULT_INJECTION_TEST)')
    parser.add_argument(
        '--wasm-test-timeout', type=_timeout, metavar='SECONDS',
        default=default_timeout,
        help='colcon test --wasm: time limit of a test that sets none '
             f'(default: {default_timeout}); a test over its limit is '
             'stopped and reported as timed out')


def _timeout(value):
    import argparse
    try:
        seconds = float(value)
    except ValueError:
        seconds = 0
    if seconds <= 0:
        raise argparse.ArgumentTypeError(
            f"'{value}' is not a time limit: give a number of seconds above 0")
    return seconds


class TestSettings:
    """The test settings derived from the `--wasm-tests*` options."""

    __test__ = False  # not a pytest class

    def __init__(self, args):
        """Read the settings from parsed arguments."""
        names = getattr(args, 'wasm_tests', None)
        self.enabled = names is not None
        self.packages = set(names or ())
        self.fault_injection = bool(getattr(args, 'wasm_fault_injection', False))
        self.timeout = float(getattr(args, 'wasm_test_timeout', None)
                             or _default_timeout())

    def tests_of(self, pkg_name, rule):
        """
        Check if a package's tests are built, and why not.

        :param rule: the recipe's :class:`PackageRule` of the package
        :returns: (bool, reason or None)
        """
        if not self.enabled:
            return False, None
        if self.packages:
            if pkg_name in self.packages:
                return True, None
            return False, 'not named by --wasm-tests'
        if rule.tests.not_built:
            return False, rule.tests.not_built
        return True, None

    def describe(self):
        """Get what changes every package's build (for stamps and manifests)."""
        return {'fault_injection': True} if self.fault_injection else {}


def recipe_overlays_for_tests(args):
    """Get the recipe overlays `--wasm-tests` and `colcon test` add (before the user's)."""
    if getattr(args, 'wasm_tests', None) is None and \
            getattr(args, 'verb_name', None) != 'test':
        return []
    return [resources.file('recipes', TESTS_RECIPE)]


def cmake_arguments_for_tests(settings, pkg_name, rule):
    """
    Get the CMake arguments of the test settings for one package.

    Always both, ON or OFF: a cache variable given once would stay in the
    package's CMake cache. toolchains/wasm-ros-cache.cmake turns
    COLCON_WASM_TESTS into BUILD_TESTING, so they come before it (`-C`).
    """
    on_off = {True: 'ON', False: 'OFF'}
    tests, _ = settings.tests_of(pkg_name, rule)
    return [f'-DCOLCON_WASM_TESTS={on_off[tests]}',
            f'-DCOLCON_WASM_FAULT_INJECTION={on_off[settings.fault_injection]}']
