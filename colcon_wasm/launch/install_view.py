# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""What programs see of their install spaces when ``run``, ``launch`` or the page starts them.

Every program gets a read-only view of each install base at its real path
(wasm_js ``Runtime.spawn({mounts})``, ``packages/wasm_js/src/view_fs.mjs``)
and ``AMENT_PREFIX_PATH`` naming the package prefixes in them, highest
priority first, so that ament_index_cpp, pluginlib and
``get_package_share_directory()`` find what they find natively.
"""

from pathlib import Path

RESOURCE_INDEX = Path('share') / 'ament_index' / 'resource_index'
PACKAGES_INDEX = RESOURCE_INDEX / 'packages'
AMENT_PREFIX_PATH = 'AMENT_PREFIX_PATH'


def view_bases(install_space, underlays=()):
    """
    Return the install bases programs see, highest priority first.

    :param install_space: the InstallSpace the command was given: its base,
      then the underlays it was built on (``InstallSpace.bases``)
    :param underlays: more install bases below those (highest priority first)
    :returns: absolute Paths, each once
    """
    bases = []
    for base in list(install_space.bases) + [Path(u) for u in underlays]:
        base = base.absolute()
        if base not in bases:
            bases.append(base)
    return bases


def ament_prefixes(bases):
    """
    Return the package prefixes of install bases, as ``AMENT_PREFIX_PATH`` lists them.

    A merged install (``<base>/share/ament_index/resource_index/packages/``
    has markers) is one prefix, ``<base>``; in an isolated install each
    ``<base>/<pkg>`` holding its marker
    ``share/ament_index/resource_index/packages/<pkg>`` is one, by name.
    Bases keep their order (overlay first); a prefix appears once.

    :returns: a list of absolute path strings
    """
    prefixes = []
    for base in bases:
        base = Path(base)
        if not base.is_dir():
            continue
        merged = base / PACKAGES_INDEX
        if merged.is_dir() and any(merged.iterdir()):
            prefixes.append(base)
        for child in sorted(base.iterdir()):
            if (child / PACKAGES_INDEX / child.name).is_file():
                prefixes.append(child)
    unique = []
    for prefix in prefixes:
        if str(prefix) not in unique:
            unique.append(str(prefix))
    return unique


def program_environment(env, prefixes):
    """
    Return a process' environment with ``AMENT_PREFIX_PATH`` added.

    A value the user set (a launch file's ``<env>``) is kept as it is; so is
    an environment when there are no prefixes.
    """
    env = dict(env or {})
    if AMENT_PREFIX_PATH not in env and prefixes:
        env[AMENT_PREFIX_PATH] = ':'.join(prefixes)
    return env


def view_mounts(bases):
    """Describe the read-only views of ``bases`` for ``Runtime.spawn({mounts})`` (Node.js)."""
    return [{'path': str(base)} for base in bases]
