# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Every COLCON_WASM_* variable the package reads is registered and documented."""

from importlib.metadata import entry_points
import re

from colcon_helpers import REPO

# what the tests and the build read (tests/*.py, CMake cache variables) is not
# the package's environment
_READ = re.compile(
    r"""(?:environ(?:\.get)?\(\s*|environ\[|getenv\(\s*|process\.env\.|"""
    r"""EnvironmentVariable\(\s*|_VARIABLE = |_ENV = )['"]?(COLCON_WASM_[A-Z_]+)""")


def _read_by_the_package():
    names = set()
    sources = list((REPO / 'colcon_wasm').glob('**/*.py'))
    sources += list((REPO / 'packages' / 'wasm_js' / 'src').glob('**/*.mjs'))
    for path in sources:
        names |= set(_READ.findall(path.read_text(encoding='utf-8')))
    return names


def _registered():
    return {entry.load().name
            for entry in entry_points(group='colcon_core.environment_variable')
            if entry.value.startswith('colcon_wasm.')}


def test_every_variable_read_is_registered_with_colcon():
    read = _read_by_the_package()
    assert {'COLCON_WASM_NODE', 'COLCON_WASM_CHROMIUM', 'COLCON_WASM_LAUNCHER_VERIFY',
            'COLCON_WASM_CACHE', 'COLCON_WASM_ROSBRIDGE_DEBUG'} <= read
    assert read - _registered() == set(), 'register them in colcon_wasm/environment_variables.py'


def test_every_registered_variable_is_listed_in_the_readme():
    readme = (REPO / 'README.md').read_text(encoding='utf-8')
    missing = {name for name in _registered() if f'| `{name}` |' not in readme}
    assert missing == set(), "add them to the README's table of environment variables"
