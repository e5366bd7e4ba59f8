# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The link report beside each executable, and when its link is stale.

CMake relinks an executable when one of *its* inputs changes. The archives
the link launcher adds (plugins, components) and the ament index entries
that chose them are not CMake's: the report records them, and before a
package is built again :func:`stale_links` finds the executables whose
added inputs changed (a plugin rebuilt, a component registered), so that
the build removes them and CMake links them again.
"""

import hashlib
import json
import os

from colcon_wasm.link import ament_index

"""Suffix of the report written next to a linked `.js`."""
REPORT_SUFFIX = '.colcon_wasm_link.json'

REPORT_SCHEMA = 2


def launcher_digest():
    """Hash the link launcher's own code: another launcher links differently."""
    digest = hashlib.sha256()
    folder = os.path.dirname(os.path.abspath(__file__))
    for name in sorted(os.listdir(folder)):
        if name.endswith('.py'):
            with open(os.path.join(folder, name), 'rb') as handle:
                digest.update(name.encode() + b'\0' + handle.read())
    return digest.hexdigest()


def file_stamps(paths):
    """Describe files by path, size and modification time."""
    stamps = []
    for path in paths:
        try:
            status = os.stat(path)
            stamps.append([path, status.st_size, status.st_mtime_ns])
        except OSError:
            stamps.append([path, None, None])
    return stamps


def index_fingerprint(prefixes, base_classes, hosts_components):
    """
    Hash the ament index entries that decide what a link adds.

    :param prefixes: the package prefixes of the install chain
    :param base_classes: the pluginlib base classes the executable loads
    :param bool hosts_components: True for a component container
    """
    chosen = []
    if base_classes:
        chosen += sorted(
            json.dumps(p.to_json(), sort_keys=True)
            for p in ament_index.plugins(prefixes) if p.base in base_classes)
    if hosts_components:
        chosen += sorted(json.dumps(c.to_json(), sort_keys=True)
                         for c in ament_index.components(prefixes))
    return hashlib.sha256('\n'.join(chosen).encode()).hexdigest()


def read_report(path):
    """Read a link report (None when missing, unreadable or of another schema)."""
    try:
        with open(path, encoding='utf-8') as handle:
            report = json.load(handle)
    except (OSError, ValueError):
        return None
    return report if report.get('schema') == REPORT_SCHEMA else None


def stale_reason(report, bases):
    """
    Say why an executable's link is out of date, or None when it is not.

    :param report: the executable's link report
    :param bases: the install chain of the build (current base first)
    """
    inputs = report.get('inputs')
    if not inputs or inputs.get('launcher') != launcher_digest():
        return 'it was linked by another colcon-wasm'
    for path, size, mtime in inputs.get('archives', []):
        current = file_stamps([path])[0]
        if current[1:] != [size, mtime]:
            return f"'{path}' changed"
    fingerprint = index_fingerprint(
        ament_index.package_prefixes(bases), inputs.get('plugin_base_classes', []),
        inputs.get('hosts_components', False))
    if fingerprint != inputs.get('index'):
        return 'the plugins or components of the ament index changed'
    return None


def stale_links(build_folder, bases):
    """
    Find the executables of a build folder whose added link inputs changed.

    :returns: a list of (linked `.js` path, reason)
    """
    stale = []
    for root, dirs, files in os.walk(build_folder):
        dirs[:] = [d for d in dirs if d != 'CMakeFiles']
        for name in files:
            if not name.endswith(REPORT_SUFFIX):
                continue
            report = read_report(os.path.join(root, name))
            output = os.path.join(root, name[:-len(REPORT_SUFFIX)])
            if not os.path.exists(output):
                continue
            reason = stale_reason(report, bases) if report is not None else \
                'it was linked by another colcon-wasm'
            if reason:
                stale.append((output, reason))
    return stale
