# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
``colcon-wasm export DIR``: the launcher page and its nodes as a static site.

Everything ``serve`` answers for the page is written into ``DIR`` at the
same URL paths (``site.py``): the page (rendered, the workspace embedded),
``/launcher/``, ``/wasm_js/``, the files the manifests list (``/ws/``), the
share files of ``package://`` (``/package/``), the page's libraries
(``/vendor/``) and the read-only views of the install bases (``/fs/``), each
directory's listing as the ``index.html`` a static host sends for ``dir/``.
Any static host serves it (``python3 -m http.server``, nginx, GitHub Pages).

Static hosts seldom send the cross-origin isolation headers that
``SharedArrayBuffer`` needs: the site's service worker (``coi_sw.js``, at its
root) adds them, and the page reloads once under it (``app.mjs``).

What needs the server is off in an exported page, and says so: launch files
(serve evaluates them; ``--launch`` plans XML and YAML ones here) and the
rosbridge relay. Bags are read and recorded in the page itself
(``bag_local.mjs``), and Python nodes run when the export copied Pyodide in
(``--python``).
"""

import json
from pathlib import Path
import shutil
from typing import NamedTuple
import urllib.parse

from colcon_wasm.error import ColconWasmError
from colcon_wasm.launch.install_view import AMENT_PREFIX_PATH
from colcon_wasm.server.export_files import compress_site
from colcon_wasm.server.export_files import download_sizes
from colcon_wasm.server.export_files import MANIFEST
from colcon_wasm.server.export_files import site_size
from colcon_wasm.server.export_launch import LaunchExportError
from colcon_wasm.server.export_launch import plan_launch
from colcon_wasm.server.export_select import left_out_prefixes
from colcon_wasm.server.export_select import select_packages
from colcon_wasm.server.export_select import SelectionError
from colcon_wasm.server.site import GATEWAY_FILES
from colcon_wasm.server.site import PAGE_MODULE
from colcon_wasm.server.site import run_entry

MARKER = '.colcon-wasm-export.json'
SERVICE_WORKER = 'coi_sw.js'
BOOT_SCRIPT = 'static_boot.js'
PYODIDE_FOLDER = 'pyodide'
_NO_SERVER = 'an exported page has no colcon-wasm serve behind it'


class ExportError(ColconWasmError):
    """An export that cannot be written; the text says why and what to do."""


def check_target(target):
    """
    Refuse a target folder that holds something other than an earlier export.

    :raises ExportError: naming the folder
    """
    target = Path(target)
    if target.exists() and not target.is_dir():
        raise ExportError(f"'{target}' is a file: export into a folder")
    if target.is_dir() and any(target.iterdir()) and not (target / MARKER).is_file():
        raise ExportError(
            f"'{target}' is not empty and holds no earlier export ({MARKER}): export into an "
            'empty or new folder, or remove it first; nothing was written')


def check_runs(site, runs, selection=None):
    """
    Refuse ``--run`` items that name no executable of the install space (or the selection).

    :param selection: the package options, for the message, or None
    :raises ExportError: with the executables there are
    """
    known = {f"{p['name']}/{e['name']}" for p in site.workspace()['packages']
             for e in p['executables']}
    where = f'the install space {site.install_space.base}'
    if selection:
        where = f'the packages of {selection} in {where}'
    for spec in runs:
        item = spec.split(' ')[0]
        if item not in known:
            raise ExportError(
                f"--run {spec}: there is no executable '{item}' in {where}; there are: "
                f"{', '.join(sorted(known)) or 'none'}; nothing was written")


def _plan_launches(site, launches, selection, left_out):
    """
    Plan each ``--launch`` (export_launch.py), refusing one that runs what the site lacks.

    :raises ExportError: the planner's error, or an executable of the plan not exported
    """
    if not launches:
        return []
    from colcon_wasm.server.launch_socket import LaunchService
    service = LaunchService(site.install_space, runtime_python=Path(site.runtime_dir) / 'python')
    plans = []
    for spec in launches:
        try:
            plan = plan_launch(site.install_space, spec, service.find)
        except LaunchExportError as e:
            raise ExportError(str(e)) from None
        try:
            check_runs(site, [f"{p['package']}/{p['executable']}" for p in plan['processes']],
                       selection)
        except ExportError as e:
            raise ExportError(f'--launch {spec}: {e}') from None
        for process in plan['processes']:  # the ament index lists the exported packages only
            _drop_prefixes(process.get('env') or {}, left_out)
        plans.append(plan)
    return plans


def _drop_prefixes(env, left_out):
    """Take the left-out packages' prefixes out of an environment's ``AMENT_PREFIX_PATH``."""
    if env.get(AMENT_PREFIX_PATH) and left_out:
        env[AMENT_PREFIX_PATH] = ':'.join(
            p for p in env[AMENT_PREFIX_PATH].split(':') if p not in left_out)


def _selection_text(select, up_to):
    """Return the package options as given (``--packages-up-to A B``), or None."""
    parts = []
    if select:
        parts.append('--packages-select ' + ' '.join(select))
    if up_to:
        parts.append('--packages-up-to ' + ' '.join(up_to))
    return ' '.join(parts) or None


def _narrow(site, chosen):
    """List only the chosen packages' executables in the page (every type description stays)."""
    if chosen is None:
        return
    listed = site.workspace()
    listed['packages'] = [p for p in listed['packages'] if p['name'] in chosen]
    site.workspace = lambda: listed


