# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm doctor`'s checks of CMake and the native C++ compiler."""

from pathlib import Path
import re

from colcon_wasm import doctor

REPO = Path(__file__).resolve().parents[1]


def _script(folder, name, body):
    """Write an executable shell script ``folder/name`` running ``body``."""
    path = folder / name
    path.write_text(f'#!/bin/sh\n{body}\n')
    path.chmod(0o755)
    return path


def _only_path(monkeypatch, folder):
    """Make ``folder`` the whole PATH, with CMAKE_COMMAND and CXX unset."""
    monkeypatch.setenv('PATH', str(folder))
    monkeypatch.delenv('CMAKE_COMMAND', raising=False)
    monkeypatch.delenv('CXX', raising=False)


def test_both_checks_pass_on_this_machine():
    cmake = doctor.check_cmake()
    assert cmake.ok, cmake.line()
    assert re.match(r'\d+\.\d+', cmake.detail), cmake.detail
    cxx = doctor.check_cxx()
    assert cxx.ok, cxx.line()
    assert 'C++17 builds and runs' in cxx.detail
    assert not cxx.required


def test_doctor_runs_both_checks():
    names = [c.name for c in doctor.run_checks()]
    assert names[:3] == ['Emscripten', 'CMake', 'C++ compiler'], names


def test_no_cmake_on_path(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    check = doctor.check_cmake()
    assert not check.ok and check.required
    assert 'no `cmake` on PATH' in check.detail
    assert 'CMAKE_COMMAND is unset' in check.detail
    assert 'sudo apt-get install -y cmake' in check.fix
    line = check.line()
    assert line.strip().startswith('MISSING  CMake:'), line


def test_cmake_too_old(monkeypatch, tmp_path):
    cmake = _script(tmp_path, 'cmake', 'echo "cmake version 3.2.0"')
    _only_path(monkeypatch, tmp_path)
    check = doctor.check_cmake()
    assert not check.ok
    assert check.detail == f'3.2.0 at {cmake}, need 3.16 or newer', check.detail
    assert 'install CMake 3.16 or newer' in check.fix


def test_cmake_new_enough_and_from_cmake_command(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    cmake = _script(tmp_path, 'my-cmake', 'echo "cmake version 3.16.0-rc2"')
    monkeypatch.setenv('CMAKE_COMMAND', str(cmake))
    check = doctor.check_cmake()
    assert check.ok, check.line()
    assert check.detail == f'3.16.0-rc2 at {cmake}'


def test_cmake_command_naming_nothing(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    monkeypatch.setenv('CMAKE_COMMAND', str(tmp_path / 'absent'))
    check = doctor.check_cmake()
    assert not check.ok
    assert f'CMAKE_COMMAND={tmp_path / "absent"} is no program' in check.detail


def test_cmake_printing_no_version(monkeypatch, tmp_path):
    _script(tmp_path, 'cmake', 'echo "something else"')
    _only_path(monkeypatch, tmp_path)
    check = doctor.check_cmake()
    assert not check.ok and 'printed no version' in check.detail


def test_minimum_cmake_is_what_the_packages_and_readme_ask_for():
    asked = []
    for lists in sorted(REPO.glob('packages/*/CMakeLists.txt')):
        match = re.search(r'cmake_minimum_required\(VERSION (\d+)\.(\d+)', lists.read_text())
        assert match, lists
        asked.append((int(match.group(1)), int(match.group(2))))
    assert max(asked) == doctor.MINIMUM_CMAKE
    readme = (REPO / 'README.md').read_text(encoding='utf-8')
    major, minor = doctor.MINIMUM_CMAKE
    assert f'CMake ≥ {major}.{minor}' in readme


def test_no_cxx_on_path(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    check = doctor.check_cxx()
    assert not check.ok and not check.required
    assert check.detail == 'CXX is unset and no c++, g++, clang++ on PATH'
    assert 'sudo apt-get install -y g++' in check.fix
    assert check.line().strip().startswith('missing (optional)  C++ compiler:')


def test_cxx_naming_nothing(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    monkeypatch.setenv('CXX', 'no-such-compiler -O2')
    check = doctor.check_cxx()
    assert not check.ok
    assert check.detail == 'CXX=no-such-compiler -O2 names no program'


def test_cxx_failing_shows_its_message(monkeypatch, tmp_path):
    compiler = _script(tmp_path, 'broken-c++',
                       'echo "broken-c++: fatal error: cannot find $1" >&2\nexit 1')
    _only_path(monkeypatch, tmp_path)
    monkeypatch.setenv('CXX', f'{compiler} -Wall')
    check = doctor.check_cxx()
    assert not check.ok
    assert check.detail.startswith(f'{compiler} -Wall failed to build a C++17 program '
                                   '(exit 1): '), check.detail
    # the compiler's own stderr
    assert 'broken-c++: fatal error: cannot find -Wall' in check.detail


def test_cxx_building_something_else(monkeypatch, tmp_path):
    # exits 0 and writes a program that prints the wrong thing (a cross compiler, say)
    compiler = _script(tmp_path, 'c++', '[ "$1" = --version ] && exit 0\n'
                       'for a; do out="$a"; done\n'
                       'printf "%s\\n" "#!/bin/sh" "echo other" > "$out"; /bin/chmod +x "$out"')
    _only_path(monkeypatch, tmp_path)
    check = doctor.check_cxx()
    assert not check.ok
    assert f'the C++17 program {compiler} built does not run here' in check.detail
    assert check.detail.endswith("(exit 0, printed 'other', not 'c++17'): no message"), \
        check.detail


def test_cxx_that_cannot_be_split(monkeypatch, tmp_path):
    _only_path(monkeypatch, tmp_path)
    monkeypatch.setenv('CXX', '"g++')
    check = doctor.check_cxx()
    assert not check.ok and 'CXX="g++ cannot be split into words' in check.detail
