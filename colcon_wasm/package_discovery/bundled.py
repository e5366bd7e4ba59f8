# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Add the packages shipped with colcon-wasm to `--wasm` builds."""

from colcon_core.logging import colcon_logger
from colcon_core.package_discovery import PackageDiscoveryExtensionPoint
from colcon_core.package_identification import identify
from colcon_core.plugin_system import satisfies_version
from colcon_wasm import resources
from colcon_wasm.underlay import get_underlays

logger = colcon_logger.getChild(__name__)

"""Descriptor metadata key marking a package shipped with colcon-wasm."""
BUNDLED_KEY = 'colcon_wasm_bundled'


def bundled_package_paths():
    """List the folders of the bundled packages (`packages/*`)."""
    folder = resources.path('packages')
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.is_dir())


def is_bundled(descriptor):
    """Check if a package descriptor is one of the bundled packages."""
    return bool(descriptor.metadata.get(BUNDLED_KEY))


class BundledPackageDiscovery(PackageDiscoveryExtensionPoint):
    """Discover the middleware packages shipped with colcon-wasm."""

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(
            PackageDiscoveryExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    def has_parameters(self, *, args):  # noqa: D102
        # None: this extension has no parameters of its own, so colcon
        # consults it both with and without --base-paths / --paths
        return None

    def discover(self, *, args, identification_extensions):  # noqa: D102
        if not getattr(args, 'wasm', False):
            return set()
        underlays = get_underlays(args)
        installed = {}
        for underlay in reversed(underlays):
            installed.update({name: underlay for name in underlay.packages()})
        descriptors = set()
        for path in bundled_package_paths():
            result = identify(identification_extensions, str(path))
            if not result or result is True:
                continue
            if result.name in installed:
                # the middleware comes from the underlay, as rmw_fastrtps_cpp
                # comes from /opt/ros/humble for a native overlay
                logger.info(
                    f"Using '{result.name}' of the underlay "
                    f"'{installed[result.name].base}' (not the bundled copy)")
                continue
            result.metadata[BUNDLED_KEY] = True
            logger.debug(
                f"Bundled package '{result.name}' in '{result.path}'")
            descriptors.add(result)
        return descriptors
