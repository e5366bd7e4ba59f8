# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The `wasm.*` build task: the stock colcon task plus the wasm steps."""

import json
from pathlib import Path
import shutil

from colcon_core.logging import colcon_logger
from colcon_core.plugin_system import satisfies_version
from colcon_core.task import get_task_extension
from colcon_core.task import TaskExtensionPoint
from colcon_wasm import debian_source
from colcon_wasm.build_plan import PLAN_KEY
from colcon_wasm.error import ColconWasmError
from colcon_wasm.error import exit_message
from colcon_wasm.link.report import stale_links
from colcon_wasm.options import cmake_arguments
from colcon_wasm.patch import prepare_patched_source
from colcon_wasm.postprocess import postprocess_package
from colcon_wasm.python_package import pack_python_package
from colcon_wasm.task.stamp import build_inputs
from colcon_wasm.task.stamp import is_up_to_date
from colcon_wasm.task.stamp import remove_stamp
from colcon_wasm.task.stamp import write_stamp
from colcon_wasm.underlay import underlay_stamps

logger = colcon_logger.getChild(__name__)

"""Folder (inside the build base) holding patched copies of sources."""
PATCHED_SOURCES = Path('.colcon_wasm') / 'source'

"""File in a package's build folder recording the toolchain settings."""
SETTINGS_FILE = 'colcon_wasm_settings.json'


def empty_build_folder(path):
    """Remove everything inside a package's build folder, keeping the folder."""
    if not path.is_dir():
        return
    for child in path.iterdir():
        if child.is_dir() and not child.is_symlink():
            shutil.rmtree(child)
        else:
            child.unlink()


def patched_source_folder(build_base, pkg_name):
    """Get where the patched copy of a package's source is kept."""
    return Path(build_base).parent / PATCHED_SOURCES / pkg_name


