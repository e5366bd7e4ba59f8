# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Select and prepare the packages of a `--wasm` build.

Two extensions, because colcon runs package selection extensions by
priority:

* :class:`WasmDependencyPackageSelection` (high priority, runs first) adds the
  recipe's extra dependencies (`depends`), so that `--packages-up-to` and the
  build order see them;
* :class:`WasmPackageSelection` (low priority, runs last, after the user's
  own selection) unselects what the recipe skips and packages of other
  types than CMake, ``ament_python`` and plain ``python``, checks that
  nothing selected needs a skipped package, keeps a workspace copy of a
  bundled package over the bundled one, and switches the package types to
  the `wasm.*` build tasks (the Python ones are packed for Pyodide).
"""

import os
from pathlib import Path

from colcon_core.dependency_descriptor import DependencyDescriptor
from colcon_core.logging import colcon_logger
from colcon_core.package_selection import PackageSelectionExtensionPoint
from colcon_core.plugin_system import satisfies_version
from colcon_core.topological_order import topological_order_decorators
from colcon_wasm.build_plan import BuildPlan
from colcon_wasm.build_plan import PLAN_KEY
from colcon_wasm.error import ColconWasmError
from colcon_wasm.error import exit_message
from colcon_wasm.options import add_wasm_arguments
from colcon_wasm.options import WasmSettings
from colcon_wasm.package_discovery.bundled import is_bundled
from colcon_wasm.system_deps import add_system_packages
from colcon_wasm.system_deps import check_system_dependencies
from colcon_wasm.system_deps import system_cmake_args
from colcon_wasm.system_deps import SYSTEM_RULE_KEY
from colcon_wasm.underlay import get_underlays
from colcon_wasm.verb_start import get_recipe
from colcon_wasm.verb_start import started_emscripten

logger = colcon_logger.getChild(__name__)

"""Package types built by the wasm task, and their `wasm.*` names."""
WASM_TYPES = {
    'cmake': 'wasm.cmake',
    'ros.cmake': 'wasm.ros.cmake',
    'ros.ament_cmake': 'wasm.ros.ament_cmake',
}

"""
Python package types packed for Pyodide (installed by their stock task,
given a manifest by colcon_wasm.python_package), and their `wasm.*` names.
"""
PYTHON_TYPES = {
    'ros.ament_python': 'wasm.ros.ament_python',
    'python': 'wasm.python',
}

"""
Packages a Python package may need that colcon-wasm's runtime provides in
their place: the rclpy of packages/wasm_js/src/python (docs/python.md).
"""
RUNTIME_PYTHON_PACKAGES = {'rclpy': "colcon-wasm's rclpy for Pyodide"}

"""
Package types of host tools wrapped by the wasm task (it skips them when up
to date; the stock Python task does the build).
"""
HOST_TOOL_TYPE_PREFIX = 'wasm.host.'
HOST_TOOL_TYPES = ('wasm.host.python', 'wasm.host.ros.ament_python')

"""Dependency categories that must be buildable (tests are off)."""
NEEDED_CATEGORIES = ('build', 'run')

"""The bundled package that builds rclcpp_components' stock containers again."""
CONTAINERS_PACKAGE = 'colcon_wasm_component_containers'

"""The bundled package of the Zenoh gateway, built with the package it needs."""
GATEWAY_PACKAGE = 'zenoh_wasm_gateway'
GATEWAY_NEEDS = 'zenoh_pico'


class WasmDependencyPackageSelection(PackageSelectionExtensionPoint):
    """Add the recipe's extra dependencies before the user's selection."""

    PRIORITY = 1000

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            PackageSelectionExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    def select_packages(self, *, args, decorators):  # noqa: D102
        if not getattr(args, 'wasm', False):
            return
        recipe = get_recipe(args)
        by_name = {}
        for decorator in decorators:
            by_name.setdefault(decorator.descriptor.name, []).append(decorator)
        added = {}
        for name, rule in recipe.packages.items():
            for dep in rule.depends:
                if name not in by_name or dep not in by_name:
                    continue
                for decorator in by_name[name]:
                    for category in NEEDED_CATEGORIES:
                        decorator.descriptor.dependencies.setdefault(
                            category, set()).add(DependencyDescriptor(dep))
                added.setdefault(name, set()).add(dep)
        build_base = Path(getattr(args, 'build_base', None) or 'build_wasm').absolute()
        for name, deps in add_system_packages(
                decorators, recipe, build_base=build_base,
                known=known_package_names(args, decorators)).items():
            added.setdefault(name, set()).update(deps)
        if not added:
            return
        _extend_recursive_dependencies(decorators, added)
        decorators[:] = topological_order_decorators(decorators)


