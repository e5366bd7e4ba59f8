# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""What package selection hands to the wasm build task, per package."""

"""Descriptor metadata key holding the :class:`BuildPlan`."""
PLAN_KEY = 'colcon_wasm'


class BuildPlan:
    """How one package is built with `--wasm`."""

    def __init__(self, *, original_type, recipe, rule, emscripten, settings,
                 host_tool=False, python_package=False, underlays=(), system_rule=None,
                 extra_cmake_args=()):
        """
        Describe the wasm build of a package.

        :param str original_type: the package type before the switch to
          `wasm.*` (selects the stock colcon task that does the work)
        :param recipe: the :class:`colcon_wasm.recipe.Recipe`
        :param rule: the recipe's :class:`PackageRule` for this package
        :param emscripten: the :class:`colcon_wasm.toolchain.Emscripten`
          (None for verbs that do not build, e.g. `colcon list`)
        :param settings: the :class:`colcon_wasm.options.WasmSettings`
        :param bool host_tool: a recipe host tool (pure Python, built by its
          stock task for the host; no CMake arguments, no post-processing)
        :param bool python_package: an ``ament_python`` package packed for
          Pyodide (installed by its stock task, then given a manifest by
          :mod:`colcon_wasm.python_package`)
        :param underlays: install bases of the `--wasm` underlays, highest
          priority first
        :param system_rule: for a package built from Debian's source (a
          rosdep key), the recipe's :class:`SystemRule`
        :param extra_cmake_args: CMake arguments the package's system
          dependencies need (header-only libraries of the host)
        """
        self.original_type = original_type
        self.recipe = recipe
        self.rule = rule
        self.emscripten = emscripten
        self.settings = settings
        self.host_tool = host_tool
        self.python_package = python_package
        self.underlays = list(underlays)
        self.system_rule = system_rule
        self.extra_cmake_args = list(extra_cmake_args)
