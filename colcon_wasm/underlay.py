# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Underlays of `--wasm` builds, as `/opt/ros/humble` is for native ones.

A workspace built with `colcon build --wasm` is an install base that other
`--wasm` workspaces can build on. Its `setup.sh` (written by
:mod:`colcon_wasm.shell`) only prepends the base to `COLCON_WASM_PREFIX_PATH`:
a native build or ROS tool in the same shell sees nothing of WebAssembly.
colcon's own scripts, which set `CMAKE_PREFIX_PATH`, `AMENT_PREFIX_PATH`,
`COLCON_PREFIX_PATH` and `PYTHONPATH`, are kept in `<base>/.colcon_wasm/`,
and a `--wasm` build sources them for its underlays only, in its own process.

Every `--wasm` install base holds a marker, `<base>/.colcon_wasm_install.json`
(what built it: colcon-wasm, Emscripten, threads, its own underlays). A
prefix without it is a native install and is refused as an underlay.
"""

import json
import os
from pathlib import Path
import subprocess

from colcon_wasm import __version__
from colcon_wasm.error import ColconWasmError
from colcon_wasm.error import exit_on_error

"""The marker file of a `--wasm` install base."""
MARKER = '.colcon_wasm_install.json'

MARKER_SCHEMA = 1

"""Where colcon's own prefix scripts of a `--wasm` install base are kept."""
COLCON_SCRIPTS = Path('.colcon_wasm') / 'colcon'

"""The environment variable that lists the `--wasm` underlays (setup.sh)."""
PREFIX_PATH_VARIABLE = 'COLCON_WASM_PREFIX_PATH'

_ARGS_ATTRIBUTE = '_colcon_wasm_underlays'

"""Path-like variables colcon's scripts set, merged from the underlays."""
MERGED_VARIABLES = ('CMAKE_PREFIX_PATH', 'AMENT_PREFIX_PATH',
                    'COLCON_PREFIX_PATH', 'PYTHONPATH', 'PKG_CONFIG_PATH')

"""Variables from which native prefixes are removed in `--wasm` builds."""
NATIVE_PREFIX_VARIABLES = ('CMAKE_PREFIX_PATH', 'AMENT_PREFIX_PATH',
                           'COLCON_PREFIX_PATH')


def write_marker(install_base, *, emscripten, pthread, underlays, recipe):
    """
    Mark an install base as built by `colcon build --wasm`.

    :param install_base: the install base
    :param emscripten: the Emscripten's `describe()`
    :param bool pthread: whether executables use threads
    :param underlays: the install bases of the underlays (Paths)
    :param recipe: the recipe's `describe()`
    """
    base = Path(install_base)
    base.mkdir(parents=True, exist_ok=True)
    data = {'schema': MARKER_SCHEMA, 'colcon_wasm': __version__,
            'emscripten': emscripten, 'pthread': bool(pthread),
            'underlays': [str(u) for u in underlays], 'recipe': recipe}
    path = base / MARKER
    text = json.dumps(data, indent=2) + '\n'
    if not path.is_file() or path.read_text() != text:
        path.write_text(text)


def read_marker(base):
    """Read the marker of a `--wasm` install base, or None when there is none."""
    path = Path(base) / MARKER
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text())
    except (OSError, ValueError) as e:
        raise ColconWasmError(
            f"the --wasm install marker '{path}' cannot be read ({e}): rebuild that "
            'workspace with colcon build --wasm') from e


def install_base_of(prefix):
    """
    Get the install base a prefix belongs to.

    That is the prefix itself (merged install) or its parent (isolated
    install), whichever holds colcon's `.colcon_install_layout`.
    """
    prefix = Path(prefix)
    for candidate in (prefix, prefix.parent):
        if (candidate / '.colcon_install_layout').is_file() or \
                (candidate / MARKER).is_file():
            return candidate
    return prefix


def is_wasm_prefix(prefix):
    """Check if a prefix belongs to an install base built with `--wasm`."""
    return (install_base_of(prefix) / MARKER).is_file()


