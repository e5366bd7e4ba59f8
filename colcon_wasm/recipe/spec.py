# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The recipe schema (documented in `recipes/schema.md`).

Each section is checked by a small `_check_*` function. Every error names
the file, the line, the key and what is expected.
"""

from fnmatch import fnmatchcase
from pathlib import Path
import re

from colcon_wasm.error import ColconWasmError
from colcon_wasm.recipe import system
from colcon_wasm.recipe.tests import check_tests_rule
from colcon_wasm.recipe.tests import TestsRule
from colcon_wasm.recipe.yaml_lines import LineDict
from packaging.specifiers import InvalidSpecifier
from packaging.specifiers import SpecifierSet

TOP_LEVEL_KEYS = (
    'recipe', 'env', 'skip', 'unskip', 'host-tools', 'system', 'packages')
RECIPE_KEYS = ('name', 'version', 'ros-distro')
PACKAGE_KEYS = (
    'cmake-args', 'env', 'patches', 'depends', 'drop-depends',
    'project-include', 'note', 'tests')
PATCH_KEYS = ('file', 'versions')

_NAME_PATTERN = re.compile(r'^[A-Za-z0-9_.*?\[\]-]+$')
_ENV_NAME = re.compile(r'^[A-Za-z_][A-Za-z0-9_]*$')


class RecipeError(ColconWasmError):
    """A recipe file is invalid; the message names file, line and key."""


class PatchSpec:
    """One patch of a package, for a range of package versions."""

    def __init__(self, *, file, versions, origin):
        """
        Describe a patch.

        :param pathlib.Path file: the patch file
        :param versions: a `SpecifierSet` or None (all versions)
        :param str origin: `recipe-file:line`, for messages
        """
        self.file = file
        self.versions = versions
        self.origin = origin

    def applies_to(self, version):
        """
        Check if the patch is for a package version.

        :param str version: the package version, or None when unknown
        :raises RecipeError: when a version range is given but the package
          declares no version
        """
        if self.versions is None:
            return True
        if version is None:
            raise RecipeError(
                f"{self.origin}: patch '{self.file.name}' is for versions "
                f"'{self.versions}' but the package declares no version; "
                "remove 'versions' or add a package.xml version")
        return self.versions.contains(version, prereleases=True)


class PackageRule:
    """What the recipe says about one package."""

    def __init__(self, name):
        """Create an empty rule for a package name."""
        self.name = name
        self.cmake_args = []
        self.env = {}
        self.patches = []
        self.depends = []
        self.drop_depends = []
        self.project_include = None
        self.note = None
        self.tests = TestsRule()

    def merge(self, other):
        """Add an overlay's rule: lists are appended, mappings updated."""
        self.cmake_args += other.cmake_args
        self.env.update(other.env)
        self.patches += other.patches
        self.depends += [d for d in other.depends if d not in self.depends]
        self.drop_depends += [
            d for d in other.drop_depends if d not in self.drop_depends]
        if other.project_include is not None:
            self.project_include = other.project_include
        if other.note is not None:
            self.note = other.note
        self.tests.merge(other.tests)


class Recipe:
    """A validated recipe: the default one plus the user's overlays."""

    def __init__(self):
        """Create an empty recipe."""
        self.name = None
        self.version = None
        self.ros_distro = None
        self.files = []
        self.env = {}
        self.skip = {}
        self.python_only = set()
        self.host_tools = []
        self.system = system.SystemRules()
        self.packages = {}

    def skip_reason(self, name):
        """
        Get why a package is skipped.

        :param str name: the package name
        :returns: the reason, or None when the package is not skipped
        """
        if name in self.skip:
            return self.skip[name]
        for pattern, reason in self.skip.items():
            if fnmatchcase(name, pattern):
                return reason
        return None

    def is_python_only(self, name):
        """
        Check if a skipped package is one only Python code needs.

        A C/C++ package that depends on it (for its Python part: rclpy,
        python_cmake_module) is built without that dependency.
        """
        if self.skip_reason(name) is None:
            return False
        return name in self.python_only or any(
            fnmatchcase(name, p) for p in self.python_only)

    def rule(self, name):
        """Get the rule of a package (an empty one when none is given)."""
        return self.packages.get(name) or PackageRule(name)

    def describe(self):
        """Get name and version, for the manifest."""
        return {'name': self.name, 'version': self.version}

    def merge(self, overlay):
        """
        Apply an overlay recipe on top of this one.

        :param dict overlay: the checked sections of one file
        """
        meta = overlay.get('recipe') or {}
        self.name = meta.get('name', self.name)
        self.version = meta.get('version', self.version)
        self.ros_distro = meta.get('ros-distro', self.ros_distro)
        self.env.update(overlay.get('env') or {})
        for name in overlay.get('unskip') or []:
            self.skip.pop(name, None)
            self.python_only.discard(name)
        for name, (reason, python_only) in (overlay.get('skip') or {}).items():
            self.skip[name] = reason
            if python_only:
                self.python_only.add(name)
            else:
                self.python_only.discard(name)
        self.system.update(overlay.get('system') or {})
        for name in overlay.get('host-tools') or []:
            if name not in self.host_tools:
                self.host_tools.append(name)
        for name, rule in (overlay.get('packages') or {}).items():
            if name in self.packages:
                self.packages[name].merge(rule)
            else:
                self.packages[name] = rule


