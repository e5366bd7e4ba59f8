# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Bad input gets a clear error, and nothing is built or lost."""

from pathlib import Path

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import tree_digest


def _built_packages(workspace):
    base = Path(workspace) / 'build_wasm'
    if not base.is_dir():
        return []
    return sorted(p.name for p in base.iterdir()
                  if p.is_dir() and not p.name.startswith('.'))


def _one_error_line(output):
    lines = [line for line in output.splitlines()
             if line.startswith('colcon build --wasm: ')]
    assert len(lines) == 1, output[-3000:]
    return lines[0]


def test_explicit_emscripten_that_is_not_one(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    result = colcon(ws, 'build', '--wasm', '--wasm-emscripten',
                    str(tmp_path / 'nowhere'), check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert f"--wasm-emscripten '{tmp_path / 'nowhere'}'" in line
    assert 'apt-get install emscripten' in line and 'emsdk' in line
    assert _built_packages(ws) == []


def test_too_old_emscripten(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    old = tmp_path / 'emsdk-1.39' / 'upstream' / 'emscripten'
    old.mkdir(parents=True)
    (old / 'emcc.py').write_text('# not run: the version file is read\n')
    (old / 'emscripten-version.txt').write_text('"1.39.20"\n')
    result = colcon(ws, 'build', '--wasm', '--wasm-emscripten',
                    str(tmp_path / 'emsdk-1.39'), check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert 'Emscripten 1.39.20' in line and 'too old' in line
    assert 'need 3.1.6 or newer' in line
    assert _built_packages(ws) == []


def test_broken_recipe_names_file_line_and_key(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    recipe = tmp_path / 'mine.yaml'
    recipe.write_text(
        '# my overlay\n'
        'packages:\n'
        '  calc_app:\n'
        '    cmake-arg: [-DFOO=1]\n')
    result = colcon(ws, 'build', '--wasm', '--wasm-recipe', str(recipe),
                    check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert f'{recipe}:4:' in line
    assert "'packages.calc_app.cmake-arg': unknown key" in line
    assert 'cmake-args' in line
    assert _built_packages(ws) == []


def test_recipe_yaml_syntax_error(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    recipe = tmp_path / 'broken.yaml'
    recipe.write_text('skip:\n  foo: [unclosed\n')
    result = colcon(ws, 'list', '--wasm', '--wasm-recipe', str(recipe),
                    check=False)
    assert result.returncode != 0
    assert f'{recipe}:' in result.stdout and 'invalid YAML' in result.stdout


def test_depending_on_a_skipped_dds_package(tmp_path):
    ws = copy_fixture('ws_dds_user', tmp_path)
    before = tree_digest(ws / 'src')
    result = colcon(ws, 'build', '--wasm', check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert '1 dependencies on packages that --wasm skips' in line
    assert "package 'dds_user' needs 'fastcdr' to build, which --wasm skips " \
        '(Fast DDS serialization library' in result.stdout
    assert 'drop-depends: [DEP]' in line
    assert _built_packages(ws) == []
    assert tree_digest(ws / 'src') == before


def test_dropping_a_skipped_dependency_is_allowed(tmp_path):
    ws = copy_fixture('ws_dds_user', tmp_path)
    recipe = tmp_path / 'drop.yaml'
    recipe.write_text(
        'packages:\n  dds_user:\n    drop-depends: [fastcdr]\n')
    result = colcon(ws, 'list', '--wasm', '--wasm-recipe', str(recipe))
    assert 'dds_user' in result.stdout


def test_workspace_without_packages(tmp_path):
    ws = copy_fixture('ws_empty', tmp_path)
    result = colcon(ws, 'build', '--wasm', check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert 'no packages found' in line and '--base-paths' in line


def test_wasm_over_a_native_build_folder(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--packages-select', 'calc_lib')
    cache = ws / 'build' / 'calc_lib' / 'CMakeCache.txt'
    before = cache.read_bytes()
    result = colcon(ws, 'build', '--wasm', '--build-base', 'build',
                    check=False)
    assert result.returncode != 0
    line = _one_error_line(result.stdout)
    assert f"build base '{ws / 'build'}' holds native builds" in line
    assert str(ws / 'build' / 'calc_lib') in line
    assert cache.read_bytes() == before  # nothing lost


def test_native_over_a_wasm_build_folder(tmp_path):
    ws = copy_fixture('ws_basic', tmp_path)
    colcon(ws, 'build', '--wasm', '--packages-select', 'calc_lib')
    result = colcon(ws, 'build', '--build-base', 'build_wasm', check=False)
    assert result.returncode != 0
    assert f"build base '{ws / 'build_wasm'}' holds --wasm builds" in \
        result.stdout