def check_base_url(base_url):
    """
    Return the ``--base-url`` of a site under a sub-path, ended with ``/``.

    :param base_url: ``/PATH/`` or ``https://HOST/PATH/``, or None
    :raises ExportError: for anything else, with the forms that work
    """
    if base_url is None:
        return None
    parsed = urllib.parse.urlsplit(base_url)
    absolute = parsed.scheme in ('http', 'https') and parsed.netloc
    if not (absolute or (not parsed.scheme and not parsed.netloc
                         and parsed.path.startswith('/'))) \
            or parsed.query or parsed.fragment or '..' in parsed.path.split('/'):
        raise ExportError(
            f"--base-url {base_url}: give the path the site lives under, from the host's root "
            "(e.g. '/demo/' for https://USER.github.io/demo/), or a whole http(s) URL; "
            'nothing was written')
    return base_url if base_url.endswith('/') else base_url + '/'


def export_site(site, target, *, runs=(), base_url=None, select=(), up_to=(), pyodide=None,
                launches=()):
    """
    Write the static site of ``site`` into ``target``.

    :param runs: ``PKG/EXE [ARGS]`` the page starts on load, as ``?run=`` does
    :param base_url: where the site lives (``/PATH/``), for the page's ``<base href>``;
      without it the site works under any path its page is opened at with a ``/`` at its end
    :param select: ``--packages-select``: only these packages (export_select.py)
    :param up_to: ``--packages-up-to``: these packages and their dependencies
    :param pyodide: the Pyodide folder to copy in (``--python``), for Python nodes and
      the console; None leaves them off, and the page says why
    :param launches: ``--launch`` values (``PKG FILE [NAME:=VALUE ...]``), planned now and
      started by the page on load (export_launch.py)
    :returns: :class:`Exported`
    """
    target = Path(target)
    base_url = check_base_url(base_url)
    check_target(target)
    try:
        chosen = select_packages(site.install_space, select, up_to)
    except SelectionError as e:
        raise ExportError(str(e)) from None
    left_out = left_out_prefixes(site.install_space, chosen)
    selection = _selection_text(select, up_to)
    _narrow(site, chosen)
    check_runs(site, runs, selection)
    plans = _plan_launches(site, launches, selection, left_out)
    if target.is_dir():
        for child in target.iterdir():  # an earlier export: replaced as a whole
            shutil.rmtree(child) if child.is_dir() and not child.is_symlink() else child.unlink()
    target.mkdir(parents=True, exist_ok=True)
    writer = _Writer(target)
    workspace = static_workspace(site, runs, left_out, selection, python=pyodide is not None)
    workspace['launch']['planned'] = plans
    site.workspace = lambda: workspace  # what the page embeds
    boot = (site.launcher_dir / BOOT_SCRIPT).read_text(encoding='utf-8')
    writer.body('index.html', site.page({'run': list(runs)}, root='./', base=base_url,
                                        boot=boot).body)
    writer.body('workspace.json', json.dumps(workspace).encode())
    writer.tree('launcher', site.launcher_dir, skip=('.jinja', '.html'))
    _write_runtime(writer, site)
    for (package_name, relative), package in sorted(site._allowed_files().items()):
        if chosen is None or package_name in chosen or \
                Path(package.prefix, relative) == Path(package.types_path):
            writer.file(f'ws/{package_name}/{relative}', Path(package.prefix) / relative)
    for name, share in sorted(site.install_space.share_folders().items()):
        if chosen is None or name in chosen:
            writer.tree(f'package/{name}', share)
    _write_vendor(writer)
    if pyodide is not None:
        writer.tree(PYODIDE_FOLDER, pyodide, skip=('.map', '.d.ts', '.html'))
    gateway = site._gateway_dir()
    if gateway is not None:  # ?zenoh=: the page's Zenoh gateway (zenoh-pico)
        for name in GATEWAY_FILES:
            if (Path(gateway) / name).is_file():
                writer.file(f'zenoh/{name}', Path(gateway) / name)
    _write_views(writer, site, left_out)
    writer.file(SERVICE_WORKER, site.launcher_dir / SERVICE_WORKER)
    writer.body(MARKER, json.dumps({
        'install_base': str(site.install_space.base), 'runs': list(runs), 'base_url': base_url,
        'launches': list(launches),
        'packages': None if chosen is None else sorted(chosen)}).encode())
    first = first_visit_paths(site, workspace, runs)
    files = compress_site(target, set(first))
    count, size = site_size(target)
    executables = sum(len(p['executables']) for p in workspace['packages'])
    return Exported(files=count, bytes=size, plain_bytes=writer.bytes, executables=executables,
                    first_visit=download_sizes(files, first))


