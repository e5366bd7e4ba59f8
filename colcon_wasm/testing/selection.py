# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Order test tooling before the tests that use it (`--wasm-tests`, `colcon test`).

A package's tests find googletest through ament_cmake_gtest, which finds
gtest_vendor's sources; package.xml files name ament_cmake_gtest only. When
ament_cmake_gtest comes from an underlay (a `--wasm` install base with
Humble's core) and gtest_vendor is built in the workspace, colcon sees no
edge between the test package and gtest_vendor, and may build both at once.
This extension adds those edges, as colcon-wasm's recipe `depends` does for
other packages.
"""

from colcon_core.dependency_descriptor import DependencyDescriptor
from colcon_core.logging import colcon_logger
from colcon_core.package_selection import PackageSelectionExtensionPoint
from colcon_core.plugin_system import satisfies_version
from colcon_core.topological_order import topological_order_decorators

logger = colcon_logger.getChild(__name__)

"""Test helper packages -> the vendor packages they take the sources from."""
TOOLING = {
    'ament_cmake_gtest': ('gtest_vendor',),
    'ament_cmake_gmock': ('gmock_vendor', 'gtest_vendor'),
}


def tests_requested(args):
    """Check if the command builds tests (`--wasm-tests`) or runs them (`colcon test`)."""
    return getattr(args, 'wasm', False) and (
        getattr(args, 'wasm_tests', None) is not None or
        getattr(args, 'verb_name', None) == 'test')


class WasmTestDependencyPackageSelection(PackageSelectionExtensionPoint):
    """Add test tooling dependencies (gtest_vendor, gmock_vendor) before the user's selection."""

    # after the recipe's dependencies (1000), before the user's selection
    PRIORITY = 950

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            PackageSelectionExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    def select_packages(self, *, args, decorators):  # noqa: D102
        if not tests_requested(args):
            return
        from colcon_wasm.package_selection.wasm import _extend_recursive_dependencies
        names = {d.descriptor.name for d in decorators}
        added = {}
        for decorator in decorators:
            pkg = decorator.descriptor
            depends = {str(d) for deps in pkg.dependencies.values() for d in deps}
            for helper, vendors in TOOLING.items():
                if helper not in depends:
                    continue
                for vendor in vendors:
                    if vendor in names and vendor != pkg.name and vendor not in depends:
                        pkg.dependencies.setdefault('test', set()).add(
                            DependencyDescriptor(vendor))
                        added.setdefault(pkg.name, set()).add(vendor)
        if not added:
            return
        for name, vendors in sorted(added.items()):
            logger.debug(f"'{name}' tests need " + ', '.join(sorted(vendors)))
        _extend_recursive_dependencies(decorators, added)
        decorators[:] = topological_order_decorators(decorators)