class Underlay:
    """One `--wasm` install base a build stands on."""

    def __init__(self, base, marker, source):
        """Describe an underlay found by `source` (for messages)."""
        self.base = Path(base)
        self.marker = marker
        self.source = source

    def __repr__(self):  # noqa: D105
        return f'Underlay({str(self.base)!r})'

    def packages(self):
        """Get the names of the packages installed in this underlay."""
        index = self.base / 'share' / 'colcon-core' / 'packages'
        names = set()
        if index.is_dir():
            names |= {p.name for p in index.iterdir()}
        for child in self.base.iterdir():
            if (child / 'share' / 'colcon-core' / 'packages' / child.name).is_file():
                names.add(child.name)
        return names

    def colcon_local_setup(self):
        """Get colcon's own local_setup.sh of this base (sets the build variables)."""
        return self.base / COLCON_SCRIPTS / 'local_setup.sh'


def _check_underlay(path, source, *, pthread):
    base = Path(path).expanduser().absolute()
    if not base.is_dir():
        raise ColconWasmError(
            f"the underlay '{path}' ({source}) does not exist: build that workspace with "
            'colcon build --wasm, or fix the path')
    marker = read_marker(base)
    if marker is None:
        hint = ''
        if (base / 'install_wasm' / MARKER).is_file():
            hint = f" (did you mean '{base / 'install_wasm'}'?)"
        raise ColconWasmError(
            f"the underlay '{base}' ({source}) was not built with colcon build --wasm{hint}: "
            'it is a native install (its libraries are not WebAssembly). Build that '
            'workspace with `colcon build --wasm` and use its install_wasm/ (source '
            'install_wasm/setup.sh or pass --wasm-underlay), or drop it')
    if marker.get('schema') != MARKER_SCHEMA:
        raise ColconWasmError(
            f"the underlay '{base}' ({source}) was built by another colcon-wasm (marker "
            f"schema {marker.get('schema')!r}, this one reads {MARKER_SCHEMA}): rebuild "
            'it with this colcon-wasm')
    if bool(marker.get('pthread', True)) != bool(pthread):
        built = 'with' if marker.get('pthread', True) else 'without'
        want = 'with' if pthread else 'without'
        raise ColconWasmError(
            f"the underlay '{base}' ({source}) was built {built} threads and this build is "
            f'{want} them: objects of both kinds cannot be linked together; build both '
            'with the same --wasm-no-pthread setting')
    return Underlay(base, marker, source)


def find_underlays(*, option_paths, environ, install_base, pthread):
    """
    Find the underlays of a `--wasm` build, highest priority first.

    `--wasm-underlay` paths come first (in the order given), then the entries
    of `COLCON_WASM_PREFIX_PATH` (as sourced `setup.sh` files left them),
    then the underlays those were built on (their markers), as sourcing an
    overlay's setup.sh brings the chain below it: an overlay of an overlay
    sees the packages of both. The build's own install base is never its own
    underlay.

    :raises ColconWasmError: for a path that is missing or not a `--wasm` install
    """
    own = Path(install_base).absolute()
    found = []
    candidates = [(p, '--wasm-underlay') for p in option_paths or []]
    candidates += [(p, PREFIX_PATH_VARIABLE) for p in
                   environ.get(PREFIX_PATH_VARIABLE, '').split(os.pathsep) if p]
    for path, source in candidates:
        if Path(path).expanduser().absolute() == own:
            continue
        underlay = _check_underlay(path, source, pthread=pthread)
        if all(u.base != underlay.base for u in found):
            found.append(underlay)
    return _with_their_underlays(found, own, pthread)


def _with_their_underlays(found, own, pthread):
    """Append the underlays the found ones were built on, recursively, after them."""
    at = 0
    while at < len(found):
        for path in found[at].marker.get('underlays', []):
            base = Path(path).absolute()
            if base == own or not base.is_dir() or any(u.base == base for u in found):
                continue  # a moved underlay of an underlay: what it had is gone with it
            found.append(_check_underlay(
                base, f"an underlay of '{found[at].base}'", pthread=pthread))
        at += 1
    return found


