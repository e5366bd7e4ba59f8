# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Compile C/C++ to WebAssembly with clang directly, as emcc would.

CMake runs this script as the compiler launcher of a `--wasm` build
(`CMAKE_<LANG>_COMPILER_LAUNCHER`, see toolchains/wasm-ros.cmake)::

    python3 -I -S compile_launcher.py --cache DIR --root ROOT -- \
        /usr/bin/em++ <flags> -c src.cpp -o src.cpp.o

For a compile-only command emcc computes the clang command line (target,
sysroot, defines, `-mllvm` options for exceptions, ...) from a few of its
arguments, then runs clang. emcc is a Python program that takes about 0.3 s
to start; clang compiles a small file in less. This launcher asks emcc once
which clang command it runs for a given set of flags (`emcc -v`, the same
probe `emcc --cflags` uses) and keeps the answer in a cache folder. Later
compiles with the same flags run that clang command directly.

Arguments are split into two kinds. *Pass-through* arguments are the ones
emcc hands to clang unchanged and that never change what emcc adds:
include folders, macro definitions, dependency-file options, `-c`, `-o` and
the source. Every other argument (optimization, `-f`, `-m`, `-W`, `-s`
settings, `-pthread`, ...) is part of the cache key and goes through the
emcc probe, so emcc decides what clang sees. Anything unusual (no `-c`, no
single C/C++ source, response files holding other arguments, emcc's own
`--` options, LTO, preprocessing only) runs emcc itself.

Set `COLCON_WASM_LAUNCHER_VERIFY=1` to compile every file both ways and
fail on any difference of the object files.

This file must stay importable without colcon or any third-party module:
it runs once per translation unit, with Python's site packages off (it
imports only :mod:`colcon_wasm.error`, which needs nothing else).
"""

import hashlib
import json
import os
import shlex
import sys

if __package__ in (None, ''):
    # run as a script with site packages off: import colcon_wasm from beside it
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from colcon_wasm.error import ColconWasmError  # noqa: E402 (after the path)

"""Source file suffixes compiled through the fast path."""
SOURCE_SUFFIXES = ('.c', '.cc', '.cp', '.cpp', '.cxx', '.c++', '.C', '.CPP')

"""Arguments followed by a value that emcc passes through unchanged."""
PASS_THROUGH_WITH_VALUE = (
    '-I', '-isystem', '-iquote', '-idirafter', '-D', '-U', '-MT', '-MF',
    '-MQ', '-include')

"""Prefixes of one-word arguments emcc passes through unchanged."""
PASS_THROUGH_PREFIXES = (
    '-I', '-D', '-U', '-isystem', '-iquote', '-idirafter')

"""One-word arguments emcc passes through unchanged."""
PASS_THROUGH_FLAGS = ('-MD', '-MMD', '-MP')

"""Arguments that make this launcher hand the command to emcc."""
EMCC_ONLY = ('-E', '-S', '-M', '-MM', '-fsyntax-only', '-emit-llvm', '-v',
             '-###', '--cflags')

"""Environment variables emcc reads while it builds the clang command."""
ENVIRONMENT_PREFIXES = ('EMCC_', 'EM_', 'EMMAKEN_', 'EMSDK')

VERIFY_VARIABLE = 'COLCON_WASM_LAUNCHER_VERIFY'


class Unsupported(ColconWasmError):
    """The command is not a plain compile: emcc runs it."""


def read_response_file(argument):
    """Expand `@file` the way clang and emcc do (shell-like quoting)."""
    with open(argument[1:], encoding='utf-8') as handle:
        return shlex.split(handle.read())


def split_arguments(arguments):
    """
    Split a compile command's arguments for the fast path.

    :param list arguments: the arguments after the compiler
    :returns: (key arguments, pass-through arguments, source, output)
    :raises Unsupported: when emcc has to run the command itself
    """
    expanded = []
    for argument in arguments:
        if argument.startswith('@'):
            expanded += read_response_file(argument)
        else:
            expanded.append(argument)
    key, passed, sources = [], [], []
    output = None
    compile_only = False
    index = 0
    while index < len(expanded):
        argument = expanded[index]
        index += 1
        if argument in EMCC_ONLY or argument.startswith(('--', '-flto')):
            raise Unsupported(argument)
        if argument == '-c':
            compile_only = True
        elif argument == '-o':
            if index >= len(expanded):
                raise Unsupported('-o without a value')
            output = expanded[index]
            index += 1
        elif argument in PASS_THROUGH_WITH_VALUE:
            if index >= len(expanded):
                raise Unsupported(f'{argument} without a value')
            passed += [argument, expanded[index]]
            index += 1
        elif argument in PASS_THROUGH_FLAGS or \
                argument.startswith(PASS_THROUGH_PREFIXES):
            passed.append(argument)
        elif argument.startswith('-'):
            key.append(argument)
        else:
            sources.append(argument)
    if not compile_only or output is None or len(sources) != 1:
        raise Unsupported('not a compile of one source to one object')
    source = sources[0]
    if os.path.splitext(source)[1] not in SOURCE_SUFFIXES:
        raise Unsupported(f'source type of {source}')
    if '-x' in key:
        raise Unsupported('-x')
    return key, passed, source, output


def emscripten_stamp(root):
    """Describe the Emscripten installation (changes when it is updated)."""
    stamp = []
    for name in ('emscripten-version.txt', 'emcc.py', '.emscripten'):
        try:
            status = os.stat(os.path.join(root, name))
        except OSError:
            continue
        stamp.append([name, status.st_size, status.st_mtime_ns])
    return stamp


def cache_key(compiler, key_arguments, suffix, root):
    """Hash everything emcc's choice of clang command depends on."""
    environment = sorted(
        (name, value) for name, value in os.environ.items()
        if name.startswith(ENVIRONMENT_PREFIXES))
    data = json.dumps([compiler, key_arguments, suffix, environment,
                       emscripten_stamp(root)])
    return hashlib.sha256(data.encode()).hexdigest()[:32]


