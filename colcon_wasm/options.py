# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The `--wasm*` command line options and the settings they give."""

import argparse
import os
from pathlib import Path
import sys

from colcon_core.environment_variable import EnvironmentVariable
from colcon_wasm import resources
from colcon_wasm.testing.options import add_wasm_test_arguments
from colcon_wasm.testing.options import cmake_arguments_for_tests
from colcon_wasm.testing.options import TestSettings

OPT_LEVELS = ('1', '2', '3', 's', 'z')

"""Folder (inside the build base) of the compile launcher's cache."""
LAUNCHER_CACHE = Path('.colcon_wasm') / 'compile_launcher'

"""Environment variable: default size of the pthread pool."""
PTHREAD_POOL_SIZE_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_PTHREAD_POOL_SIZE',
    'Set the default number of workers started with each --wasm executable')
PTHREAD_POOL_SIZE_ENV = PTHREAD_POOL_SIZE_ENVIRONMENT_VARIABLE.name

"""Environment variable: the --wasm underlays (set by sourcing setup.sh)."""
PREFIX_PATH_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_PREFIX_PATH',
    'The install bases built with --wasm that --wasm builds stand on and '
    'colcon-wasm serve/run/launch read (set by sourcing install_wasm/setup.sh)')


class WasmOption:
    """One row of :data:`OPTIONS`: a `--wasm*` flag, its default, what it sets."""

    def __init__(self, flag, default, *, setting=None, cmake=None):
        """
        Describe a `--wasm*` option.

        :param str flag: the command line flag
        :param default: its default value (the only place it is written)
        :param str setting: the :class:`WasmSettings` attribute it sets (None:
          the option is not a build setting)
        :param str cmake: the CMake variable :func:`cmake_arguments` passes
          the setting as (None: not passed to CMake)
        """
        self.flag = flag
        self.dest = flag[2:].replace('-', '_')
        self.default = default
        self.setting = setting
        self.cmake = cmake


"""
Every `--wasm*` option: its default and where its value goes, in one table.

Read a row from the flag to CMake: `--wasm-opt-level` (default '2') sets
:attr:`WasmSettings.opt_level`, which :func:`cmake_arguments` passes as
`-DCOLCON_WASM_OPT_LEVEL=2`, which toolchains/wasm-ros-cache.cmake turns
into the Release flags (`-O2 -DNDEBUG`). The toolchain files default none of
the CMake variables: they stop with an error naming the variable when one is
unset. The test options (`--wasm-tests*`) are added by
:mod:`colcon_wasm.testing.options`, which reads its defaults here; their
CMake variables are per package (:func:`cmake_arguments_for_tests`).
"""
OPTIONS = (
    WasmOption('--wasm', False),
    WasmOption('--wasm-emscripten', None),  # toolchain.find_emscripten's lookup
    WasmOption('--wasm-recipe', ()),
    WasmOption('--wasm-underlay', ()),
    # -pthread on every compile and link, -sPTHREAD_POOL_SIZE on links
    WasmOption('--wasm-no-pthread', False, setting='pthread', cmake='COLCON_WASM_PTHREAD'),
    WasmOption('--wasm-pthread-pool-size', 4, setting='pthread_pool_size',
               cmake='COLCON_WASM_PTHREAD_POOL_SIZE'),
    # CMAKE_BUILD_TYPE Debug instead of Release
    WasmOption('--wasm-debug', False, setting='debug', cmake='COLCON_WASM_DEBUG'),
    # CMAKE_<LANG>_FLAGS_RELEASE
    WasmOption('--wasm-opt-level', '2', setting='opt_level', cmake='COLCON_WASM_OPT_LEVEL'),
    # CMAKE_EXE_LINKER_FLAGS_RELEASE; None: the --wasm-opt-level
    WasmOption('--wasm-link-opt-level', None, setting='link_opt_level',
               cmake='COLCON_WASM_LINK_OPT_LEVEL'),
    # BUILD_TESTING per package (COLCON_WASM_TESTS)
    WasmOption('--wasm-tests', None),
    # COLCON_WASM_FAULT_INJECTION
    WasmOption('--wasm-fault-injection', False),
    # colcon test --wasm only
    WasmOption('--wasm-test-timeout', 300),
)