def _where(path, container, key):
    line = container.line_of(key) if hasattr(container, 'line_of') else None
    return f'{path}:{line}' if line else f'{path}'


def _fail(path, container, key, dotted, problem):
    raise RecipeError(f"{_where(path, container, key)}: '{dotted}': {problem}")


def _check_mapping(path, parent, key, dotted, value):
    if not isinstance(value, dict):
        _fail(path, parent, key, dotted,
              f'expected a mapping, got {_describe(value)}')


def _check_keys(path, mapping, dotted, allowed):
    for key in mapping:
        if key not in allowed:
            _fail(path, mapping, key, f'{dotted}{key}',
                  'unknown key, expected one of: ' + ', '.join(allowed))


def _describe(value):
    if value is None:
        return 'nothing'
    if isinstance(value, dict):
        return 'a mapping'
    if isinstance(value, list):
        return 'a list'
    return f'{type(value).__name__} {value!r}'


def _check_string(path, parent, key, dotted, value):
    if not isinstance(value, str) or not value:
        _fail(path, parent, key, dotted,
              f'expected a non-empty string, got {_describe(value)}')
    return value


def _check_string_list(path, parent, key, dotted, value):
    if not isinstance(value, list):
        _fail(path, parent, key, dotted,
              f'expected a list of strings, got {_describe(value)}')
    for index, item in enumerate(value):
        if not isinstance(item, str):
            _fail(path, value, index, f'{dotted}[{index}]',
                  f'expected a string, got {_describe(item)}')
    return list(value)


def _check_package_name(path, parent, key, dotted, value):
    _check_string(path, parent, key, dotted, value)
    if not _NAME_PATTERN.match(value):
        _fail(path, parent, key, dotted,
              f"'{value}' is not a package name (or glob pattern)")
    return value


def _check_env(path, parent, key, dotted, value):
    _check_mapping(path, parent, key, dotted, value)
    env = {}
    for name, item in value.items():
        if not isinstance(name, str) or not _ENV_NAME.match(name):
            _fail(path, value, name, f'{dotted}.{name}',
                  'not a valid environment variable name')
        if isinstance(item, bool) or not isinstance(item, (str, int, float)):
            _fail(path, value, name, f'{dotted}.{name}',
                  f'expected a string, got {_describe(item)}')
        env[name] = str(item)
    return env


def _check_recipe_section(path, data):
    value = data['recipe']
    _check_mapping(path, data, 'recipe', 'recipe', value)
    _check_keys(path, value, 'recipe.', RECIPE_KEYS)
    result = {}
    for key in RECIPE_KEYS:
        if key in value:
            item = value[key]
            if isinstance(item, (int, float)) and not isinstance(item, bool):
                item = str(item)
            result[key] = _check_string(
                path, value, key, f'recipe.{key}', item)
    return result