def known_package_names(args, decorators):
    """Get the names of the packages of the workspace and of the underlays."""
    known = {d.descriptor.name for d in decorators}
    for underlay in get_underlays(args):
        known |= underlay.packages()
    return known


def _extend_recursive_dependencies(decorators, added):
    """Add new edges (name -> deps) to every affected decorator."""
    recursive = {}
    for decorator in decorators:
        recursive[decorator.descriptor.name] = set(
            str(d) for d in decorator.recursive_dependencies)
    changed = True
    while changed:
        changed = False
        for name, deps in recursive.items():
            extra = set()
            for source in [name] + list(deps):
                for dep in added.get(source, ()):
                    extra.add(dep)
                    extra |= recursive.get(dep, set())
            extra.discard(name)
            if not extra <= deps:
                deps |= extra
                changed = True
    lookup = {d.descriptor.name: d.descriptor for d in decorators}
    for decorator in decorators:
        names = recursive[decorator.descriptor.name]
        existing = {str(d): d for d in decorator.recursive_dependencies}
        decorator.recursive_dependencies = [
            existing.get(n) or DependencyDescriptor(
                n, metadata={'origin': 'colcon-wasm recipe'})
            for n in sorted(names) if n in lookup or n in existing]


class WasmPackageSelection(PackageSelectionExtensionPoint):
    """Select the packages of a `--wasm` build (`colcon build --wasm`)."""

    # lowest priority: runs after the user's selection options
    PRIORITY = 10

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            PackageSelectionExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    def add_arguments(self, *, parser):  # noqa: D102
        add_wasm_arguments(parser)

    def check_parameters(self, *, args, pkg_names):  # noqa: D102
        # pure: the build and test verbs found Emscripten and set the
        # environment when they started (colcon_wasm.verb_start)
        if getattr(args, 'wasm', False):
            get_recipe(args)

    def select_packages(self, *, args, decorators):  # noqa: D102
        if not getattr(args, 'wasm', False):
            return
        recipe = get_recipe(args)
        _check_workspace_not_empty(args, decorators)
        _prefer_workspace_copies(decorators)
        left_out = set()
        for decorator in decorators:
            if decorator.selected:
                _select_one(decorator, recipe)
            if _never_built(decorator.descriptor, recipe):
                left_out.add(decorator.descriptor.name)
        _check_skipped_dependencies(decorators, recipe)
        _forget_left_out(decorators, left_out)
        _schedule_component_containers(args, decorators)
        _trim_unused_bundled(decorators, requested=set(
            (getattr(args, 'packages_up_to', None) or [])
            + (getattr(args, 'packages_select', None) or [])))
        known = known_package_names(args, decorators)
        problems = check_system_dependencies(decorators, recipe, known)
        if problems:
            raise SystemExit(exit_message(ColconWasmError(
                f'{len(problems)} system dependencies have no WebAssembly build:\n'
                + '\n'.join(f'  {p}' for p in problems))))
        emscripten = started_emscripten(args)
        settings = WasmSettings(args)
        for decorator in decorators:
            pkg = decorator.descriptor
            if not decorator.selected:
                continue
            if pkg.type in WASM_TYPES:
                wasm_type = WASM_TYPES[pkg.type]
            elif pkg.name in recipe.host_tools and \
                    HOST_TOOL_TYPE_PREFIX + pkg.type in HOST_TOOL_TYPES:
                wasm_type = HOST_TOOL_TYPE_PREFIX + pkg.type
            elif pkg.type in PYTHON_TYPES:
                wasm_type = PYTHON_TYPES[pkg.type]
            else:
                continue
            pkg.metadata[PLAN_KEY] = BuildPlan(
                original_type=pkg.type, recipe=recipe,
                rule=recipe.rule(pkg.name), emscripten=emscripten,
                settings=settings, host_tool=wasm_type.startswith(HOST_TOOL_TYPE_PREFIX),
                python_package=wasm_type in PYTHON_TYPES.values(),
                underlays=[u.base for u in get_underlays(args)],
                system_rule=pkg.metadata.get(SYSTEM_RULE_KEY),
                extra_cmake_args=system_cmake_args(recipe))
            pkg.type = wasm_type