class Exported(NamedTuple):
    """What an export wrote: the whole folder, and what a first visit downloads."""

    files: int
    bytes: int
    plain_bytes: int
    """The site without its compressed forms."""
    executables: int
    """The executables the page lists."""
    first_visit: tuple
    """``(plain, gzip, brotli)`` bytes of the page, its modules, types and ``--run`` programs."""


def first_visit_paths(site, workspace, runs):
    """
    Return the site's files a first visit loads before its nodes run.

    The page, the modules it imports, the workspace's type descriptions, the
    service worker and its manifest, and each ``--run`` executable's files
    (``.js``, ``.wasm``, a pthread ``.worker.js``).
    """
    paths = ['index.html', SERVICE_WORKER, MANIFEST]
    runtime = '/' + workspace['runtime'].lstrip('./')
    paths += [url.lstrip('/') for url in site.module_graph([PAGE_MODULE, runtime])]
    paths += [url.lstrip('./') for url in workspace['types']]
    for spec in runs:
        entry = run_entry(workspace, spec)
        if entry is not None:
            stem = entry['url'].lstrip('./')[:-len('.js')]
            paths += [f'{stem}.js', f'{stem}.wasm', f'{stem}.worker.js']
    return paths


def static_workspace(site, runs, left_out=None, selection=None, python=False):
    """
    Return the workspace the exported page embeds: what needs serve is off, and says why.

    :param left_out: ``{prefix: package}`` the export leaves out: a node that opens a file
      there is told (``left_out`` of the page's views) which option includes it
    :param selection: the package options the export was given, for that message
    :param python: Pyodide is in the site (``--python``)
    """
    workspace = relative_urls(site.workspace())
    if left_out:
        # the ament index of the page's programs lists the exported packages only
        _drop_prefixes(workspace.get('environment') or {}, left_out)
        workspace['left_out'] = {
            'prefixes': left_out,
            'hint': f'the export ({selection}) left out package {{package}}: export with '
                    f'--packages-select {{package}} too, or with --packages-up-to of the '
                    'package that runs this node'}
    workspace['static'] = True
    workspace['autorun'] = list(runs)
    workspace['rosbridge'] = None
    workspace['launch'] = {'socket': None, 'files': [], 'problem':
                           f'{_NO_SERVER}: launch files are evaluated by serve'}
    if python:
        workspace['python'] = dict(workspace.get('python') or {},
                                   pyodide=f'./{PYODIDE_FOLDER}/', problem=None)
    else:
        workspace['python'] = dict(
            workspace.get('python') or {}, pyodide=None,
            problem='Pyodide is not in this export: export with --python for Python nodes '
                    'and the console')
    workspace['bag'] = {'local': True, 'problem': None}  # the page reads and writes MCAP
    return workspace


def relative_urls(workspace):
    """
    Return the workspace with the site's URLs relative to the page (``/ws/…`` → ``./ws/…``).

    So the site works under any sub-path: the page resolves them against its
    base URL (``site_url.mjs``).
    """
    def relative(url):
        return '.' + url if isinstance(url, str) and url.startswith('/') else url
    workspace = json.loads(json.dumps(workspace))
    workspace['runtime'] = relative(workspace['runtime'])
    workspace['types'] = [relative(u) for u in workspace['types']]
    for package in workspace['packages']:
        for executable in package['executables']:
            executable['url'] = relative(executable['url'])
    python = workspace.get('python') or {}
    python['pyodide'] = relative(python.get('pyodide'))
    for entry in python.get('files', []):
        entry['url'] = relative(entry['url'])
    if workspace.get('zenoh'):
        workspace['zenoh']['module'] = relative(workspace['zenoh']['module'])
    for mount in workspace.get('mounts', []):
        mount['url'] = relative(mount['url'])
    return workspace