"""The defaults of :data:`OPTIONS` by argument destination (`wasm_opt_level`: '2')."""
DEFAULTS = {option.dest: option.default for option in OPTIONS}


def add_wasm_arguments(parser):
    """
    Add the `--wasm*` options to a colcon verb's parser.

    :param parser: the argument parser (or group)
    """
    parser.add_argument(
        '--wasm', action='store_true',
        help='Build to WebAssembly with Emscripten (default bases: '
             'build_wasm/ and install_wasm/)')
    parser.add_argument(
        '--wasm-emscripten', metavar='PATH',
        help='Emscripten to use: an emcc executable, an emsdk folder or an '
             'Emscripten root (default: $EMSDK, then emcc on PATH, then '
             '/usr/share/emscripten)')
    parser.add_argument(
        '--wasm-recipe', metavar='FILE', action='append', default=[],
        help='Recipe file applied on top of the default Humble recipe '
             '(repeatable, applied in order)')
    parser.add_argument(
        '--wasm-underlay', metavar='PATH', action='append', default=[],
        help='An install base built with --wasm to build on (repeatable, '
             'highest priority first; also read from $COLCON_WASM_PREFIX_PATH, '
             'which sourcing its setup.sh sets)')
    parser.add_argument(
        '--wasm-debug', action='store_true',
        help='Debug build: -g and -sASSERTIONS=2')
    parser.add_argument(
        '--wasm-no-pthread', action='store_true',
        help='Build without -pthread (no worker threads)')
    parser.add_argument(
        '--wasm-opt-level', choices=OPT_LEVELS, default=DEFAULTS['wasm_opt_level'],
        help=f"Optimization level of Release builds (default: {DEFAULTS['wasm_opt_level']})")
    parser.add_argument(
        '--wasm-link-opt-level', choices=('0',) + OPT_LEVELS,
        default=DEFAULTS['wasm_link_opt_level'],
        help='Optimization level of Release links only (default: the '
             '--wasm-opt-level); 1 links much faster, 2 and 3 make smaller '
             'and faster .wasm files')
    parser.add_argument(
        '--wasm-pthread-pool-size', type=_pool_size, metavar='N',
        default=_default_pool_size(),
        help='Workers started with each executable (default: '
             f"${PTHREAD_POOL_SIZE_ENV} or {DEFAULTS['wasm_pthread_pool_size']})")
    add_wasm_test_arguments(parser)


def _pool_size(value):
    """Parse a pthread pool size: a whole number, 0 or more."""
    try:
        size = int(value)
    except ValueError:
        size = -1
    if size < 0:
        raise argparse.ArgumentTypeError(
            f"'{value}' is not a pool size: give a whole number, 0 or more "
            '(0 starts no worker ahead: threads then start only while the '
            'creating thread returns to its event loop)')
    return size


def _default_pool_size():
    """Get the pool size of `$COLCON_WASM_PTHREAD_POOL_SIZE`, else the table's."""
    default = DEFAULTS['wasm_pthread_pool_size']
    try:
        return int(os.environ.get(PTHREAD_POOL_SIZE_ENV, default))
    except ValueError:
        return default


class WasmSettings:
    """The build settings derived from the `--wasm*` options (see :data:`OPTIONS`)."""

    def __init__(self, args):
        """Read the settings from parsed arguments (the table's defaults where absent)."""
        def value(dest):
            found = getattr(args, dest, None)
            return DEFAULTS[dest] if found is None else found

        self.pthread = not value('wasm_no_pthread')
        self.debug = bool(value('wasm_debug'))
        self.opt_level = str(value('wasm_opt_level') or DEFAULTS['wasm_opt_level'])
        link = value('wasm_link_opt_level')
        self.link_opt_level = self.opt_level if link is None else str(link)
        pool = getattr(args, 'wasm_pthread_pool_size', None)
        self.pthread_pool_size = _default_pool_size() if pool is None else int(pool)
        self.testing = TestSettings(args)

    def describe(self, cmake_args):
        """Get the flags entry of the manifest: what the build used."""
        return {
            'pthread': self.pthread, 'debug': self.debug,
            'opt': self.opt_level, 'link_opt': self.link_opt_level,
            'pthread_pool_size': self.pthread_pool_size if self.pthread else 0,
            **self.testing.describe(),
            'cmake_args': list(cmake_args)}

    def cmake_arguments(self):
        """Get the `-D` arguments of the settings, as :data:`OPTIONS` maps them."""
        args = []
        for option in OPTIONS:
            if option.cmake is None:
                continue
            value = getattr(self, option.setting)
            if isinstance(value, bool):
                value = 'ON' if value else 'OFF'
            args.append(f'-D{option.cmake}={value}')
        return args


