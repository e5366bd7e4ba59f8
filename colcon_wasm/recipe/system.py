# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The `system` section of a recipe: how each rosdep key is provided.

A ROS package names system libraries by rosdep key (`eigen`, `tinyxml`,
`libconsole-bridge-dev`). Natively rosdep installs them; for WebAssembly a
key is one of:

* `workspace: PKG` -- built from a package of the workspace (an upstream
  source placed there, e.g. `libconsole-bridge-dev` -> `console_bridge`);
* `host-headers` -- a header-only library used from the host, e.g. Eigen
  from Debian's `libeigen3-dev` (`check` names a file that must exist,
  `cmake-args` tell CMake where it is);
* `debian-source` -- built by colcon-wasm from Debian's source package with
  Emscripten (:mod:`colcon_wasm.system_packages`);
* `host-tool` -- a program the build runs on the host (cmake, git, python3);
* `builtin` -- provided by Emscripten's own libraries (libatomic).

Every other key a selected package needs to build is an error before
configure (:mod:`colcon_wasm.system_check`).
"""

from fnmatch import fnmatchcase

"""The ways a rosdep key is provided (exactly one per entry)."""
KINDS = ('workspace', 'host-headers', 'debian-source', 'host-tool', 'builtin')

SYSTEM_KEYS = KINDS + ('debian', 'note')
HOST_HEADERS_KEYS = ('check', 'cmake-args')
DEBIAN_SOURCE_KEYS = ('package', 'version', 'build', 'cmake-args')


class SystemRule:
    """How the recipe provides one rosdep key (or keys matching a glob)."""

    def __init__(self, key, kind, *, origin):
        """
        Describe a rosdep key.

        :param str key: the key or a glob
        :param str kind: one of :data:`KINDS`
        :param str origin: `recipe-file:line`, for messages
        """
        self.key = key
        self.kind = kind
        self.origin = origin
        self.workspace = None      # workspace: the package name
        self.reason = None         # host-tool, builtin: why
        self.check = None          # host-headers: a file that must exist
        self.cmake_args = []       # host-headers, debian-source
        self.debian = None         # the Debian binary package of the key
        self.source_package = None  # debian-source: Debian's source package
        self.source_version = None  # debian-source: a version prefix to expect
        self.build_file = None     # debian-source: CMakeLists.txt to use (Path)
        self.note = None

    def describe(self):
        """Describe how the key is provided, for messages."""
        if self.kind == 'workspace':
            return f"built from the workspace package '{self.workspace}'"
        if self.kind == 'host-headers':
            return f'headers of the host ({self.debian or self.check})'
        if self.kind == 'debian-source':
            return f"built from Debian's source package '{self.source_package}'"
        return self.reason or self.kind


class SystemRules:
    """The `system` entries of a recipe and its overlays (later ones win)."""

    def __init__(self):
        """Start with no entries."""
        self.rules = {}

    def update(self, rules):
        """Add or replace entries."""
        self.rules.update(rules)

    def rule(self, key):
        """
        Get the rule of a rosdep key: its own entry, else the first glob.

        :returns: the :class:`SystemRule` or None when the recipe does not
          know the key
        """
        if key in self.rules:
            return self.rules[key]
        for pattern, rule in self.rules.items():
            if fnmatchcase(key, pattern):
                return rule
        return None

    def debian_sources(self):
        """Get the entries built from Debian's source packages."""
        return [r for r in self.rules.values() if r.kind == 'debian-source']


def matches(pattern, key):
    """Check if a `system` entry (a key or glob) names a key."""
    return pattern == key or fnmatchcase(key, pattern)