def _write_runtime(writer, site):
    """Write the runtime (``/wasm_js/``): its folder, and the page's own modules over it."""
    from colcon_wasm.server.site import PAGE_MODULES
    writer.tree('wasm_js', site.runtime_dir)
    if site.runtime_manifest():
        # what runtime.mjs reads of its build flags (the pthread pool size); not the rest
        # (the build's CMake arguments name this machine's paths, for a public site)
        flags = json.loads(site.runtime_manifest().read_text(encoding='utf-8')).get('flags') or {}
        writer.body('colcon_wasm/manifest.json', json.dumps({'flags': {
            k: flags[k] for k in ('pthread', 'pthread_pool_size') if k in flags}}).encode())
    for name in PAGE_MODULES:
        source = site.page_modules_dir / name
        if source.is_dir():
            writer.tree(f'wasm_js/{name}', source)
        elif source.is_file():
            writer.file(f'wasm_js/{name}', source)


def _write_vendor(writer):
    """Write the page's pinned libraries, when they are there (the 3D view needs them)."""
    from colcon_wasm.vendor import vendor_dir
    from colcon_wasm.vendor import VendorError
    try:
        folder = vendor_dir()
    except VendorError:
        return  # the 3D tab then says why, as under serve
    writer.tree('vendor', folder)


def _write_views(writer, site, left_out=None):
    """
    Write the read-only views (``/fs/<n>/``): files, each directory's listing as index.html.

    What no node reads at run time is left out of the views (and their
    listings), as it would double the site: headers (``include/``), static
    libraries, and the executables themselves (the page loads them from
    ``ws/``). So are the packages the selection leaves out.

    :param left_out: ``{prefix: package}`` of packages not exported
    """
    skipped = {Path(prefix).resolve() for prefix in (left_out or {})}
    for number, base in enumerate(site.views.bases):
        base = Path(base)
        prefixes = {base.resolve(), *(Path(p.prefix).resolve()
                                      for p in site.install_space.packages().values())}
        skipped |= {prefix / 'include' for prefix in prefixes}
        for folder in [base, *sorted(p for p in base.rglob('*') if p.is_dir())]:
            real = folder.resolve()
            if real in skipped or any(s in real.parents for s in skipped):
                continue
            parts = list(folder.relative_to(base).parts)
            try:
                kind, listing = site.views.content(str(number), parts, True)
            except Exception:  # out of bounds (a link leaving the base): not in the view
                continue
            document = json.loads(listing)
            names = {e['name'] for e in document['entries']}
            document['entries'] = [
                e for e in document['entries']
                if (folder / e['name']).resolve() not in skipped
                and not (e['kind'] == 'file' and _build_only(e['name'], names))]
            relative = '/'.join(['fs', str(number), *parts])
            if (folder / 'index.html').exists():
                raise ExportError(
                    f"'{folder / 'index.html'}' is in the install space: an exported view "
                    'writes each directory listing there; rename the file')
            writer.body(f'{relative}/index.html', json.dumps(document).encode())
            for entry in document['entries']:
                if entry['kind'] == 'file':
                    writer.file(f'{relative}/{entry["name"]}', folder / entry['name'])


def _build_only(name, names):
    """Tell whether a file of a view is one no node reads: a static library, an executable."""
    if name.endswith('.a'):
        return True
    stem = name[:-len('.worker.js')] if name.endswith('.worker.js') else Path(name).stem
    return Path(name).suffix in ('.wasm', '.js') and f'{stem}.wasm' in names


class _Writer:
    """Files into the export folder, counted."""

    def __init__(self, root):
        self.root = Path(root)
        self.count = 0
        self.bytes = 0

    def _target(self, relative):
        path = self.root / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        return path

    def body(self, relative, data):
        self._target(relative).write_bytes(data)
        self.count += 1
        self.bytes += len(data)

    def file(self, relative, source):
        path = self._target(relative)
        shutil.copyfile(source, path)
        self.count += 1
        self.bytes += path.stat().st_size

    def tree(self, relative, folder, skip=()):
        for source in sorted(Path(folder).rglob('*')):
            if source.is_file() and not source.name.endswith(skip) \
                    and '__pycache__' not in source.parts:
                self.file(f'{relative}/{source.relative_to(folder).as_posix()}', source)