def get_underlays(args):
    """
    Find the `--wasm` underlays of a command, once.

    They come from `--wasm-underlay`, then `$COLCON_WASM_PREFIX_PATH`,
    highest priority first.

    :raises SystemExit: naming the underlay that is missing or native
    """
    underlays = getattr(args, _ARGS_ATTRIBUTE, None)
    if underlays is None:
        install_base = getattr(args, 'install_base', None) or 'install_wasm'
        option_paths = getattr(args, 'wasm_underlay', None) or []
        pthread = not getattr(args, 'wasm_no_pthread', False)
        with exit_on_error():
            if getattr(args, 'verb_name', None) == 'test':
                option_paths, pthread = _as_built(install_base, option_paths, pthread)
            underlays = find_underlays(
                option_paths=option_paths,
                environ=os.environ, install_base=install_base,
                pthread=pthread)
        setattr(args, _ARGS_ATTRIBUTE, underlays)
    return underlays


def _as_built(install_base, option_paths, pthread):
    """
    Get the underlays and threads setting `colcon test` uses: the build's.

    The tests run on what the install base was built on (its marker), unless
    `--wasm-underlay` or `COLCON_WASM_PREFIX_PATH` name underlays.
    """
    marker = read_marker(install_base)
    if marker is None:
        return option_paths, pthread
    if not option_paths and not os.environ.get(PREFIX_PATH_VARIABLE):
        option_paths = list(marker.get('underlays') or [])
    return option_paths, bool(marker.get('pthread', pthread))


def split_native_prefixes(environ):
    """
    Find the native prefixes of the path variables a `--wasm` build reads.

    :returns: ({variable: kept entries}, [(variable, removed entry)])
    """
    kept = {}
    removed = []
    for name in NATIVE_PREFIX_VARIABLES:
        value = environ.get(name)
        if value is None:
            continue
        entries = []
        for entry in value.split(os.pathsep):
            if not entry:
                continue
            if Path(entry).exists() and not is_wasm_prefix(entry):
                removed.append((name, entry))
            else:
                entries.append(entry)
        kept[name] = os.pathsep.join(entries)
    return kept, removed


def underlay_environment(underlays, environ):
    """
    Get the build variables the underlays' colcon scripts set.

    The scripts are sourced in a shell of their own, lowest priority first,
    starting from `environ`; only :data:`MERGED_VARIABLES` are returned.

    :raises ColconWasmError: when a script is missing or fails
    """
    if not underlays:
        return {}
    lines = ['set -e']
    for underlay in reversed(underlays):
        script = underlay.colcon_local_setup()
        if not script.is_file():
            raise ColconWasmError(
                f"the underlay '{underlay.base}' has no '{script}': it was built by an "
                'older colcon-wasm; rebuild it with colcon build --wasm')
        lines.append(f'COLCON_CURRENT_PREFIX={_sh_quote(underlay.base)} '
                     f'. {_sh_quote(script)} >/dev/null')
    lines.append('env -0')
    completed = subprocess.run(
        ['sh', '-c', '\n'.join(lines)], env=dict(environ), capture_output=True)
    if completed.returncode != 0:
        raise ColconWasmError(
            'sourcing the underlays failed (' + ', '.join(str(u.base) for u in underlays)
            + '): ' + completed.stderr.decode(errors='replace').strip())
    result = {}
    for item in completed.stdout.split(b'\0'):
        name, _, value = item.decode(errors='replace').partition('=')
        if name in MERGED_VARIABLES:
            result[name] = value
    return result


def _sh_quote(path):
    return "'" + str(path).replace("'", "'\\''") + "'"


def underlay_stamps(bases):
    """
    Describe the state of underlays for a package's up-to-date check.

    A package is rebuilt when an underlay moved or one of its packages was
    installed again (colcon rewrites `share/colcon-core/packages/<pkg>`).
    """
    stamps = []
    for base in bases:
        base = Path(base)
        newest = 0
        for index in [base / 'share' / 'colcon-core' / 'packages'] + sorted(
                base.glob('*/share/colcon-core/packages')):
            try:
                for entry in index.iterdir():
                    newest = max(newest, entry.stat().st_mtime_ns)
            except OSError:
                continue
        stamps.append([str(base), newest])
    return stamps
