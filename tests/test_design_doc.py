# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
docs/design.md against the tree, and the layers' imports.

Its layout tables name files that exist and cover every tracked file of the
JS runtime; imports go down the layers.

The layers: rmw_wasm_cpp → wasm_cpp → wasm_js (a lower layer never names a
higher one); in wasm_js, the page, launch and bridge modules use the runtime,
the runtime uses the client and the bus, the bus uses the layout and the ABI;
in Python, the CLI uses the library and never the other way round.
"""

from pathlib import Path
import re
import subprocess

REPO = Path(__file__).resolve().parents[1]
DESIGN = REPO / 'docs' / 'design.md'
WASM_JS = 'packages/wasm_js/'


def tracked_files():
    """Return the files git tracks, as repository-relative POSIX paths."""
    done = subprocess.run(['git', 'ls-files'], cwd=REPO, capture_output=True, text=True,
                          check=True)
    return [line for line in done.stdout.splitlines() if line]


def layout_table(heading):
    """Return the quoted paths of the first column of the table under ``heading``."""
    text = DESIGN.read_text(encoding='utf-8')
    start = text.index(heading)
    rows = []
    for line in text[start:].splitlines()[1:]:
        if line.startswith('#'):
            break
        if line.startswith('| `'):
            first = line.split('|')[1]
            rows.extend(re.findall(r'`([^`]+)`', first))
    assert rows, f'no layout table under {heading!r} in {DESIGN}'
    return rows


def _exists(path, files):
    prefix = path.split('<', 1)[0]
    if path.endswith('/') or '<' in path:
        return any(f.startswith(prefix) for f in files)
    return path in files


def _covered(file, paths):
    return any(file == p or (p.endswith('/') and file.startswith(p)) for p in paths)


def test_every_path_of_the_repository_layout_table_exists():
    files = tracked_files()
    missing = [p for p in layout_table('## 2. Repository layout') if not _exists(p, files)]
    assert not missing, f'docs/design.md §2 names paths git does not track: {missing}'


def test_every_top_level_folder_is_in_the_repository_layout_table():
    files = tracked_files()
    paths = layout_table('## 2. Repository layout')
    folders = sorted({f.split('/', 1)[0] + '/' for f in files if '/' in f})
    named = {p.split('/', 1)[0] + '/' for p in paths}
    absent = [f for f in folders if f not in named]
    assert not absent, f'docs/design.md §2 does not name these top-level folders: {absent}'


def test_the_wasm_js_table_names_existing_files_and_covers_every_one():
    files = [f[len(WASM_JS):] for f in tracked_files() if f.startswith(WASM_JS)]
    paths = layout_table('### 6.3 wasm_js')
    missing = [p for p in paths if not _exists(p, files)]
    assert not missing, f'docs/design.md §6.3 names files wasm_js does not have: {missing}'
    sources = [f for f in files if f.startswith(('src/', 'cmake/')) or '/' not in f]
    sources = [f for f in sources if f != 'README.md']
    uncovered = [f for f in sources if not _covered(f, paths)]
    assert not uncovered, f'docs/design.md §6.3 covers none of these wasm_js files: {uncovered}'


# wasm_js rooms, lowest first: a module may import its own room and lower ones.
JS_LAYERS = [
    ('abi', ('src/abi/', 'src/layout.mjs', 'src/qos.mjs')),
    ('bus', ('src/bus/', 'src/bus.mjs', 'src/copier.mjs')),
    ('client', ('src/client/', 'src/bus_client.mjs')),
]
JS_IMPORT = re.compile(r"""(?:^|\s)(?:import|export)\b[^'"]*?from\s+['"](\.[^'"]+)['"]"""
                       r"""|import\(\s*['"](\.[^'"]+)['"]""", re.M)


def _js_layer(path):
    for rank, (_, prefixes) in enumerate(JS_LAYERS):
        if path.startswith(prefixes):
            return rank
    return len(JS_LAYERS)


