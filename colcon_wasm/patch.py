# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Apply the recipe's patches to a copy of a package's source.

The package's own folder (under `src/`) is never written. A patched copy is
made in the package's build folder; it is rebuilt only when the source or a
patch changes (so unchanged files keep their timestamps and a rebuild stays a
no-op). All patches are applied in memory first: a patch that does not apply
raises :class:`PatchError` naming the package, the patch file and the hunk,
and leaves the previous copy (if any) untouched.
"""

import hashlib
import os
from pathlib import Path
import re
import shutil

from colcon_wasm.error import ColconWasmError

"""Name of the stamp file inside a patched copy."""
STAMP_NAME = '.colcon_wasm_patched'

_HUNK_HEADER = re.compile(
    r'^@@ -(?P<old>\d+)(?:,(?P<old_len>\d+))? '
    r'\+(?P<new>\d+)(?:,(?P<new_len>\d+))? @@')

_IGNORED_NAMES = {'.git', '.hg', '.svn', '__pycache__'}


class PatchError(ColconWasmError):
    """A patch does not apply (or cannot be read)."""


class Hunk:
    """One `@@` block of a unified diff."""

    def __init__(self, number, old_start, line_in_patch):
        """Start an empty hunk."""
        self.number = number
        self.old_start = old_start
        self.line_in_patch = line_in_patch
        self.old = []
        self.new = []


class FileDiff:
    """The hunks for one file."""

    def __init__(self, old_path, new_path, strip=None):
        """
        Describe the changes of one file.

        :param int strip: leading path components to remove (`patch -p`);
          None: remove an `a/` or `b/` prefix only
        """
        self.old_path = old_path
        self.new_path = new_path
        self.strip = strip
        self.hunks = []

    @property
    def path(self):
        """The path relative to the package (first component stripped)."""
        name = self.new_path if self.new_path != '/dev/null' \
            else self.old_path
        return _strip_component(name, self.strip)


def _strip_component(name, strip=None):
    name = name.split('\t')[0].strip()
    if strip is not None:
        return name.split('/', strip)[-1] if strip else name
    parts = name.split('/', 1)
    if len(parts) == 2 and parts[0] in ('a', 'b'):
        return parts[1]
    return name


def parse_patch(text, patch_name, strip=None):
    """
    Parse a unified diff (as written by `git diff` or `diff -u`).

    :param str text: the patch
    :param str patch_name: for messages
    :param int strip: leading path components to remove (see FileDiff)
    :returns: list of :class:`FileDiff`
    :raises PatchError: for a malformed patch
    """
    lines = text.splitlines(keepends=True)
    diffs = []
    current = None
    index = 0
    while index < len(lines):
        line = lines[index]
        if line.startswith('--- ') and index + 1 < len(lines) and \
                lines[index + 1].startswith('+++ '):
            current = FileDiff(line[4:].rstrip('\n'),
                               lines[index + 1][4:].rstrip('\n'), strip)
            diffs.append(current)
            index += 2
            continue
        match = _HUNK_HEADER.match(line)
        if match:
            if current is None:
                raise PatchError(
                    f"patch '{patch_name}' line {index + 1}: hunk before "
                    "any '---'/'+++' file header")
            hunk = Hunk(len(current.hunks) + 1, int(match.group('old')),
                        index + 1)
            old_len = int(match.group('old_len') or 1)
            new_len = int(match.group('new_len') or 1)
            index += 1
            while (len(hunk.old) < old_len or
                   len(hunk.new) < new_len) and index < len(lines):
                body = lines[index]
                if body.startswith('\\'):
                    # "\ No newline at end of file": drop the newline
                    _drop_newline(hunk, lines[index - 1][:1])
                    index += 1
                    continue
                tag, content = body[:1], body[1:]
                if body in ('\n', '\r\n'):
                    tag, content = ' ', body
                if tag == ' ':
                    hunk.old.append(content)
                    hunk.new.append(content)
                elif tag == '-':
                    hunk.old.append(content)
                elif tag == '+':
                    hunk.new.append(content)
                else:
                    raise PatchError(
                        f"patch '{patch_name}' line {index + 1}: hunk "
                        f'#{hunk.number} of {current.path} ends early '
                        f'(expected {old_len} old and {new_len} new lines)')
                index += 1
            if index < len(lines) and lines[index].startswith('\\'):
                _drop_newline(hunk, lines[index - 1][:1])
                index += 1
            current.hunks.append(hunk)
            continue
        index += 1
    if not diffs:
        raise PatchError(f"patch '{patch_name}' contains no file changes")
    return diffs


def _drop_newline(hunk, tag):
    targets = {'-': [hunk.old], '+': [hunk.new], ' ': [hunk.old, hunk.new]}
    for target in targets.get(tag, []):
        if target and target[-1].endswith('\n'):
            target[-1] = target[-1][:-1]


def _find(lines, block, expected):
    """Find `block` in `lines`, nearest to `expected` first."""
    if not block:
        return min(max(expected, 0), len(lines))
    limit = len(lines) - len(block)
    for distance in range(0, max(limit, 0) + len(lines) + 1):
        for position in (expected - distance, expected + distance):
            if 0 <= position <= limit and \
                    lines[position:position + len(block)] == block:
                return position
        if expected - distance < 0 and expected + distance > limit:
            break
    return None


def apply_file_diff(lines, diff, *, package, patch_name):
    """
    Apply the hunks of one file to its lines.

    A hunk whose result is already present is skipped, so applying a patch
    twice changes nothing.

    :returns: the new lines
    :raises PatchError: naming package, patch file, hunk and line
    """
    result = list(lines)
    offset = 0
    for hunk in diff.hunks:
        expected = hunk.old_start - 1 + offset
        position = _find(result, hunk.old, expected)
        if position is None:
            if hunk.new and _find(result, hunk.new, expected) is not None:
                continue  # already applied
            first = next((line for line in hunk.old
                          if line not in result), hunk.old[0]
                         if hunk.old else '')
            raise PatchError(
                f"package '{package}': patch '{patch_name}' hunk "
                f'#{hunk.number} (patch line {hunk.line_in_patch}, '
                f'{diff.path} near line {hunk.old_start}) does not apply: '
                f'the source has no line {first.rstrip()!r}; the package '
                'version may not match the patch: fix the patch or its '
                "'versions' range in the recipe")
        result[position:position + len(hunk.old)] = hunk.new
        offset = position - (hunk.old_start - 1) + \
            len(hunk.new) - len(hunk.old)
    return result


def apply_patches(tree, patch_files, *, package, strip=None):
    """
    Apply patches to a folder, all or nothing.

    Every patch is applied in memory first; files are written only when all
    hunks of all patches applied.

    :param pathlib.Path tree: the folder to patch (a copy of the source)
    :param patch_files: the patch files, in order
    :param str package: the package name, for messages
    :param int strip: leading path components to remove (`patch -p`)
    :raises PatchError: when a patch does not apply
    """
    contents = {}
    for patch_file in patch_files:
        patch_file = Path(patch_file)
        try:
            text = patch_file.read_text(encoding='utf-8', errors='surrogateescape')
        except OSError as e:
            raise PatchError(
                f"package '{package}': cannot read patch '{patch_file}': "
                f'{e.strerror}') from e
        for diff in parse_patch(text, patch_file.name, strip):
            target = tree / diff.path
            if not _is_inside(target, tree):
                raise PatchError(
                    f"package '{package}': patch '{patch_file.name}' "
                    f"writes outside the package: '{diff.path}'")
            if diff.path not in contents:
                if diff.old_path == '/dev/null':
                    contents[diff.path] = []
                elif target.is_file():
                    # any bytes survive (surrogateescape): sources need not be UTF-8
                    contents[diff.path] = target.read_text(
                        encoding='utf-8', errors='surrogateescape').splitlines(keepends=True)
                else:
                    raise PatchError(
                        f"package '{package}': patch '{patch_file.name}' "
                        f"changes '{diff.path}' which does not exist in the "
                        'package')
            if diff.new_path == '/dev/null':
                contents[diff.path] = None
                continue
            contents[diff.path] = apply_file_diff(
                contents[diff.path], diff, package=package,
                patch_name=patch_file.name)
    for relative, lines in contents.items():
        target = tree / relative
        if lines is None:
            if target.exists():
                target.unlink()
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(''.join(lines), encoding='utf-8', errors='surrogateescape')


def _is_inside(path, folder):
    try:
        path.resolve().relative_to(folder.resolve())
    except ValueError:
        return False
    return True


def source_fingerprint(source, patch_files):
    """
    Hash what a patched copy depends on.

    :returns: a hex digest over the source files (path, size, mtime) and
      the content of every patch
    """
    digest = hashlib.sha256()
    for root, dirs, files in os.walk(source):
        dirs[:] = sorted(d for d in dirs if d not in _IGNORED_NAMES)
        for name in sorted(files):
            path = Path(root, name)
            try:
                stat = path.stat()
            except OSError:
                continue
            digest.update(
                f'{path.relative_to(source)}\0{stat.st_size}\0'
                f'{stat.st_mtime_ns}\0'.encode())
    for patch_file in patch_files:
        digest.update(Path(patch_file).read_bytes())
    return digest.hexdigest()


def prepare_patched_source(source, destination, patch_files, *, package):
    """
    Get a patched copy of a package's source.

    :param pathlib.Path source: the package folder (read only)
    :param pathlib.Path destination: where the patched copy lives
    :param patch_files: the patches to apply (none: the source is returned)
    :param str package: the package name, for messages
    :returns: the folder to build from
    :raises PatchError: when a patch does not apply (nothing is changed)
    """
    source = Path(source)
    destination = Path(destination)
    if not patch_files:
        return source
    fingerprint = source_fingerprint(source, patch_files)
    stamp = destination / STAMP_NAME
    if stamp.is_file() and stamp.read_text() == fingerprint:
        return destination
    staging = destination.with_name(destination.name + '.tmp')
    if staging.exists():
        shutil.rmtree(staging)
    try:
        shutil.copytree(
            source, staging, symlinks=True,
            ignore=shutil.ignore_patterns(*_IGNORED_NAMES))
        apply_patches(staging, patch_files, package=package)
        (staging / STAMP_NAME).write_text(fingerprint)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    if destination.exists():
        old = destination.with_name(destination.name + '.old')
        if old.exists():
            shutil.rmtree(old)
        destination.rename(old)
        staging.rename(destination)
        shutil.rmtree(old)
    else:
        destination.parent.mkdir(parents=True, exist_ok=True)
        staging.rename(destination)
    return destination