def _check_workspace_not_empty(args, decorators):
    if any(not is_bundled(d.descriptor) for d in decorators):
        return
    paths = getattr(args, 'paths', None) or \
        getattr(args, 'base_paths', None) or ['.']
    raise SystemExit(exit_message(ColconWasmError(
        'no packages found in ' + ', '.join(f"'{p}'" for p in paths)
        + f" (from '{os.getcwd()}'); run it in a workspace whose src/ "
        'holds packages, or pass --base-paths / --paths')))


def _prefer_workspace_copies(decorators):
    workspace = {d.descriptor.name: d.descriptor for d in decorators
                 if not is_bundled(d.descriptor)}
    for decorator in decorators:
        pkg = decorator.descriptor
        if is_bundled(pkg) and pkg.name in workspace and decorator.selected:
            logger.info(
                f"Using the workspace copy of '{pkg.name}' in "
                f"'{workspace[pkg.name].path}' instead of the bundled one in "
                f"'{pkg.path}'")
            decorator.selected = False


def _select_one(decorator, recipe):
    """Unselect a package --wasm does not build."""
    pkg = decorator.descriptor
    reason = recipe.skip_reason(pkg.name)
    if reason:
        logger.info(f"Skipping '{pkg.name}' for --wasm: {reason}")
    elif pkg.type in WASM_TYPES:
        return
    elif pkg.name in recipe.host_tools:
        logger.info(
            f"Building host tool '{pkg.name}' ({pkg.type}) with its usual "
            'task: it runs on the host at configure time')
        return
    elif pkg.type in PYTHON_TYPES:
        return
    else:
        logger.info(
            f"Skipping '{pkg.name}' for --wasm: a '{pkg.type}' package, only "
            'CMake packages are built to WebAssembly and ament_python and python '
            'packages packed for Pyodide')
    decorator.selected = False


def _never_built(pkg, recipe):
    """Check if --wasm never builds a package (whatever the selection)."""
    if recipe.skip_reason(pkg.name):
        return True
    return pkg.type not in WASM_TYPES and pkg.type not in PYTHON_TYPES and \
        pkg.name not in recipe.host_tools


def _forget_left_out(decorators, left_out):
    """
    Remove the packages --wasm leaves out from everyone's dependencies.

    colcon expects every dependency of a job to be installed (it sources
    their environment); packages left out of a --wasm build never will be.
    Packages the user unselected stay: colcon expects them built already.
    """
    if not left_out:
        return
    for decorator in decorators:
        decorator.recursive_dependencies = [
            d for d in decorator.recursive_dependencies
            if str(d) not in left_out]


def _dependency_names(pkg):
    names = set()
    for category in NEEDED_CATEGORIES:
        names |= {str(d) for d in pkg.dependencies.get(category, ())}
    return names


