# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`blasm`: the thesis' build script (appendix C.1) on top of `colcon build --wasm`.

It keeps the thesis' options. Unlike the thesis' script, `-d` works (it was
missing from that script's getopts string), a build without `-u`/`-s` builds
the whole workspace, and every argument blasm does not know is passed to
`colcon build`. `-p` ("install emscripten python" in the thesis) checks that
Pyodide, which runs the Python nodes, is installed (and says how to get it
when not); `colcon build --wasm` packs the `ament_python` packages for it
in every build (docs/python.md). `-e DIR` (not in the thesis) exports the
install space as a static site after a successful build, with `colcon-wasm
export` (docs/export.md); each `-r 'PKG/EXE [ARGS]'` is an executable the
page starts when it opens.
"""

import argparse
from pathlib import Path
import shlex
import shutil
import subprocess
import sys


BUILD_BASE = 'build_wasm'
INSTALL_BASE = 'install_wasm'
LOG_BASE = 'log'


def create_parser():
    """Create blasm's argument parser (the thesis' options)."""
    parser = argparse.ArgumentParser(
        prog='blasm', add_help=False,
        description='Build ROS 2 packages to WebAssembly '
                    '(`colcon build --wasm`). Arguments blasm does not know '
                    'are passed to colcon build.')
    parser.add_argument('-h', action='help', help='help')
    parser.add_argument('-c', action='store_true', dest='clean',
                        help=f'clean workspace ({BUILD_BASE}/, '
                             f'{INSTALL_BASE}/, {LOG_BASE}/) and exit')
    parser.add_argument('-d', action='store_true', dest='debug',
                        help='activate debug mode (--wasm-debug: -g and '
                             'assertions; verbose CMake makefiles)')
    parser.add_argument('-u', metavar='PKG', dest='up_to',
                        help='build up to package')
    parser.add_argument('-s', metavar='PKG', dest='select',
                        help='build selected package (from a clean build '
                             'folder)')
    parser.add_argument('-i', metavar="'PKG ...'", dest='ignore',
                        help="ignore 'listed packages'")
    parser.add_argument('-p', action='store_true', dest='python',
                        help='Python nodes: check that Pyodide is installed '
                             '(ament_python packages are packed for it)')
    parser.add_argument('-v', action='store_true', dest='verbose',
                        help='verbose')
    parser.add_argument('-e', metavar='DIR', dest='export',
                        help='after a successful build, export the install '
                             'space as a static site into DIR (colcon-wasm '
                             'export)')
    parser.add_argument('-r', metavar="'PKG/EXE [ARGS]'", dest='run',
                        action='append', default=[],
                        help='with -e: an executable the exported page '
                             'starts when it opens (repeatable)')
    return parser


def colcon_arguments(options, extra):
    """
    Translate blasm options into `colcon build` arguments.

    :param options: parsed blasm options
    :param list extra: arguments passed through to colcon
    :rtype: list
    """
    args = ['build', '--wasm']
    if options.up_to:
        args += ['--packages-up-to', options.up_to]
    if options.select:
        args += ['--packages-select', options.select]
    if options.ignore:
        args += ['--packages-ignore'] + options.ignore.split()
    if options.verbose:
        args += ['--event-handlers', 'console_direct+']
    if options.debug:
        args += ['--wasm-debug']
    extra = [a for a in extra if a != '--']
    if options.debug:
        # --cmake-args takes the rest of the line: keep it last
        extra += ['--cmake-args', '-DCMAKE_VERBOSE_MAKEFILE=ON']
    return args + extra


def install_base(extra):
    """
    Get the install base the build writes: colcon's `--install-base`, if passed.

    :param list extra: arguments passed through to colcon
    :rtype: str
    """
    parser = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    parser.add_argument('--install-base', default=INSTALL_BASE)
    return parser.parse_known_args(extra)[0].install_base


def export(target, base, runs):
    """
    Export an install space as a static site with `colcon-wasm export`.

    :param str target: the folder to write the site into
    :param str base: the install space
    :param list runs: the executables the page starts ('PKG/EXE [ARGS]')
    :returns: the exit code of the export (nonzero when it failed)
    """
    # the colcon-wasm command itself (installed beside this Python), as a user runs it
    command = Path(sys.executable).parent / 'colcon-wasm'
    if not command.is_file():
        command = shutil.which('colcon-wasm')
    if command is None:
        print('[BLASM]: -e: the colcon-wasm command is not on PATH: install colcon-wasm '
              '(pip install .) in this environment', file=sys.stderr)
        return 1
    args = ['export', target, '--install-base', base] + [f'--run={r}' for r in runs]
    print('[BLASM]: colcon-wasm ' + ' '.join(shlex.quote(a) for a in args))
    sys.stdout.flush()
    rc = subprocess.run([str(command), *args]).returncode
    if rc:
        print(f"[BLASM]: -e: exporting '{base}' into '{target}' failed (exit "
              f'code {rc}, the reason is above); the build itself succeeded',
              file=sys.stderr)
    return rc


def clean(workspace):
    """Remove the wasm build, install and log folders of a workspace."""
    for name in (BUILD_BASE, INSTALL_BASE, LOG_BASE):
        path = Path(workspace) / name
        if path.is_dir():
            shutil.rmtree(path)
            print(f'[BLASM]: removed {path}')


def check_pyodide():
    """
    Say where the Pyodide that runs the Python nodes is, or how to install it.

    :returns: True when it is there
    """
    from colcon_wasm.launch.errors import LaunchError
    from colcon_wasm.launch.python_nodes import find_pyodide
    from colcon_wasm.launch.python_nodes import PYODIDE_VERSION
    try:
        folder = find_pyodide()
    except LaunchError as e:
        print(f'[BLASM]: -p: {e}', file=sys.stderr)
        return False
    print(f'[BLASM]: Python nodes run with Pyodide {PYODIDE_VERSION} from {folder}; '
          'colcon build --wasm packs the ament_python packages for it')
    return True


def main(argv=None, *, run_colcon=None):
    """
    Run blasm.

    :param argv: the arguments (default: sys.argv[1:])
    :param run_colcon: the function running colcon with a list of arguments
      (default: colcon in this Python environment)
    :returns: the exit code
    """
    options, extra = create_parser().parse_known_args(argv)
    if options.run and not options.export:
        print('[BLASM]: -r needs -e DIR: it names an executable the exported '
              'page starts', file=sys.stderr)
        return 2
    if options.python and not check_pyodide():
        return 2
    workspace = Path.cwd()
    if options.clean:
        clean(workspace)
        return 0
    if not (workspace / 'src').is_dir():
        print(f"[BLASM]: '{workspace}' is not a workspace directory (no "
              'src/ folder): run blasm in the workspace root',
              file=sys.stderr)
        return 1
    if options.select:
        stale = workspace / BUILD_BASE / options.select
        if stale.is_dir():
            shutil.rmtree(stale)
    args = colcon_arguments(options, extra)
    print('[BLASM]: colcon ' + ' '.join(shlex.quote(a) for a in args))
    if run_colcon is None:
        from colcon_core.command import main as colcon
        rc = colcon(argv=args)
    else:
        rc = run_colcon(args)
    if rc or not options.export:
        return rc
    return export(options.export, install_base(extra), options.run)
