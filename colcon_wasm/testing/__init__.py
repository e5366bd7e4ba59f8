# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Tests of `--wasm` packages: built with `--wasm-tests`, run by `colcon test --wasm`.

* :mod:`colcon_wasm.testing.options`: `--wasm-tests [PKG...]`,
  `--wasm-fault-injection`, `--wasm-test-timeout`, and the CMake arguments
  they give a package (`BUILD_TESTING=ON`, toolchains/wasm-ros-tests.cmake);
* the link launcher makes every executable that links gtest or gmock a
  Node.js program (:mod:`colcon_wasm.link.test_link`): the host file
  system (`-sNODERAWFS=1`), the test's environment, and a `#!` line, so that
  CTest, ament's `run_test.py` or a shell run `test_foo.js` as they would run
  a native test;
* :mod:`colcon_wasm.task.test`: the `colcon test` task of the `wasm.*`
  package types (the stock CMake/ament task with Node.js, a default time
  limit, the recipe's not-applicable tests left out);
* :mod:`colcon_wasm.testing.results`: xUnit files for what `colcon
  test-result` would not see otherwise (tests CTest stopped after their
  time limit, tests that never ran, plain CTest tests, skipped linters and
  not-applicable tests, each with its reason).
"""
