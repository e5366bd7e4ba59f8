# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The patch engine: copies, all-or-nothing, idempotent."""

from pathlib import Path

from colcon_helpers import REPO
from colcon_helpers import tree_digest
from colcon_wasm.patch import apply_patches
from colcon_wasm.patch import parse_patch
from colcon_wasm.patch import PatchError
from colcon_wasm.patch import prepare_patched_source
import pytest

PATCH = """--- a/src/a.c
+++ b/src/a.c
@@ -1,3 +1,3 @@
 one
-two
+TWO
 three
@@ -6,3 +6,4 @@
 six
 seven
+seven and a half
 eight
--- /dev/null
+++ b/new.txt
@@ -0,0 +1,1 @@
+brand new
"""


def _source(tmp_path):
    src = tmp_path / 'pkg'
    (src / 'src').mkdir(parents=True)
    (src / 'src' / 'a.c').write_text(
        ''.join(f'{w}\n' for w in
                'one two three four five six seven eight nine'.split()))
    (src / 'CMakeLists.txt').write_text('project(pkg)\n')
    return src


def test_parse():
    diffs = parse_patch(PATCH, 'p.patch')
    assert [d.path for d in diffs] == ['src/a.c', 'new.txt']
    assert [h.number for h in diffs[0].hunks] == [1, 2]


def test_apply_and_apply_again(tmp_path):
    src = _source(tmp_path)
    patch = tmp_path / 'p.patch'
    patch.write_text(PATCH)
    apply_patches(src, [patch], package='pkg')
    text = (src / 'src' / 'a.c').read_text()
    assert 'TWO\n' in text and 'seven and a half\n' in text
    assert (src / 'new.txt').read_text() == 'brand new\n'
    digest = tree_digest(src)
    apply_patches(src, [patch], package='pkg')  # already applied: no change
    assert tree_digest(src) == digest


def test_offset_is_found(tmp_path):
    src = _source(tmp_path)
    text = (src / 'src' / 'a.c').read_text()
    (src / 'src' / 'a.c').write_text('zero\nzero again\n' + text)
    patch = tmp_path / 'p.patch'
    patch.write_text(PATCH)
    apply_patches(src, [patch], package='pkg')
    assert (src / 'src' / 'a.c').read_text().startswith(
        'zero\nzero again\none\nTWO\n')


def test_failing_hunk_changes_nothing(tmp_path):
    src = _source(tmp_path)
    bad = PATCH.replace(' seven\n+seven', ' SEVEN\n+seven')
    patch = tmp_path / 'bad.patch'
    patch.write_text(bad)
    digest = tree_digest(src)
    with pytest.raises(PatchError) as info:
        apply_patches(src, [patch], package='pkg')
    message = str(info.value)
    assert "package 'pkg': patch 'bad.patch' hunk #2" in message
    assert 'src/a.c near line 6' in message
    assert "the source has no line 'SEVEN'" in message
    # hunk #1 and new.txt were fine, but nothing was written
    assert tree_digest(src) == digest


def test_patched_copy_is_atomic(tmp_path):
    src = _source(tmp_path)
    good = tmp_path / 'good.patch'
    good.write_text(PATCH)
    dest = tmp_path / 'copies' / 'pkg'
    digest = tree_digest(src)
    assert prepare_patched_source(src, dest, [good], package='pkg') == dest
    assert (dest / 'new.txt').is_file()
    copy_digest = tree_digest(dest)
    # unchanged inputs: the copy is reused as it is
    prepare_patched_source(src, dest, [good], package='pkg')
    assert tree_digest(dest) == copy_digest
    # a failing patch leaves the previous copy and no staging folder
    bad = tmp_path / 'bad.patch'
    bad.write_text(PATCH.replace('-two\n+TWO', '-deux\n+DEUX'))
    with pytest.raises(PatchError):
        prepare_patched_source(src, dest, [good, bad], package='pkg')
    assert tree_digest(dest) == copy_digest
    assert not Path(str(dest) + '.tmp').exists()
    assert tree_digest(src) == digest


def test_no_patches_builds_from_source(tmp_path):
    src = _source(tmp_path)
    assert prepare_patched_source(
        src, tmp_path / 'x', [], package='pkg') == src
    assert not (tmp_path / 'x').exists()


def test_patch_outside_the_package_is_refused(tmp_path):
    src = _source(tmp_path)
    patch = tmp_path / 'evil.patch'
    patch.write_text('--- a/../x\n+++ b/../x\n@@ -0,0 +1 @@\n+x\n')
    with pytest.raises(PatchError, match='writes outside the package'):
        apply_patches(src, [patch], package='pkg')


def test_rcutils_patch_applies_to_humble(tmp_path):
    """The shipped rcutils patch applies to Humble's rcutils 5.1.x source."""
    humble = _humble_source()
    strerror = humble / 'ros2' / 'rcutils' / 'src' / 'strerror.c'
    if not strerror.is_file():
        pytest.skip(f'Humble sources not unpacked at {humble}')
    src = tmp_path / 'rcutils'
    (src / 'src').mkdir(parents=True)
    (src / 'src' / 'strerror.c').write_text(strerror.read_text())
    apply_patches(src, [REPO / 'patches' / 'rcutils' /
                        '0001-strerror_r-xsi-under-emscripten.patch'],
                  package='rcutils')
    assert '!defined(__EMSCRIPTEN__)' in (src / 'src' / 'strerror.c') \
        .read_text()


def _humble_source():
    from humble_build import unpacked_source
    return unpacked_source()
