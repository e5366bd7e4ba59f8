# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The recipe schema: each check is tested by its message."""

from pathlib import Path

from colcon_wasm.recipe import default_recipe_path
from colcon_wasm.recipe import load_recipe
from colcon_wasm.recipe import load_recipe_file
from colcon_wasm.recipe import RecipeError
import pytest


def _write(tmp_path, text, name='r.yaml'):
    path = tmp_path / name
    path.write_text(text)
    return path


def _error(tmp_path, text):
    path = _write(tmp_path, text)
    with pytest.raises(RecipeError) as info:
        load_recipe_file(path)
    return str(info.value), path


def test_default_recipe_is_valid():
    recipe = load_recipe()
    assert recipe.name == 'humble'
    assert recipe.files == [default_recipe_path().resolve()]
    assert recipe.skip_reason('fastcdr')
    assert recipe.skip_reason('iceoryx_posh')  # glob pattern
    assert recipe.skip_reason('rmw_cyclonedds_cpp')
    assert recipe.skip_reason('rclcpp') is None
    assert 'ament_package' in recipe.host_tools
    rule = recipe.rule('rcutils')
    assert [p.file.name for p in rule.patches] == [
        '0001-strerror_r-xsi-under-emscripten.patch',
        '0002-shared_library-no-dlinfo-under-emscripten.patch',
        '0003-shared_library-linked-libraries-under-emscripten.patch']
    assert rule.patches[0].applies_to('5.1.6')
    assert not rule.patches[0].applies_to('6.0.0')
    assert 'yaml' in recipe.rule('libyaml_vendor').depends
    assert recipe.rule('libyaml_vendor').project_include.is_file()
    assert recipe.rule('no_such_package').cmake_args == []
    # Python parts: rclpy is dropped from C/C++ packages, tf2_py is skipped
    assert recipe.is_python_only('rclpy') and recipe.is_python_only('python_cmake_module')
    assert not recipe.is_python_only('fastcdr') and not recipe.is_python_only('rclcpp')
    assert recipe.skip_reason('tf2_py') and not recipe.is_python_only('tf2_py')
    # system dependencies
    assert recipe.system.rule('libconsole-bridge-dev').workspace == 'console_bridge'
    tinyxml = recipe.system.rule('tinyxml')
    assert tinyxml.kind == 'debian-source' and tinyxml.source_package == 'tinyxml'
    assert tinyxml.build_file.name == 'CMakeLists.txt' and tinyxml.build_file.is_file()
    assert recipe.system.rule('eigen').kind == 'host-headers'
    assert recipe.system.rule('python3-yaml').kind == 'host-tool'  # a glob
    assert recipe.system.rule('libopencv-dev') is None


def test_overlays_change_system_rules_and_python_only_skips(tmp_path):
    overlay = _write(tmp_path, """
skip:
  rclpy: native only here
system:
  eigen: {builtin: someone else provides it}
  libopencv-dev: {workspace: opencv, debian: libopencv-dev, note: from src/opencv}
""")
    recipe = load_recipe([overlay])
    assert recipe.skip_reason('rclpy') == 'native only here'
    assert not recipe.is_python_only('rclpy')
    assert recipe.system.rule('eigen').kind == 'builtin'
    rule = recipe.system.rule('libopencv-dev')
    assert (rule.workspace, rule.debian, rule.note) == (
        'opencv', 'libopencv-dev', 'from src/opencv')
    assert 'opencv' in rule.describe()