def _check_skip_section(path, data):
    value = data['skip']
    _check_mapping(path, data, 'skip', 'skip', value)
    skip = {}
    for name, reason in value.items():
        _check_package_name(path, value, name, f'skip.{name}', name)
        python_only = False
        if isinstance(reason, dict):
            entry = reason
            _check_keys(path, entry, f'skip.{name}.', ('reason', 'python-only'))
            reason = entry.get('reason')
            python_only = entry.get('python-only', False)
            if not isinstance(python_only, bool):
                _fail(path, entry, 'python-only', f'skip.{name}.python-only',
                      f'expected true or false, got {_describe(python_only)}')
        _check_string(path, value, name, f'skip.{name}', reason)
        skip[name] = (reason, python_only)
    return skip


def _check_system_entry(path, section, key, value):
    dotted = f'system.{key}'
    _check_mapping(path, section, key, dotted, value)
    _check_keys(path, value, f'{dotted}.', system.SYSTEM_KEYS)
    kinds = [k for k in system.KINDS if k in value]
    if len(kinds) != 1:
        _fail(path, section, key, dotted,
              'expected exactly one of ' + ', '.join(system.KINDS)
              + (f", got {', '.join(kinds)}" if kinds else ''))
    kind = kinds[0]
    rule = system.SystemRule(key, kind, origin=_where(path, section, key))
    item = value[kind]
    if kind == 'workspace':
        rule.workspace = _check_package_name(
            path, value, kind, f'{dotted}.{kind}', item)
    elif kind in ('host-tool', 'builtin'):
        rule.reason = _check_string(path, value, kind, f'{dotted}.{kind}', item)
    elif kind == 'host-headers':
        _check_mapping(path, value, kind, f'{dotted}.{kind}', item)
        _check_keys(path, item, f'{dotted}.{kind}.', system.HOST_HEADERS_KEYS)
        if 'check' not in item:
            _fail(path, value, kind, f'{dotted}.{kind}',
                  "missing key 'check' (a file the host must have)")
        rule.check = _check_string(path, item, 'check', f'{dotted}.{kind}.check',
                                   item['check'])
        if 'cmake-args' in item:
            rule.cmake_args = _check_string_list(
                path, item, 'cmake-args', f'{dotted}.{kind}.cmake-args', item['cmake-args'])
    else:  # debian-source
        _check_mapping(path, value, kind, f'{dotted}.{kind}', item)
        _check_keys(path, item, f'{dotted}.{kind}.', system.DEBIAN_SOURCE_KEYS)
        if 'package' not in item:
            _fail(path, value, kind, f'{dotted}.{kind}',
                  "missing key 'package' (Debian's source package)")
        rule.source_package = _check_package_name(
            path, item, 'package', f'{dotted}.{kind}.package', item['package'])
        if 'version' in item:
            rule.source_version = _check_string(
                path, item, 'version', f'{dotted}.{kind}.version', str(item['version']))
        if 'build' in item:
            build = _check_string(path, item, 'build', f'{dotted}.{kind}.build',
                                  item['build'])
            build_file = (path.parent / build).resolve()
            if not build_file.is_file():
                _fail(path, item, 'build', f'{dotted}.{kind}.build',
                      f"CMake file '{build_file}' does not exist")
            rule.build_file = build_file
        if 'cmake-args' in item:
            rule.cmake_args = _check_string_list(
                path, item, 'cmake-args', f'{dotted}.{kind}.cmake-args', item['cmake-args'])
    for extra in ('debian', 'note'):
        if extra in value:
            setattr(rule, extra, _check_string(
                path, value, extra, f'{dotted}.{extra}', value[extra]))
    return rule


def _check_system_section(path, data):
    value = data['system']
    _check_mapping(path, data, 'system', 'system', value)
    rules = {}
    for key, entry in value.items():
        _check_package_name(path, value, key, f'system.{key}', str(key))
        rules[key] = _check_system_entry(path, value, key, entry)
    return rules


def _check_patch(path, patches, index, dotted, item):
    if isinstance(item, str):
        item = LineDict(file=item)
        item.line = patches.line_of(index)
    if not isinstance(item, dict):
        _fail(path, patches, index, dotted,
              f'expected a mapping with file and versions, got '
              f'{_describe(item)}')
    _check_keys(path, item, f'{dotted}.', PATCH_KEYS)
    if 'file' not in item:
        _fail(path, patches, index, dotted, "missing key 'file'")
    file_name = _check_string(path, item, 'file', f'{dotted}.file',
                              item['file'])
    patch_file = (path.parent / file_name).resolve()
    if not patch_file.is_file():
        _fail(path, item, 'file', f'{dotted}.file',
              f"patch file '{patch_file}' does not exist")
    versions = None
    if 'versions' in item:
        text = _check_string(path, item, 'versions', f'{dotted}.versions',
                             str(item['versions']))
        try:
            versions = SpecifierSet(text)
        except InvalidSpecifier:
            _fail(path, item, 'versions', f'{dotted}.versions',
                  f"'{text}' is not a version range like '>=5.1,<6'")
    return PatchSpec(file=patch_file, versions=versions,
                     origin=_where(path, patches, index))