def probe(compiler, key_arguments, suffix, folder):
    """
    Ask emcc which clang command it runs for these arguments.

    :returns: the clang command without source, output and `-c`, or None
      when emcc's answer cannot be read
    """
    import subprocess  # only when the cache misses
    import tempfile
    with tempfile.TemporaryDirectory(dir=folder) as scratch:
        source = os.path.join(scratch, 'colcon_wasm_probe' + suffix)
        output = os.path.join(scratch, 'colcon_wasm_probe.o')
        with open(source, 'w') as handle:
            handle.write('int colcon_wasm_probe;\n')
        completed = subprocess.run(
            [compiler, '-v', '-c', source, '-o', output] + key_arguments,
            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            universal_newlines=True)
        if completed.returncode != 0:
            return None
        for line in completed.stderr.splitlines():
            if source not in line or output not in line:
                continue
            try:
                parts = shlex.split(line)
            except ValueError:
                continue
            if not parts or 'emcc' in os.path.basename(parts[0]) or \
                    'em++' in os.path.basename(parts[0]):
                continue
            command = []
            skip_next = False
            for part in parts:
                if skip_next:
                    skip_next = False
                elif part == '-o':
                    skip_next = True
                elif part not in ('-c', '-v', source):
                    command.append(part)
            return command
    return None


def clang_command(compiler, arguments, cache_folder, root):
    """
    Get the clang command emcc would run, or None when emcc must run.

    :param str compiler: the emcc or em++ CMake calls
    :param list arguments: its arguments
    :param str cache_folder: where probe results are kept
    :param str root: the Emscripten root (for the cache key)
    """
    try:
        key_arguments, passed, source, output = split_arguments(arguments)
    except (Unsupported, OSError, ValueError):
        return None
    suffix = os.path.splitext(source)[1]
    entry = os.path.join(
        cache_folder, cache_key(compiler, key_arguments, suffix, root)
        + '.json')
    try:
        with open(entry) as handle:
            prefix = json.load(handle)['command']
    except (OSError, ValueError, KeyError):
        os.makedirs(cache_folder, exist_ok=True)
        prefix = probe(compiler, key_arguments, suffix, cache_folder)
        staging = f'{entry}.{os.getpid()}'
        with open(staging, 'w') as handle:
            json.dump({'compiler': compiler, 'arguments': key_arguments,
                       'suffix': suffix, 'command': prefix}, handle)
        os.replace(staging, entry)
    if not prefix:
        return None
    return prefix + passed + ['-c', source, '-o', output]


def verify(command, compiler, arguments):
    """Compile with emcc too and compare the object files."""
    import subprocess
    output = arguments[arguments.index('-o') + 1] if '-o' in arguments \
        else None
    status = subprocess.call(command)
    if status or output is None:
        return status
    with open(output, 'rb') as handle:
        fast = handle.read()
    reference = output + '.emcc'
    emcc_arguments = list(arguments)
    emcc_arguments[emcc_arguments.index('-o') + 1] = reference
    status = subprocess.call([compiler] + emcc_arguments)
    if status:
        return status
    with open(reference, 'rb') as handle:
        same = handle.read() == fast
    os.unlink(reference)
    if not same:
        sys.stderr.write(
            f'colcon-wasm compile launcher: {output} differs from what '
            f'emcc makes\n  clang: {shlex.join(command)}\n  emcc:  '
            f'{shlex.join([compiler] + arguments)}\n')
        return 1
    return 0


def parse_command_line(argv):
    """Split `--cache DIR --root ROOT -- compiler args...`."""
    options = {'--cache': None, '--root': ''}
    index = 0
    while index < len(argv) and argv[index] != '--':
        if argv[index] not in options or index + 1 >= len(argv):
            raise SystemExit(
                f'compile_launcher.py: unknown argument {argv[index]!r}; '
                'usage: compile_launcher.py --cache DIR [--root ROOT] -- '
                'COMPILER ARGS...')
        options[argv[index]] = argv[index + 1]
        index += 2
    command = argv[index + 1:]
    if not command or not options['--cache']:
        raise SystemExit(
            'compile_launcher.py: usage: compile_launcher.py --cache DIR '
            '[--root ROOT] -- COMPILER ARGS...')
    return options['--cache'], options['--root'], command[0], command[1:]


def main(argv=None):
    """Run one compile command (never returns on the fast path)."""
    cache_folder, root, compiler, arguments = parse_command_line(
        sys.argv[1:] if argv is None else argv)
    command = clang_command(compiler, arguments, cache_folder, root)
    if command is None:
        command = [compiler] + arguments
    elif os.environ.get(VERIFY_VARIABLE):
        return verify(command, compiler, arguments)
    sys.stdout.flush()
    os.execvp(command[0], command)


if __name__ == '__main__':
    sys.exit(main())