def test_wasm_js_imports_go_down_the_layers():
    upward = []
    seen = 0
    for file in tracked_files():
        if not (file.startswith(WASM_JS + 'src/') and file.endswith(('.mjs', '.js'))):
            continue
        own = file[len(WASM_JS):]
        text = (REPO / file).read_text(encoding='utf-8')
        for match in JS_IMPORT.finditer(text):
            target = (Path(own).parent / (match.group(1) or match.group(2))).as_posix()
            target = str(Path(target)).replace('\\', '/')
            resolved = Path('/' + target).resolve().as_posix()[1:]
            seen += 1
            if _js_layer(resolved) > _js_layer(own):
                upward.append(f'{own} imports {resolved}')
    assert seen > 100, f'only {seen} relative imports found: is the pattern still right?'
    assert not upward, 'wasm_js modules import upward:\n' + '\n'.join(upward)


def test_lower_cpp_layers_never_name_higher_ones():
    offenders = []
    for file in tracked_files():
        if file.startswith('packages/wasm_cpp/'):
            higher = ('rmw_wasm_cpp', 'rmw/', 'rcutils/')
        elif file.startswith(WASM_JS + 'src/abi/') or file.startswith(WASM_JS + 'src/bus'):
            higher = ('rmw_wasm_cpp', '#include')
        else:
            continue
        if not file.endswith(('.hpp', '.cpp', '.h', '.mjs', '.js', '.txt', '.cmake')):
            continue
        text = (REPO / file).read_text(encoding='utf-8')
        for line in text.splitlines():
            if line.lstrip().startswith(('#include', 'find_package', 'import ')):
                if any(h in line for h in higher):
                    offenders.append(f'{file}: {line.strip()}')
    assert not offenders, 'a lower layer names a higher one:\n' + '\n'.join(offenders)


def test_the_python_library_never_imports_the_cli():
    offenders = []
    for file in tracked_files():
        if not file.startswith('colcon_wasm/') or not file.endswith('.py'):
            continue
        if file.startswith('colcon_wasm/cli/'):
            continue
        text = (REPO / file).read_text(encoding='utf-8')
        for line in text.splitlines():
            if re.match(r'\s*(from|import)\s+colcon_wasm\.cli\b', line) or \
                    re.match(r'\s*from\s+colcon_wasm\s+import\s+cli\b', line) or \
                    re.match(r'\s*from\s+\.+cli\b', line):
                offenders.append(f'{file}: {line.strip()}')
    assert not offenders, 'library modules import the CLI:\n' + '\n'.join(offenders)


# "No JS module over ~500 lines without a reason at its top": about 500, 5 % slack.
LONG_MODULE_LINES = 525
LONG_MODULE_REASON = 'Over 500 lines on purpose'


def test_long_js_modules_say_why_at_their_top():
    unexplained = []
    for file in tracked_files():
        if not file.endswith(('.mjs', '.js')) or file.startswith('tests/'):
            continue
        lines = (REPO / file).read_text(encoding='utf-8').splitlines()
        if len(lines) > LONG_MODULE_LINES and \
                not any(LONG_MODULE_REASON in line for line in lines[:60]):
            unexplained.append(f'{file} ({len(lines)} lines)')
    assert not unexplained, (
        f'JS modules over {LONG_MODULE_LINES} lines without "{LONG_MODULE_REASON}: <why>" in '
        f'their first 60 lines (split them, or say why not): {unexplained}')


def test_every_exception_class_of_colcon_wasm_is_a_colcon_wasm_error():
    import ast
    outside = []
    for file in tracked_files():
        if not file.startswith('colcon_wasm/') or not file.endswith('.py'):
            continue
        tree = ast.parse((REPO / file).read_text(encoding='utf-8'))
        for node in ast.walk(tree):
            if not isinstance(node, ast.ClassDef):
                continue
            bases = [ast.unparse(b) for b in node.bases]
            builtin = [b for b in bases if b in ('Exception', 'ValueError', 'RuntimeError',
                                                 'OSError', 'TypeError', 'KeyError')]
            if builtin and 'ColconWasmError' not in bases and node.name != 'ColconWasmError':
                outside.append(f'{file}: class {node.name}({", ".join(bases)})')
    assert not outside, ('exceptions outside the ColconWasmError family (colcon_wasm/error.py):\n'
                         + '\n'.join(outside))