def _check_package(path, packages, name, value):
    dotted = f'packages.{name}'
    if value is None:
        value = LineDict()
    _check_mapping(path, packages, name, dotted, value)
    _check_keys(path, value, f'{dotted}.', PACKAGE_KEYS)
    rule = PackageRule(name)
    if 'cmake-args' in value:
        rule.cmake_args = _check_string_list(
            path, value, 'cmake-args', f'{dotted}.cmake-args',
            value['cmake-args'])
    if 'env' in value:
        rule.env = _check_env(path, value, 'env', f'{dotted}.env',
                              value['env'])
    for key in ('depends', 'drop-depends'):
        if key in value:
            items = _check_string_list(
                path, value, key, f'{dotted}.{key}', value[key])
            for index, item in enumerate(items):
                _check_package_name(
                    path, value[key], index, f'{dotted}.{key}[{index}]', item)
            setattr(rule, key.replace('-', '_'), items)
    if 'patches' in value:
        patches = value['patches']
        if not isinstance(patches, list):
            _fail(path, value, 'patches', f'{dotted}.patches',
                  f'expected a list, got {_describe(patches)}')
        rule.patches = [
            _check_patch(path, patches, index, f'{dotted}.patches[{index}]',
                         item)
            for index, item in enumerate(patches)]
    if 'project-include' in value:
        file_name = _check_string(
            path, value, 'project-include', f'{dotted}.project-include',
            value['project-include'])
        include = (path.parent / file_name).resolve()
        if not include.is_file():
            _fail(path, value, 'project-include',
                  f'{dotted}.project-include',
                  f"CMake file '{include}' does not exist")
        rule.project_include = include
    if 'note' in value:
        rule.note = _check_string(path, value, 'note', f'{dotted}.note',
                                  value['note'])
    if 'tests' in value:
        rule.tests = check_tests_rule(
            path, value, f'{dotted}.tests', value['tests'], fail=_fail,
            check_keys=_check_keys, check_string=_check_string,
            check_mapping=_check_mapping)
    return rule


def check_recipe_data(path, data):
    """
    Check the data of one recipe file.

    :param pathlib.Path path: the file (for messages and relative paths)
    :param data: the loaded YAML (with line numbers)
    :returns: the checked sections as plain values
    :rtype: dict
    :raises RecipeError: naming file, line, key and what is expected
    """
    path = Path(path)
    if data is None:
        data = LineDict()
    if not isinstance(data, dict):
        raise RecipeError(
            f'{path}:1: expected a mapping with the keys '
            + ', '.join(TOP_LEVEL_KEYS) + f', got {_describe(data)}')
    _check_keys(path, data, '', TOP_LEVEL_KEYS)
    checked = {}
    if 'recipe' in data:
        checked['recipe'] = _check_recipe_section(path, data)
    if 'env' in data:
        checked['env'] = _check_env(path, data, 'env', 'env', data['env'])
    if 'skip' in data:
        checked['skip'] = _check_skip_section(path, data)
    if 'system' in data:
        checked['system'] = _check_system_section(path, data)
    for key in ('unskip', 'host-tools'):
        if key in data:
            items = _check_string_list(path, data, key, key, data[key])
            for index, item in enumerate(items):
                _check_package_name(
                    path, data[key], index, f'{key}[{index}]', item)
            checked[key] = items
    if 'packages' in data:
        packages = data['packages']
        _check_mapping(path, data, 'packages', 'packages', packages)
        checked['packages'] = {}
        for name, value in packages.items():
            _check_package_name(
                path, packages, name, f'packages.{name}', name)
            checked['packages'][name] = _check_package(
                path, packages, name, value)
    return checked
