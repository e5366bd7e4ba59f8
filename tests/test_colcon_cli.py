# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""The `colcon-wasm` command and its `doctor` subcommand."""

import subprocess

from colcon_helpers import tool
from colcon_wasm import doctor


def test_subcommands_are_entry_points():
    result = subprocess.run([tool('colcon-wasm'), '--help'],
                            capture_output=True, text=True)
    assert result.returncode == 0
    assert 'doctor' in result.stdout


def test_doctor_reports_every_check():
    result = subprocess.run([tool('colcon-wasm'), 'doctor'],
                            capture_output=True, text=True)
    for name in ('Emscripten', 'CMake', 'C++ compiler', 'Node.js', 'Chromium',
                 'Python: colcon-core', 'Python: empy'):
        assert name in result.stdout, name
    failed = [c for c in doctor.run_checks() if c.required and not c.ok]
    assert result.returncode == (1 if failed else 0), result.stdout


def test_doctor_says_how_to_fix(tmp_path):
    result = subprocess.run(
        [tool('colcon-wasm'), 'doctor', '--wasm-emscripten',
         str(tmp_path / 'none')], capture_output=True, text=True)
    assert result.returncode == 1
    line = next(line for line in result.stdout.splitlines()
                if 'Emscripten:' in line)
    assert line.strip().startswith('MISSING')
    assert 'apt-get install emscripten' in line
    assert 'required item(s) missing: Emscripten' in result.stdout


def test_node_check_parses_versions(monkeypatch):
    monkeypatch.setattr(doctor, '_run_version', lambda command: 'v18.19.0')
    monkeypatch.setattr(doctor.shutil, 'which', lambda name: '/x/node')
    check = doctor.check_node()
    assert not check.ok and 'need v20 or newer' in check.detail
    assert 'Node.js 20' in check.fix
