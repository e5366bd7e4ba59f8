# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The plugins and components the ament index of an install chain declares.

An install chain is the install base being built followed by its underlays
(highest priority first). Each base holds package prefixes: the base itself
(merged install) and `<base>/<pkg>` (isolated install). A package found in
several prefixes is taken from the first, as `AMENT_PREFIX_PATH` orders them.
"""

import os
import xml.etree.ElementTree as ElementTree

from colcon_wasm.error import ColconWasmError

RESOURCE_INDEX = os.path.join('share', 'ament_index', 'resource_index')

"""The resource type of pluginlib's plugin descriptions for a base package."""
PLUGIN_RESOURCE_SUFFIX = '__pluginlib__plugin'


class AmentIndexError(ColconWasmError):
    """A broken ament index entry or plugin description (named in the text)."""


def package_prefixes(bases):
    """
    List the package prefixes of an install chain.

    :param bases: install bases, highest priority first
    :returns: a list of prefix folders, highest priority first
    """
    prefixes = []
    for base in bases:
        if os.path.isdir(os.path.join(base, RESOURCE_INDEX)):
            prefixes.append(base)
        try:
            children = sorted(os.listdir(base))
        except OSError:
            continue
        for child in children:
            prefix = os.path.join(base, child)
            if os.path.isdir(os.path.join(prefix, RESOURCE_INDEX)):
                prefixes.append(prefix)
    return prefixes


def resources(prefixes, resource_type):
    """
    Get the entries of one resource type: {package: (prefix, content)}.

    The first prefix that registers a package wins.
    """
    found = {}
    for prefix in prefixes:
        folder = os.path.join(prefix, RESOURCE_INDEX, resource_type)
        try:
            names = sorted(os.listdir(folder))
        except OSError:
            continue
        for name in names:
            if name.startswith('.') or name in found:
                continue
            try:
                with open(os.path.join(folder, name), encoding='utf-8') as handle:
                    found[name] = (prefix, handle.read())
            except OSError:
                continue
    return found


class Plugin:
    """One `<class>` of a pluginlib plugin description."""

    def __init__(self, *, name, type_, base, library, package, description_file):
        """Describe a plugin class and the library that holds it."""
        self.name = name
        self.type = type_
        self.base = base
        self.library = library
        self.package = package
        self.description_file = description_file

    def to_json(self):
        """Describe the plugin for the link report."""
        return {'name': self.name, 'type': self.type, 'base': self.base,
                'library': self.library, 'package': self.package}


def _plugin_description_files(prefix, content):
    """Get the plugin XML files an index entry names (one path per line)."""
    files = []
    for line in content.splitlines():
        line = line.strip()
        if line:
            files.append(line if os.path.isabs(line) else os.path.join(prefix, line))
    return files


def read_plugin_description(path, package):
    """
    Read a pluginlib plugin description (`<library>` or `<class_libraries>`).

    :raises AmentIndexError: naming the file when it cannot be parsed
    :rtype: list of Plugin
    """
    try:
        root = ElementTree.parse(path).getroot()
    except (OSError, ElementTree.ParseError) as e:
        raise AmentIndexError(
            f"cannot read the plugin description '{path}' of package "
            f"'{package}': {e}") from e
    libraries = [root] if root.tag == 'library' else root.findall('library')
    plugins = []
    for library in libraries:
        library_path = library.get('path')
        if not library_path:
            continue
        for element in library.findall('class'):
            type_ = element.get('type')
            base = element.get('base_class_type')
            if not type_ or not base:
                continue
            plugins.append(Plugin(
                name=element.get('name') or type_, type_=type_, base=base,
                library=library_path, package=package, description_file=path))
    return plugins


def plugins(prefixes):
    """Get every plugin the chain's ament index declares."""
    found = []
    resource_types = set()
    for prefix in prefixes:
        folder = os.path.join(prefix, RESOURCE_INDEX)
        try:
            resource_types |= {n for n in os.listdir(folder)
                               if n.endswith(PLUGIN_RESOURCE_SUFFIX)}
        except OSError:
            continue
    for resource_type in sorted(resource_types):
        for package, (prefix, content) in resources(prefixes, resource_type).items():
            for path in _plugin_description_files(prefix, content):
                found += read_plugin_description(path, package)
    return found


class Component:
    """One node class registered with rclcpp_components."""

    def __init__(self, *, class_name, library, package):
        """Describe a component class and its library (as the index names it)."""
        self.class_name = class_name
        self.library = library
        self.package = package

    def to_json(self):
        """Describe the component for the link report."""
        return {'class': self.class_name, 'library': self.library,
                'package': self.package}


def components(prefixes, resource_type='rclcpp_components'):
    """Get every component the chain's ament index registers."""
    found = []
    for package, (prefix, content) in resources(prefixes, resource_type).items():
        for line in content.splitlines():
            parts = line.strip().split(';')
            if len(parts) >= 2 and parts[0]:
                found.append(Component(
                    class_name=parts[0], library=parts[1], package=package))
    return found


def library_stem(name):
    """
    Reduce a library name or path to its stem: `lib/libfoo.so` -> `foo`.

    pluginlib descriptions and the component index name libraries in
    several forms (`foo`, `libfoo`, `lib/libfoo.so`, `libfoo.a`).
    """
    base = os.path.basename(name)
    for suffix in ('.so', '.a', '.dylib', '.dll', '.lib'):
        if base.endswith(suffix):
            base = base[:-len(suffix)]
            break
    if base.startswith('lib') and len(base) > 3:
        base = base[3:]
    return base
