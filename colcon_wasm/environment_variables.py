# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Every environment variable colcon-wasm reads, registered with colcon.

Each is a `colcon_core.environment_variable` entry point (pyproject.toml),
so `colcon --help` lists it, and the README's table lists them too
(tests/test_colcon_environment.py checks both against the code).
"""

from colcon_core.environment_variable import EnvironmentVariable
from colcon_wasm.compile_launcher import VERIFY_VARIABLE
from colcon_wasm.options import PREFIX_PATH_ENVIRONMENT_VARIABLE
from colcon_wasm.options import PTHREAD_POOL_SIZE_ENVIRONMENT_VARIABLE

__all__ = [
    'CACHE_ENVIRONMENT_VARIABLE', 'CHROMIUM_ENVIRONMENT_VARIABLE',
    'LAUNCHER_VERIFY_ENVIRONMENT_VARIABLE', 'NODE_ENVIRONMENT_VARIABLE',
    'PREFIX_PATH_ENVIRONMENT_VARIABLE', 'PTHREAD_POOL_SIZE_ENVIRONMENT_VARIABLE',
    'ROSBRIDGE_DEBUG_ENVIRONMENT_VARIABLE', 'FOXGLOVE_DEBUG_ENVIRONMENT_VARIABLE',
    'PYODIDE_ENVIRONMENT_VARIABLE', 'PYODIDE_SNAPSHOT_ENVIRONMENT_VARIABLE',
    'ZENOH_DEBUG_ENVIRONMENT_VARIABLE',
]

"""The Node.js that runs `colcon test --wasm` tests and `colcon-wasm run/launch`."""
NODE_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_NODE',
    'The Node.js executable colcon test --wasm and colcon-wasm run/launch use '
    '(default: node on PATH)')

"""The Chromium `colcon-wasm doctor` checks."""
CHROMIUM_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_CHROMIUM',
    'The Chromium colcon-wasm doctor checks for the browser tests and serve '
    '(default: /usr/bin/chromium, then chromium on PATH)')

"""Compile every file both ways in the compile launcher (colcon_wasm/compile_launcher.py)."""
LAUNCHER_VERIFY_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    VERIFY_VARIABLE,
    'Set to 1: the compile launcher compiles every file both with clang directly and '
    'with emcc and fails on any difference of the object files')

"""colcon-wasm's cache folder (Debian source packages)."""
CACHE_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_CACHE',
    "colcon-wasm's cache folder, e.g. of Debian source packages (default: "
    '~/.cache/colcon-wasm)')

"""Debug output of the rosbridge bridges of `colcon-wasm launch --rosbridge`."""
ROSBRIDGE_DEBUG_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_ROSBRIDGE_DEBUG',
    'Set to 1: colcon-wasm launch/run print the debug messages of their rosbridge bridges')

"""Debug output of the Foxglove server of `colcon-wasm launch --foxglove`."""
FOXGLOVE_DEBUG_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_FOXGLOVE_DEBUG',
    'Set to 1: colcon-wasm launch/run print the debug messages of their Foxglove server')

"""Debug output of the Zenoh gateway of `colcon-wasm launch --zenoh`."""
ZENOH_DEBUG_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_ZENOH_DEBUG',
    'Set to 1: colcon-wasm launch/run print what their Zenoh gateway bridges')

"""The Pyodide npm package of Python nodes (`colcon-wasm run --python`)."""
PYODIDE_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_PYODIDE',
    'The folder of the Pyodide npm package Python nodes run in (colcon-wasm run/launch '
    '--python; default: the one colcon-wasm doctor names)')

"""Whether Python nodes start from the host's Pyodide snapshot (python/pyodide_snapshot.mjs)."""
PYODIDE_SNAPSHOT_ENVIRONMENT_VARIABLE = EnvironmentVariable(
    'COLCON_WASM_PYODIDE_SNAPSHOT',
    'Set to 0: every Python node starts Pyodide anew rather than from the snapshot of a '
    'started Pyodide the first node of a host makes (kept in COLCON_WASM_CACHE)')