@pytest.mark.parametrize('text, line, message', [
    ('bogus: 1\n', 1, "'bogus': unknown key, expected one of: recipe"),
    ('system:\n  foo: {workspace: a, builtin: b}\n', 2,
     "'system.foo': expected exactly one of workspace, host-headers, debian-source, "
     'host-tool, builtin, got workspace, builtin'),
    ('system:\n  foo: {debian: x}\n', 2, "'system.foo': expected exactly one of"),
    ('system:\n  foo:\n    host-headers: {cmake-args: []}\n', 3,
     "'system.foo.host-headers': missing key 'check'"),
    ('system:\n  foo:\n    debian-source: {package: foo, build: nope.txt}\n', 3,
     "'system.foo.debian-source.build': CMake file"),
    ('system:\n  foo: {workspace: a, colour: b}\n', 2,
     "'system.foo.colour': unknown key, expected one of: workspace"),
    ('skip:\n  foo: {reason: x, python-only: maybe}\n', 2,
     "'skip.foo.python-only': expected true or false, got str 'maybe'"),
    ('recipe:\n  name: [a]\n', 2,
     "'recipe.name': expected a non-empty string, got a list"),
    ('skip:\n  fastcdr: 3\n', 2,
     "'skip.fastcdr': expected a non-empty string, got int 3"),
    ('skip:\n  "bad name!": x\n', 2,
     "'skip.bad name!': 'bad name!' is not a package name"),
    ('packages:\n  foo:\n    cmake-args: -DX=1\n', 3,
     "'packages.foo.cmake-args': expected a list of strings, got str"),
    ('packages:\n  foo:\n    cmake-args:\n      - -DX=1\n      - 2\n', 5,
     "'packages.foo.cmake-args[1]': expected a string, got int 2"),
    ('packages:\n  foo:\n    env:\n      1BAD: x\n', 4,
     "'packages.foo.env.1BAD': not a valid environment variable name"),
    ('packages:\n  foo:\n    patches:\n      - file: nope.patch\n', 4,
     "'packages.foo.patches[0].file': patch file"),
    ('packages:\n  foo:\n    patches:\n      - versions: "1"\n', 4,
     "'packages.foo.patches[0]': missing key 'file'"),
    ('packages:\n  foo:\n    project-include: none.cmake\n', 3,
     "'packages.foo.project-include': CMake file"),
    ('packages:\n  foo: [1]\n', 2,
     "'packages.foo': expected a mapping, got a list"),
    ('host-tools: ament_package\n', 1,
     "'host-tools': expected a list of strings"),
    ('- a\n- b\n', 1, 'expected a mapping with the keys'),
])
def test_errors_name_file_line_and_key(tmp_path, text, line, message):
    error, path = _error(tmp_path, text)
    assert error.startswith(f'{path.resolve()}:{line}: '), error
    assert message in error


def test_patch_version_range_is_checked(tmp_path):
    (tmp_path / 'p.patch').write_text('--- a/x\n+++ b/x\n')
    error, path = _error(
        tmp_path,
        'packages:\n  foo:\n    patches:\n      - file: p.patch\n'
        '        versions: "=>1"\n')
    assert f'{path.resolve()}:5:' in error
    assert "'=>1' is not a version range" in error


def test_yaml_syntax_error_has_line(tmp_path):
    error, path = _error(tmp_path, 'skip:\n  a: b\n  c: [d\n')
    assert error.startswith(f'{path.resolve()}:'), error
    assert 'invalid YAML' in error


def test_duplicate_key_is_an_error(tmp_path):
    error, _ = _error(tmp_path, 'skip:\n  a: x\n  a: y\n')
    assert "duplicate key 'a'" in error


def test_missing_file(tmp_path):
    with pytest.raises(RecipeError, match='cannot read recipe'):
        load_recipe([tmp_path / 'missing.yaml'])


def test_overlay_merges(tmp_path):
    (tmp_path / 'x.patch').write_text('--- a/x\n+++ b/x\n')
    overlay = _write(tmp_path, '\n'.join([
        'recipe: {version: 9}',
        'env: {EXTRA: "1"}',
        'unskip: [fastcdr]',
        'skip: {calc_lib: not today}',
        'host-tools: [my_tool]',
        'packages:',
        '  rcutils:',
        '    cmake-args: [-DMINE=ON]',
        '    patches: [x.patch]',
        '  libyaml_vendor:',
        '    depends: [extra]',
    ]) + '\n')
    recipe = load_recipe([overlay])
    assert recipe.name == 'humble' and recipe.version == '9'
    assert recipe.env['EXTRA'] == '1' and recipe.env['ROS_DISTRO'] == 'humble'
    assert recipe.skip_reason('fastcdr') is None
    assert recipe.skip_reason('calc_lib') == 'not today'
    assert recipe.host_tools[-1] == 'my_tool'
    rule = recipe.rule('rcutils')
    assert rule.cmake_args == ['-DMINE=ON']
    assert [p.file.name for p in rule.patches] == [
        '0001-strerror_r-xsi-under-emscripten.patch',
        '0002-shared_library-no-dlinfo-under-emscripten.patch',
        '0003-shared_library-linked-libraries-under-emscripten.patch', 'x.patch']
    assert rule.patches[-1].file == (tmp_path / 'x.patch').resolve()
    assert recipe.rule('libyaml_vendor').depends == ['yaml', 'extra']
    assert recipe.files[-1] == Path(overlay).resolve()


def test_patch_without_package_version(tmp_path):
    recipe = load_recipe()
    patch = recipe.rule('rcutils').patches[0]
    with pytest.raises(RecipeError, match='declares no version'):
        patch.applies_to(None)
