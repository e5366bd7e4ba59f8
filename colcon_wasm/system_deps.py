# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
System dependencies (rosdep keys) of a `--wasm` build, checked before configure.

A dependency that names no package of the workspace or of an underlay is a
rosdep key. The recipe's `system` section (:mod:`colcon_wasm.recipe.system`)
says how each key is provided. This module

* orders the build: a key built from a workspace package, or from a Debian
  source package, makes its dependents wait for that package
  (:func:`add_system_packages`, before the user's selection);
* refuses, before anything is configured, a selected package that needs a
  key with no WebAssembly build, naming the package, the key and what to do
  (:func:`check_system_dependencies`);
* gives the CMake arguments of header-only keys used from the host
  (:func:`system_cmake_args`).
"""

from pathlib import Path

from colcon_core.dependency_descriptor import DependencyDescriptor
from colcon_core.package_decorator import PackageDecorator
from colcon_core.package_descriptor import PackageDescriptor

"""Descriptor metadata key: the system rule of a Debian-source package."""
SYSTEM_RULE_KEY = 'colcon_wasm_system_rule'

"""Folder (inside the build base) of the Debian-source packages."""
SYSTEM_SOURCES = Path('.colcon_wasm') / 'system'


def build_dependencies(pkg):
    """Get the names a package needs to build (colcon's 'build' category)."""
    return {str(d) for d in pkg.dependencies.get('build', ())}


def system_keys(pkg, known):
    """Get the build dependencies of a package that name no known package."""
    return sorted(d for d in build_dependencies(pkg) if d not in known)


def add_system_packages(decorators, recipe, *, build_base, known):
    """
    Order the build for the system keys packages need.

    For a `workspace` key, its dependents depend on that package; for a
    `debian-source` key, a package of that name is added to the workspace
    (its source is fetched when it is built, see
    :mod:`colcon_wasm.debian_source`).

    :param decorators: every package decorator (changed in place)
    :param known: names of the packages of the workspace and the underlays
    :returns: {package name: set of names it now depends on}
    """
    added = {}
    wanted = {}
    for decorator in decorators:
        pkg = decorator.descriptor
        for key in system_keys(pkg, known):
            rule = recipe.system.rule(key)
            if rule is None:
                continue
            if rule.kind == 'workspace' and rule.workspace in known:
                added.setdefault(pkg.name, set()).add(rule.workspace)
                for category in ('build', 'run'):
                    pkg.dependencies.setdefault(category, set()).add(
                        DependencyDescriptor(rule.workspace))
            elif rule.kind == 'debian-source':
                wanted[key] = rule
                added.setdefault(pkg.name, set()).add(key)
    for key, rule in sorted(wanted.items()):
        # the folder is filled when the package is built
        descriptor = PackageDescriptor(Path(build_base) / SYSTEM_SOURCES / key)
        descriptor.name = key
        descriptor.type = 'cmake'
        descriptor.metadata[SYSTEM_RULE_KEY] = rule
        decorator = PackageDecorator(descriptor)
        decorator.recursive_dependencies = []
        decorators.append(decorator)
    return added


def system_cmake_args(recipe):
    """
    Get the CMake arguments of the header-only keys used from the host.

    They are given to every package: a package can need Eigen through a
    dependency's exported CMake config (orocos_kdl_vendor) without naming
    the key itself.
    """
    args = []
    for rule in recipe.system.rules.values():
        if rule.kind == 'host-headers' and Path(rule.check).exists():
            args += [a for a in rule.cmake_args if a not in args]
    return args


def _rosdep_debian_package(key):
    """
    Ask rosdep which Debian package a key is (None when rosdep cannot tell).

    rosdep answers from its sources cache (`rosdep update`); without one,
    or for a key it does not know, this gives None.
    """
    try:
        from rosdep2 import create_default_installer_context
        from rosdep2.lookup import RosdepLookup
        from rosdep2.rospkg_loader import DEFAULT_VIEW_KEY
        from rosdep2.sources_list import SourcesListLoader
        context = create_default_installer_context()
        os_name, os_version = context.get_os_name_and_version()
        lookup = RosdepLookup.create_from_rospkg(
            sources_loader=SourcesListLoader.create_default())
        view = lookup.get_rosdep_view(DEFAULT_VIEW_KEY)
        definition = view.lookup(key)
        installer_key, rule = definition.get_rule_for_platform(
            os_name, os_version, context.get_os_installer_keys(os_name),
            context.get_default_os_installer_key(os_name))
        installer = context.get_installer(installer_key)
        packages = installer.resolve(rule)
        return ' '.join(packages) if packages else None
    except Exception:  # noqa: B902 (no cache, unknown key, another platform)
        return None


def describe_missing(pkg_name, key, rule=None):
    """Say what a package needs and what to do, for a name with no build."""
    debian = (rule.debian if rule is not None else None) or _rosdep_debian_package(key)
    system = f' (rosdep: {debian})' if debian else ''
    return (
        f"package '{pkg_name}' needs '{key}'{system}, which is neither a package of the "
        'workspace or its underlays nor a rosdep key with a WebAssembly build: add its '
        f"sources to the workspace (a package named '{key}'), describe the rosdep key "
        f"in a recipe overlay ('system: {{{key}: ...}}', recipes/schema.md), or skip the "
        f"package (recipe: 'skip: {{{pkg_name}: REASON}}', or --packages-skip {pkg_name})")


def check_system_dependencies(decorators, recipe, known):
    """
    Check the system keys of the selected packages.

    :param known: names of the packages of the workspace and the underlays
    :returns: a list of problems (one line each); empty when all is well
    """
    problems = []
    for decorator in decorators:
        pkg = decorator.descriptor
        if not decorator.selected or pkg.metadata.get(SYSTEM_RULE_KEY) or \
                not pkg.type.startswith('ros.'):
            # a plain CMake package's dependencies are its find_package()
            # names (Threads, PythonInterp), not rosdep keys
            continue
        for key in system_keys(pkg, known):
            if recipe.skip_reason(key):
                continue  # checked with the skipped packages
            rule = recipe.system.rule(key)
            if rule is None:
                problems.append(describe_missing(pkg.name, key))
            elif rule.kind == 'workspace' and rule.workspace not in known:
                problems.append(
                    f"package '{pkg.name}' needs rosdep key '{key}', which colcon-wasm "
                    f"builds from the package '{rule.workspace}': add its source to the "
                    f'workspace (its upstream repository, e.g. from recipes/humble.repos)')
            elif rule.kind == 'host-headers' and not Path(rule.check).exists():
                install = f'`apt-get install {rule.debian}`' if rule.debian else \
                    f"install what provides '{rule.check}'"
                problems.append(
                    f"package '{pkg.name}' needs rosdep key '{key}', header-only and used "
                    f"from the host, but '{rule.check}' is missing: {install}")
    return problems