class WasmBuildTask(TaskExtensionPoint):
    """
    Build CMake, ros.cmake and ament_cmake packages to WebAssembly.

    The stock colcon task of the package's original type does the work; this
    task adds the toolchain, patches and post-processing around it, and
    skips a package whose last build is up to date
    (:mod:`colcon_wasm.task.stamp`). Recipe host tools (pure Python) get the
    up-to-date check only.
    """

    def __init__(self):  # noqa: D107
        super().__init__()
        satisfies_version(TaskExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')

    async def build(self):  # noqa: D102
        pkg = self.context.pkg
        args = self.context.args
        plan = pkg.metadata.get(PLAN_KEY)
        if plan is None or plan.emscripten is None:
            logger.error(
                f"Package '{pkg.name}' has type '{pkg.type}' but no --wasm "
                'build plan: build it with `colcon build --wasm`')
            return 1
        stock = get_task_extension(
            'colcon_core.task.build', plan.original_type)
        if stock is None:
            logger.error(
                f"No task extension to build a '{plan.original_type}' "
                f"package ('{pkg.name}'); is colcon-cmake / colcon-ros "
                'installed?')
            return 1

        if plan.host_tool:
            return await self._build_host_tool(stock, plan)
        if plan.python_package:
            return await self._build_python_package(stock, plan)

        args.cmake_args = cmake_arguments(
            emscripten=plan.emscripten, settings=plan.settings,
            install_base=self._install_base(args), rule=plan.rule,
            project_name=pkg.name,
            build_base=Path(args.build_base).parent,
            underlays=plan.underlays) + plan.extra_cmake_args + \
            (plan.system_rule.cmake_args if plan.system_rule else []) + \
            list(args.cmake_args or [])
        patches = self._patches(pkg, plan)
        inputs = build_inputs(
            args=args, source=Path(args.path), patches=patches,
            settings={'wasm': plan.settings.describe([]),
                      'emscripten': plan.emscripten.describe(),
                      'underlays': underlay_stamps(plan.underlays)},
            dependencies=self.context.dependencies)
        if self._up_to_date(inputs):
            return 0

        try:
            if plan.system_rule is not None:
                self._prepare_system_source(args, plan.system_rule)
            self._prepare_source(pkg, args, patches)
        except ColconWasmError as e:
            logger.error(exit_message(e))
            return 1
        self._clean_cache_on_new_settings(args, plan)
        self._relink_stale_executables(args, plan)

        stock.set_context(context=self.context)
        rc = await stock.build()
        if rc:
            return rc
        if self._relink_stale_executables(args, plan):
            # the package's own plugins or components only reach the ament
            # index with its install: link what loads them once more
            rc = await stock.build()
            if rc:
                return rc

        self.progress('wasm')
        try:
            postprocess_package(
                pkg_name=pkg.name,
                pkg_version=pkg.metadata.get('version'),
                build_base=args.build_base,
                install_prefix=args.install_base,
                emscripten=plan.emscripten.describe(),
                recipe=plan.recipe.describe(),
                flags=plan.settings.describe(args.cmake_args))
        except ColconWasmError as e:
            logger.error(exit_message(e))
            return 1
        write_stamp(args.build_base, inputs)
        return 0

    async def _build_host_tool(self, stock, plan):
        """Build a recipe host tool with its stock task, unless up to date."""
        return await self._build_with_stock_task(stock, {'host_tool': plan.original_type})

    async def _build_python_package(self, stock, plan):
        """
        Install an ``ament_python`` package with its stock task and pack it for Pyodide.

        Its modules run in Pyodide as they are installed; the manifest
        (:mod:`colcon_wasm.python_package`) lists its entry points.
        """
        return await self._build_with_stock_task(
            stock, {'python_package': plan.original_type, 'recipe': plan.recipe.describe()},
            then=lambda: self._pack_python_package(plan))

    async def _build_with_stock_task(self, stock, settings, then=None):
        """
        Build with the stock task alone (no toolchain), unless up to date.

        :param settings: what the build depends on besides the sources (in its stamp)
        :param then: run after the stock build; returns the exit code
        """
        args = self.context.args
        inputs = build_inputs(
            args=args, source=Path(args.path), patches=[], settings=settings,
            dependencies=self.context.dependencies)
        if self._up_to_date(inputs):
            return 0
        stock.set_context(context=self.context)
        rc = await stock.build()
        if not rc and then is not None:
            rc = then()
        if rc:
            return rc
        write_stamp(args.build_base, inputs)
        return 0

    def _pack_python_package(self, plan):
        """Write the manifest of an installed ``ament_python`` package; the exit code."""
        pkg = self.context.pkg
        self.progress('wasm')
        try:
            manifest = pack_python_package(
                pkg_name=pkg.name, pkg_version=pkg.metadata.get('version'),
                install_prefix=self.context.args.install_base, recipe=plan.recipe.describe())
        except ColconWasmError as e:
            logger.error(exit_message(e))
            return 1
        names = ', '.join(e['name'] for e in manifest['executables']) or 'no entry points'
        logger.info(f"Packed Python package '{pkg.name}' for Pyodide ({names})")
        return 0

    def _up_to_date(self, inputs):
        """Check the stamp of the last build; forget it when outdated."""
        pkg = self.context.pkg
        args = self.context.args
        up_to_date, reason = is_up_to_date(args, pkg.name, inputs)
        if up_to_date:
            logger.info(
                f"'{pkg.name}' is up to date (nothing changed since its last "
                '--wasm build): skipping it')
            self.progress('up to date')
            return True
        logger.debug(f"Building '{pkg.name}': {reason}")
        remove_stamp(args.build_base)
        return False

    def _prepare_system_source(self, args, rule):
        """
        Put the source of a rosdep key built from Debian's source in place.

        The unpacked source (cached, :mod:`colcon_wasm.debian_source`) is
        copied to the package's folder in the build base, with the recipe's
        CMakeLists.txt when it gives one.
        """
        self.progress('source')
        source = debian_source.fetch(
            rule.source_package, version_prefix=rule.source_version)
        destination = Path(args.path)
        build_file = rule.build_file.read_text() if rule.build_file else ''
        stamp = f'{source}\n{build_file}'
        marker = destination / '.colcon_wasm_source'
        if not (marker.is_file() and marker.read_text() == stamp):
            logger.info(
                f"Building rosdep key '{rule.key}' from Debian's source package "
                f"'{source.name}' ('{source}')")
            if destination.exists():
                shutil.rmtree(destination)
            shutil.copytree(source, destination, symlinks=True,
                            ignore=shutil.ignore_patterns('COLCON_IGNORE'))
            if rule.build_file:
                upstream = destination / 'CMakeLists.txt'
                if upstream.is_file():
                    upstream.rename(destination / 'CMakeLists.upstream.txt')
                (destination / 'CMakeLists.txt').write_text(build_file)
            marker.write_text(stamp)
        args.path = str(destination)

    def _patches(self, pkg, plan):
        """Get the recipe's patch files for this package version."""
        version = pkg.metadata.get('version')
        return [p.file for p in plan.rule.patches if p.applies_to(version)]

    def _prepare_source(self, pkg, args, patches):
        """Point the build at a patched copy when the recipe has patches."""
        if not patches:
            return
        self.progress('patch')
        source = prepare_patched_source(
            Path(args.path), patched_source_folder(args.build_base, pkg.name),
            patches, package=pkg.name)
        logger.info(
            f"Building '{pkg.name}' from the patched copy '{source}' ("
            + ', '.join(p.name for p in patches) + ')')
        args.path = str(source)

    def _clean_cache_on_new_settings(self, args, plan):
        """
        Configure from scratch when Emscripten, the flags or the source changed.

        The toolchain's flags initialize CMake's cached flags on the first
        configure only, so a changed setting needs a fresh CMake cache. The
        source folder changes when a recipe adds or removes patches (the
        patched copy replaces `src/`), and CMake refuses a cache made for
        another source folder.
        """
        settings = {
            'emscripten': plan.emscripten.describe(),
            'flags': plan.settings.describe([]),
            'source': str(Path(args.path).resolve()),
            'build': str(Path(args.build_base).resolve()),
        }
        path = Path(args.build_base) / SETTINGS_FILE
        previous = None
        if path.is_file():
            try:
                previous = json.loads(path.read_text())
            except ValueError:
                previous = None
        if previous != settings:
            if previous is not None and \
                    previous.get('source') != settings['source']:
                # object files newer than the other folder's sources would
                # survive a fresh cache: start from an empty build folder
                logger.info(
                    f"Source folder of '{self.context.pkg.name}' changed to "
                    f"'{settings['source']}': building from a fresh build "
                    'folder')
                empty_build_folder(Path(args.build_base))
            elif previous is not None and \
                    previous.get('build', settings['build']) != settings['build']:
                # the workspace was moved or copied: CMake refuses a cache
                # made in another folder ("CMakeCache.txt directory ... is
                # different")
                logger.info(
                    f"Build folder of '{self.context.pkg.name}' moved from "
                    f"'{previous['build']}' to '{settings['build']}': building "
                    'from a fresh build folder')
                empty_build_folder(Path(args.build_base))
            elif previous is not None:
                logger.info(
                    f"Toolchain settings of '{self.context.pkg.name}' changed"
                    ': configuring from a fresh CMake cache')
            args.cmake_clean_cache = True
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(settings, indent=2) + '\n')

    def _relink_stale_executables(self, args, plan):
        """
        Make CMake link again the executables whose added link inputs changed.

        The plugins and components the link launcher adds are not CMake's
        inputs (colcon_wasm/link/report.py): removing the output is how CMake
        learns that the executable must be linked again.

        :returns: True when an executable is to be linked again
        """
        bases = [self._install_base(args)] + [str(u) for u in plan.underlays]
        stale = stale_links(args.build_base, bases)
        for output, reason in stale:
            logger.info(
                f"Linking '{Path(output).name}' of '{self.context.pkg.name}' again: "
                f'{reason}')
            stem = output[:-len('.js')] if output.endswith('.js') else output
            for path in (output, stem + '.wasm', stem + '.worker.js'):
                if Path(path).exists():
                    Path(path).unlink()
        return bool(stale)

    def _install_base(self, args):
        """Get the install base shared by all packages."""
        if args.merge_install:
            return args.install_base
        return str(Path(args.install_base).parent)
