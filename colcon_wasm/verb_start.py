# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
What `colcon build` and `colcon test` do first when they start.

Package selection stays pure: the environment of a `--wasm` build (the
Emscripten found, the recipe's variables, the underlays' build variables,
the install base's marker) is set here, once, before the verb reads its
packages. :class:`colcon_wasm.argument_parser.wasm.WasmArgumentDecorator`
wraps the verb's `main` with :func:`start_verb` when the arguments are
parsed.
"""

import functools
import os
from pathlib import Path

from colcon_core.logging import colcon_logger
from colcon_wasm.error import ColconWasmError
from colcon_wasm.error import exit_message
from colcon_wasm.error import exit_on_error
from colcon_wasm.recipe import load_recipe
from colcon_wasm.testing.options import recipe_overlays_for_tests
from colcon_wasm.testing.verb import is_test_verb
from colcon_wasm.testing.verb import prepare_test_verb
from colcon_wasm.toolchain import find_emscripten
from colcon_wasm.underlay import get_underlays
from colcon_wasm.underlay import PREFIX_PATH_VARIABLE
from colcon_wasm.underlay import split_native_prefixes
from colcon_wasm.underlay import underlay_environment
from colcon_wasm.underlay import write_marker

logger = colcon_logger.getChild(__name__)

"""Marker in a CMake cache written by a colcon-wasm configure."""
WASM_CACHE_MARKER = 'COLCON_WASM_EMSCRIPTEN_ROOT:'

_RECIPE_ATTR = '_colcon_wasm_recipe'
_EMSCRIPTEN_ATTR = '_colcon_wasm_emscripten'


def wrap_verb_main(args):
    """
    Make the build and test verbs start with :func:`start_verb`.

    :param args: the parsed arguments (their `main` is replaced)
    """
    main = getattr(args, 'main', None)
    if main is None or not (is_build_verb(args) or is_test_verb(args)):
        return
    args.main = functools.partial(_started_main, main)


def _started_main(main, *, context):
    start_verb(context.args)
    return main(context=context)


def start_verb(args):
    """
    Check the build base, find Emscripten and set the environment.

    For `colcon build` (with or without `--wasm`): refuse to mix native and
    wasm builds in one build base. For `colcon build --wasm`: find
    Emscripten, set its and the recipe's environment, make the underlays
    visible and mark the install base. For `colcon test --wasm`: make the
    underlays the install base was built on visible.

    :raises SystemExit: with one line naming what failed and what to do
    """
    if is_build_verb(args):
        check_build_base(args)
    if not getattr(args, 'wasm', False):
        return
    get_recipe(args)
    if is_test_verb(args):
        prepare_test_verb(args)
    elif is_build_verb(args):
        emscripten = prepare_environment(args)
        setattr(args, _EMSCRIPTEN_ATTR, emscripten)
        prepare_underlays(args, emscripten)


def started_emscripten(args):
    """Get the Emscripten :func:`start_verb` found (None for other verbs)."""
    return getattr(args, _EMSCRIPTEN_ATTR, None)


def is_build_verb(args):
    """Check if the command is `colcon build`."""
    return getattr(args, 'verb_name', None) == 'build' or \
        hasattr(args, 'build_base') and hasattr(args, 'install_base')


def get_recipe(args):
    """
    Load the recipe once per command (default recipe + `--wasm-recipe`).

    :raises SystemExit: with one line naming file, line and key
    """
    recipe = getattr(args, _RECIPE_ATTR, None)
    if recipe is None:
        with exit_on_error():
            recipe = load_recipe(recipe_overlays_for_tests(args)
                                 + list(getattr(args, 'wasm_recipe', None) or []))
        setattr(args, _RECIPE_ATTR, recipe)
    return recipe


def find_build_folders(build_base, *, wasm):
    """
    List package build folders of the other kind (native vs wasm).

    :param build_base: the build base
    :param bool wasm: True to find native folders, False to find wasm ones
    :returns: sorted folder paths
    """
    base = Path(build_base)
    if not base.is_dir():
        return []
    found = []
    for cache in sorted(base.glob('*/CMakeCache.txt')):
        try:
            text = cache.read_text(errors='replace')
        except OSError:
            continue
        is_wasm = WASM_CACHE_MARKER in text
        if is_wasm != wasm:
            found.append(cache.parent)
    return found


def check_build_base(args):
    """
    Refuse to mix native and wasm builds in one build base.

    :raises SystemExit: naming the folders and what to do
    """
    build_base = getattr(args, 'build_base', None)
    if build_base is None:
        return
    wasm = bool(getattr(args, 'wasm', False))
    folders = find_build_folders(build_base, wasm=wasm)
    if not folders:
        return
    names = ', '.join(f"'{f}'" for f in folders[:5])
    more = f' and {len(folders) - 5} more' if len(folders) > 5 else ''
    if wasm:
        raise SystemExit(exit_message(ColconWasmError(
            f"build base '{build_base}' holds native builds ({names}{more}); "
            'a --wasm build must not reuse them: drop --build-base (the '
            "default is 'build_wasm') or remove those folders")))
    raise SystemExit(exit_message(ColconWasmError(
        f"build base '{build_base}' holds --wasm builds ({names}{more}); "
        'add --wasm, or use another --build-base for native builds'),
        command='colcon build'))


def prepare_environment(args):
    """
    Find Emscripten and set the environment of the whole build.

    :returns: the :class:`colcon_wasm.toolchain.Emscripten`
    :raises SystemExit: with one line when no usable Emscripten is found
    """
    with exit_on_error():
        emscripten = find_emscripten(getattr(args, 'wasm_emscripten', None))
    os.environ.update(emscripten.environment())
    os.environ.update(get_recipe(args).env)
    logger.info(
        f'Using Emscripten {emscripten.version_string} in '
        f"'{emscripten.root}' ({emscripten.source})")
    return emscripten


def prepare_underlays(args, emscripten):
    """
    Make the underlays visible to this build, and only them.

    Native prefixes (a sourced /opt/ros/humble) are dropped from the build
    variables, the underlays' colcon scripts are sourced into this process,
    and the install base is marked as a `--wasm` one.

    :returns: the :class:`colcon_wasm.underlay.Underlay` list
    """
    underlays = get_underlays(args)
    kept, removed = split_native_prefixes(os.environ)
    if removed:
        os.environ.update(kept)
        logger.warning(
            'Ignoring native prefixes for this --wasm build (their libraries are not '
            'WebAssembly): ' + ', '.join(sorted({e for _, e in removed})) + '; '
            '--wasm builds stand on --wasm underlays only (source an install_wasm/'
            f'setup.sh, which sets {PREFIX_PATH_VARIABLE}, or pass --wasm-underlay)')
    with exit_on_error():
        os.environ.update(underlay_environment(underlays, os.environ))
    for underlay in underlays:
        logger.info(f"Using the --wasm underlay '{underlay.base}' ({underlay.source})")
    write_marker(
        Path(getattr(args, 'install_base', None) or 'install_wasm').absolute(),
        emscripten=emscripten.describe(),
        pthread=not getattr(args, 'wasm_no_pthread', False),
        underlays=[u.base for u in underlays], recipe=get_recipe(args).describe())
    return underlays
