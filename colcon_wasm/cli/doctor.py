# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""`colcon-wasm doctor`."""

from colcon_wasm.cli import CliExtensionPoint
from colcon_wasm.doctor import run_checks


class DoctorCommand(CliExtensionPoint):
    """Check Emscripten, CMake, a C++ compiler, Node.js, Chromium and the Python dependencies."""

    def add_arguments(self, *, parser):  # noqa: D102
        parser.add_argument(
            '--wasm-emscripten', metavar='PATH',
            help='Check this Emscripten instead of the default lookup')

    def main(self, *, args):  # noqa: D102
        checks = run_checks(args.wasm_emscripten)
        for check in checks:
            print(check.line())
        missing = [c for c in checks if not c.ok and c.required]
        if missing:
            print(f'{len(missing)} required item(s) missing: '
                  + ', '.join(c.name for c in missing))
            return 1
        print('everything `colcon build --wasm` needs is here')
        return 0
