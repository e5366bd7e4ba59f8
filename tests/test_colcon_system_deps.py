# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
System dependencies (rosdep keys) of --wasm builds (recipes/schema.md, system).

A key with no WebAssembly build is refused before configure with the
package, the key and what to do; TinyXML 1 is built from Debian's source
package (apt-get source, with Debian's patches) and used; a C++ package that
needs rclpy for its Python part only builds without it.
"""

from colcon_helpers import colcon
from colcon_helpers import copy_fixture
from colcon_helpers import node
import pytest


@pytest.fixture
def ws(tmp_path):
    """Copy the fixture workspace (never build in place)."""
    return copy_fixture('ws_system', tmp_path)


def test_a_key_with_no_wasm_build_is_refused_before_configure(ws):
    completed = colcon(ws, 'build', '--wasm', '--packages-select', 'needs_opencv', check=False)
    assert completed.returncode != 0
    assert "package 'needs_opencv' needs rosdep key 'libopencv-dev'" in completed.stdout
    assert 'has no WebAssembly build in this workspace: add its sources to the workspace' \
        in completed.stdout
    assert '--packages-skip needs_opencv' in completed.stdout
    # nothing was configured, and run-only keys (python3-numpy) are not checked
    assert not (ws / 'build_wasm' / 'needs_opencv' / 'CMakeCache.txt').exists()
    assert 'python3-numpy' not in completed.stdout


def test_a_missing_host_header_library_says_what_to_install(ws, tmp_path):
    overlay = tmp_path / 'overlay.yaml'
    overlay.write_text('system:\n  libopencv-dev:\n    host-headers: {check: /nonexistent/cv.h}\n'
                       '    debian: libopencv-dev\n')
    completed = colcon(ws, 'build', '--wasm', '--packages-select', 'needs_opencv',
                       '--wasm-recipe', str(overlay), check=False)
    assert completed.returncode != 0
    assert "'/nonexistent/cv.h' is missing: `apt-get install libopencv-dev`" in completed.stdout


def test_tinyxml_is_built_from_debian_sources_and_used(ws):
    colcon(ws, 'build', '--wasm', '--packages-up-to', 'uses_tinyxml')
    log = (ws / 'log' / 'latest_build' / 'logger_all.log').read_text()
    assert "Building rosdep key 'tinyxml' from Debian's source package 'tinyxml-2.6.2'" in log
    install = ws / 'install_wasm'
    assert (install / 'tinyxml' / 'lib' / 'libtinyxml.a').is_file()
    # Debian's patches are applied (enforce-use-stl)
    assert '#define TIXML_USE_STL' in (install / 'tinyxml' / 'include' / 'tinyxml.h').read_text()
    result = node(install / 'uses_tinyxml' / 'bin' / 'xml_count.js')
    assert result.stdout.strip() == 'ROOT robot name=r2 links=2', result.stdout + result.stderr
    # the source is cached once, outside the workspace, and src/ holds nothing new
    assert not (ws / 'src' / 'tinyxml').exists()


def test_python_only_dependencies_are_dropped_from_cpp_packages(ws):
    colcon(ws, 'build', '--wasm', '--packages-select', 'mixed_python')
    log = (ws / 'log' / 'latest_build' / 'logger_all.log').read_text()
    assert "Building 'mixed_python' without 'rclpy': only its Python part needs them" in log
    result = node(ws / 'install_wasm' / 'mixed_python' / 'bin' / 'answer.js')
    assert result.stdout.strip() == 'ANSWER 42'
