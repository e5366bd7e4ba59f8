# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Test executables of `--wasm-tests` builds: Node.js programs run like native tests.

A test harness runs a native test as a program: CTest, ament's
`run_test.py` (`--command test_foo --gtest_output=xml:...`), a shell. In a
`--wasm-tests` build the link launcher makes every executable that links
gtest or gmock (or that is linked with `-sNODERAWFS=1`) such a program:

* `-sNODERAWFS=1`: the test's file system is the host's, so result files
  (`--gtest_output=xml:PATH`), data files next to the test and the working
  directory are the real ones (the default, MEMFS, would keep them in the
  program's memory);
* `--pre-js toolchains/test/node_test_pre.js`: the test sees the process'
  environment (the `ENV` of `ament_add_gtest`) and reads its `.wasm` from
  the file system (Node's `fetch` cannot read a path);
* after the link: a `#!/usr/bin/env node` line and the executable bit, so
  `./test_foo.js` runs (Node.js skips that line, also when a pthread worker
  evaluates the glue).

These executables run in Node.js only (NODERAWFS); installed nodes of the
same build are not affected.

Stays importable with site packages off (see :mod:`colcon_wasm.link`).
"""

import os
import stat
import subprocess

"""Archives that make a link a test executable (gtest, gmock)."""
TEST_ARCHIVES = ('libgtest.a', 'libgtest_main.a', 'libgmock.a', 'libgmock_main.a')

"""The link flag that marks any executable as a Node.js test program."""
NODERAWFS = '-sNODERAWFS=1'

SHEBANG = b'#!/usr/bin/env node\n'


def is_test_link(link):
    """Check if a link command makes a test executable (gtest/gmock, or NODERAWFS)."""
    if NODERAWFS in link.arguments:
        return True
    return any(os.path.basename(a) in TEST_ARCHIVES for a in link.archives)


def test_link_flags(link, pre_js):
    """Get the flags added to a test executable's link."""
    flags = [] if NODERAWFS in link.arguments else [NODERAWFS]
    return flags + ['--pre-js', pre_js]


def make_runnable(path):
    """Give a linked test `.js` its `#!` line and the executable bit."""
    with open(path, 'rb') as handle:
        text = handle.read()
    if not text.startswith(b'#!'):
        with open(path, 'wb') as handle:
            handle.write(SHEBANG + text)
    mode = os.stat(path).st_mode
    os.chmod(path, mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)


def run_test_link(command, output):
    """Run the link of a test executable, then make its output runnable."""
    completed = subprocess.run(command)
    if completed.returncode == 0 and os.path.isfile(output):
        make_runnable(output)
    return completed.returncode