def compile_launcher_script():
    """Get the compile launcher script (run by CMake, see the toolchain)."""
    from colcon_wasm import compile_launcher
    return Path(compile_launcher.__file__).resolve()


def link_launcher_script():
    """Get the link launcher script (run by CMake, see the toolchain)."""
    from colcon_wasm.link import launcher
    return Path(launcher.__file__).resolve()


def cmake_arguments(*, emscripten, settings, install_base, rule,
                    project_name, build_base=None, underlays=()):
    """
    Get the CMake arguments colcon-wasm passes (before the user's).

    Order: our cache variables, the initial cache file, the toolchain file,
    the recipe's project include and cmake-args. The caller appends the
    user's `--cmake-args`, so those override ours.

    :param emscripten: the :class:`colcon_wasm.toolchain.Emscripten`
    :param settings: the :class:`WasmSettings`
    :param str install_base: the wasm install base (absolute)
    :param str build_base: the wasm build base shared by all packages
      (holds the compile launcher's cache); None: per package
    :param rule: the recipe's :class:`PackageRule` for the package
    :param str project_name: the package name (for the project include)
    :param underlays: install bases of the underlays, highest priority first
    :rtype: list
    """
    args = [
        # PYTHON_EXECUTABLE etc. are unused by many packages: no warning
        '--no-warn-unused-cli',
        f'-DCOLCON_WASM_EMSCRIPTEN_ROOT={emscripten.root}',
        f'-DCOLCON_WASM_EMSCRIPTEN_BIN={emscripten.bin_dir}',
        f'-DCOLCON_WASM_INSTALL_BASE={install_base}',
        # the build settings (the CMake variables of OPTIONS)
        *settings.cmake_arguments(),
        # before the initial cache, which reads them (tests, fault injection)
        *cmake_arguments_for_tests(settings.testing, project_name, rule),
        '-C', str(resources.file('toolchains', 'wasm-ros-cache.cmake')),
        '-DCMAKE_TOOLCHAIN_FILE=' + str(
            resources.file('toolchains', 'wasm-ros.cmake')),
        # the interpreter running colcon has the code generators' modules
        f'-DPYTHON_EXECUTABLE={sys.executable}',
        f'-DPython3_EXECUTABLE={sys.executable}',
        f'-DCOLCON_WASM_PYTHON={sys.executable}',
        f'-DCOLCON_WASM_LAUNCHER_SCRIPT={compile_launcher_script()}',
        f'-DCOLCON_WASM_LINK_LAUNCHER_SCRIPT={link_launcher_script()}',
        f"-DCOLCON_WASM_LLVM_NM={emscripten.llvm_tool('llvm-nm')}",
        f"-DCOLCON_WASM_LLVM_CXXFILT={emscripten.llvm_tool('llvm-cxxfilt')}",
        '-DCOLCON_WASM_UNDERLAYS=' + ';'.join(str(u) for u in underlays),
    ]
    if build_base is not None:
        args.append('-DCOLCON_WASM_LAUNCHER_CACHE='
                    + str(Path(build_base) / LAUNCHER_CACHE))
    if rule.env:
        # set while CMake configures the package (see toolchains/wasm-ros.cmake)
        args.append('-DCOLCON_WASM_ENV=' + ';'.join(
            f'{key}={value}' for key, value in sorted(rule.env.items())))
    if rule.project_include:
        args.append(
            f'-DCMAKE_PROJECT_{project_name}_INCLUDE={rule.project_include}')
    args += rule.cmake_args
    return args