def _check_skipped_dependencies(decorators, recipe):
    """
    Refuse a selected package that needs a package --wasm skips to build.

    Allowed, with a note: dependencies the recipe lets the package drop
    (`drop-depends`), dependencies only the package's Python part needs
    (`python-only` skips: rclpy, python_cmake_module), and run-only
    dependencies (a metapackage's members, a launch file's nodes), which are
    simply not there at run time. A Python package (``ament_python``) gets
    colcon-wasm's rclpy in place of rclpy.
    """
    problems = []
    for decorator in decorators:
        pkg = decorator.descriptor
        if not decorator.selected or (
                pkg.type not in WASM_TYPES and pkg.type not in PYTHON_TYPES):
            continue
        allowed = set(recipe.rule(pkg.name).drop_depends)
        build = {str(d) for d in pkg.dependencies.get('build', ())}
        skipped = {d for d in _dependency_names(pkg) if recipe.skip_reason(d)}
        if pkg.type in PYTHON_TYPES:
            provided = sorted(d for d in skipped if d in RUNTIME_PYTHON_PACKAGES)
            for dep in provided:
                logger.info(
                    f"Python package '{pkg.name}' uses {RUNTIME_PYTHON_PACKAGES[dep]} "
                    f"in place of '{dep}' ({recipe.skip_reason(dep)})")
            allowed |= set(provided)
        python_parts = sorted(
            d for d in skipped if d not in allowed and recipe.is_python_only(d))
        if python_parts:
            logger.info(
                f"Building '{pkg.name}' without "
                + ', '.join(f"'{d}'" for d in python_parts)
                + ': only its Python part needs them, and Python code is not '
                'built for WebAssembly (the C/C++ part is)')
            allowed |= set(python_parts)
        run_only = sorted(d for d in skipped - allowed if d not in build)
        if run_only:
            logger.info(
                f"'{pkg.name}' runs with "
                + ', '.join(f"'{d}' ({recipe.skip_reason(d)})" for d in run_only)
                + ', which --wasm does not build: they are not there at run time')
            allowed |= set(run_only)
        for dep in sorted(skipped - allowed):
            problems.append(
                f"  package '{pkg.name}' needs '{dep}' to build, which "
                f'--wasm skips ({recipe.skip_reason(dep)})')
    if problems:
        raise SystemExit(exit_message(ColconWasmError(
            f'{len(problems)} dependencies on packages that --wasm skips '
            '(remove the dependency, or allow dropping it in a recipe '
            "overlay given with --wasm-recipe: 'packages: {PKG: "
            "{drop-depends: [DEP]}}'):\n" + '\n'.join(problems))))


def _schedule_component_containers(args, decorators):
    """
    Build the stock component containers after every package with components.

    rclcpp_components' containers load components with dlopen natively;
    here they are linked again, from rclcpp_components' own sources, after
    every selected package that depends on rclcpp_components (and may
    register components), so that they host all of them. `--packages-skip
    colcon_wasm_component_containers` keeps the containers as they are.
    """
    containers = next(
        (d for d in decorators if d.descriptor.name == CONTAINERS_PACKAGE), None)
    if containers is None or not is_bundled(containers.descriptor):
        return
    hosts = [
        d for d in decorators
        if d.selected and d is not containers and 'rclcpp_components' in {
            str(dep) for dep in d.descriptor.dependencies.get('build', ())}]
    skipped = CONTAINERS_PACKAGE in (getattr(args, 'packages_skip', None) or [])
    if not hosts or skipped:
        containers.selected = False
        return
    names = sorted(d.descriptor.name for d in hosts)
    logger.info(
        f"Building '{CONTAINERS_PACKAGE}' (rclcpp_components' component_container, "
        '_mt and _isolated, hosting every component) after: ' + ', '.join(names))
    containers.selected = True
    containers.descriptor.dependencies.setdefault('build', set()).update(
        DependencyDescriptor(n) for n in names)
    _extend_recursive_dependencies(decorators, {CONTAINERS_PACKAGE: set(names)})
    decorators[:] = topological_order_decorators(decorators)


def _trim_unused_bundled(decorators, requested=()):
    """
    Build bundled packages only when a selected package needs them.

    Bundled packages the user names (`--packages-up-to wasm_cpp`) are kept,
    with what they depend on. The Zenoh gateway is built when zenoh-pico is
    (`zenoh_pico` selected): no package depends on it, `--zenoh` uses it.
    """
    selected = [d for d in decorators if d.selected]
    if all(is_bundled(d.descriptor) for d in selected):
        return  # the user selected bundled packages only
    if any(d.descriptor.name == GATEWAY_NEEDS for d in selected):
        requested = set(requested) | {GATEWAY_PACKAGE}
    recursive = {d.descriptor.name: {str(n) for n in d.recursive_dependencies}
                 for d in selected}
    needed = set(requested)
    for decorator in selected:
        if not is_bundled(decorator.descriptor) or \
                decorator.descriptor.name in requested or \
                decorator.descriptor.name == CONTAINERS_PACKAGE:
            needed |= recursive[decorator.descriptor.name]
    pending = list(needed)
    while pending:
        for dep in recursive.get(pending.pop(), ()):
            if dep not in needed:
                needed.add(dep)
                pending.append(dep)
    for decorator in selected:
        pkg = decorator.descriptor
        if is_bundled(pkg) and pkg.name not in needed and pkg.name != CONTAINERS_PACKAGE:
            logger.info(
                f"Skipping bundled package '{pkg.name}': no selected package "
                'depends on it')
            decorator.selected = False
