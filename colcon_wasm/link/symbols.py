# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The symbols of link inputs that decide what a ROS executable loads.

`llvm-nm` lists each object (and each archive member); only the symbols
below are kept, in a cache keyed by the file's path, size and time.
"""

import hashlib
import json
import os
import subprocess

from colcon_wasm.error import ColconWasmError

"""A class_loader registration: the instantiation of registerPlugin<D, B>."""
REGISTRATION_PREFIX = '_ZN12class_loader4impl14registerPlugin'

"""pluginlib::ClassLoader<Base> (any member function, const or not)."""
PLUGINLIB_PREFIXES = ('_ZN9pluginlib11ClassLoaderI', '_ZNK9pluginlib11ClassLoaderI')

"""The constructor of rclcpp_components::ComponentManager (C1 or C2)."""
COMPONENT_MANAGER_PREFIX = '_ZN17rclcpp_components16ComponentManagerC'

"""Defined by a container that hosts a fixed set of components."""
FIXED_COMPONENTS_MARKER = 'colcon_wasm_fixed_components'

"""Definitions that make an object a program's entry point."""
MAIN_SYMBOLS = ('main', '__main_argc_argv', '__original_main')

CACHE_SCHEMA = 1


class SymbolError(ColconWasmError):
    """llvm-nm could not read a link input."""


class ObjectSymbols:
    """What one object file (or archive member) defines and uses."""

    def __init__(self, name):
        """Start an empty record for the object `name`."""
        self.name = name
        self.registrations = []
        self.pluginlib = []
        self.defines_main = False
        self.uses_component_manager = False
        self.fixed_components = False

    def add(self, kind, symbol):
        """Record one `llvm-nm` line (kind letter, symbol name)."""
        defined = kind not in ('U', 'w', 'v')
        if symbol.startswith(REGISTRATION_PREFIX) and defined:
            self.registrations.append(symbol)
        elif symbol.startswith(PLUGINLIB_PREFIXES):
            self.pluginlib.append(symbol)
        elif symbol in MAIN_SYMBOLS and defined:
            self.defines_main = True
        elif symbol.startswith(COMPONENT_MANAGER_PREFIX) and not defined:
            self.uses_component_manager = True
        elif symbol == FIXED_COMPONENTS_MARKER and defined:
            self.fixed_components = True

    def to_json(self):
        """Describe the record for the cache."""
        return {'name': self.name, 'registrations': self.registrations,
                'pluginlib': self.pluginlib, 'defines_main': self.defines_main,
                'uses_component_manager': self.uses_component_manager,
                'fixed_components': self.fixed_components}

    @classmethod
    def from_json(cls, data):
        """Read a record back from the cache."""
        record = cls(data['name'])
        record.registrations = list(data['registrations'])
        record.pluginlib = list(data['pluginlib'])
        record.defines_main = bool(data['defines_main'])
        record.uses_component_manager = bool(data['uses_component_manager'])
        record.fixed_components = bool(data['fixed_components'])
        return record


def parse_nm_output(text, single_object_name):
    """
    Split `llvm-nm` output into one record per object, in file order.

    :param str text: what `llvm-nm FILE` printed
    :param str single_object_name: the record name for a plain object file
      (its output has no member headers)
    :rtype: list of ObjectSymbols
    """
    records = []
    current = None
    for line in text.splitlines():
        if not line.strip():
            continue
        if line.endswith(':') and not line.startswith(' ') and \
                len(line.split()) == 1:
            current = ObjectSymbols(line[:-1])
            records.append(current)
            continue
        parts = line.split()
        if len(parts) < 2:
            continue
        kind, symbol = parts[-2], parts[-1]
        if current is None:
            current = ObjectSymbols(single_object_name)
            records.append(current)
        current.add(kind, symbol)
    return records


class SymbolReader:
    """Read link inputs with llvm-nm, once per file version."""

    def __init__(self, nm, cache_folder):
        """
        Use an `llvm-nm` and a cache folder.

        :param str nm: the llvm-nm command of the Emscripten in use
        :param str cache_folder: where records are kept
        """
        self.nm = nm
        self.cache_folder = cache_folder

    def read(self, path):
        """
        Get the records of an object or an archive's members.

        :raises SymbolError: when llvm-nm fails on the file
        :rtype: list of ObjectSymbols
        """
        status = os.stat(path)
        key = hashlib.sha256(json.dumps(
            [os.path.realpath(path), status.st_size, status.st_mtime_ns,
             CACHE_SCHEMA]).encode()).hexdigest()[:32]
        entry = os.path.join(self.cache_folder, 'nm', key + '.json')
        try:
            with open(entry) as handle:
                return [ObjectSymbols.from_json(r) for r in json.load(handle)]
        except (OSError, ValueError, KeyError):
            pass
        completed = subprocess.run(
            [self.nm, '--no-sort', path], stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, universal_newlines=True)
        if completed.returncode != 0:
            raise SymbolError(
                f"llvm-nm could not read '{path}': {completed.stderr.strip()}")
        records = parse_nm_output(completed.stdout, os.path.basename(path))
        os.makedirs(os.path.dirname(entry), exist_ok=True)
        staging = f'{entry}.{os.getpid()}'
        with open(staging, 'w') as handle:
            json.dump([r.to_json() for r in records], handle)
        os.replace(staging, entry)
        return records


def demangle(cxxfilt, symbols):
    """
    Demangle C++ symbols with llvm-cxxfilt (one call for all of them).

    :returns: {mangled: demangled}
    """
    symbols = sorted(set(symbols))
    if not symbols:
        return {}
    completed = subprocess.run(
        [cxxfilt], input='\n'.join(symbols) + '\n', stdout=subprocess.PIPE,
        universal_newlines=True, check=True)
    return dict(zip(symbols, completed.stdout.splitlines()))


def template_arguments(text, template):
    """
    Get the template arguments of the first `template<...>` in a name.

    `template_arguments('void a::f<x::Y, B<c> >(int)', 'a::f')` gives
    `['x::Y', 'B<c>']`.

    :returns: the arguments, or None when `template<` is not in the text
    """
    start = text.find(template + '<')
    if start < 0:
        return None
    position = start + len(template) + 1
    depth = 0
    arguments = []
    current = ''
    while position < len(text):
        char = text[position]
        position += 1
        if char == '<':
            depth += 1
        elif char == '>':
            if depth == 0:
                arguments.append(current.strip())
                return arguments
            depth -= 1
        elif char == ',' and depth == 0:
            arguments.append(current.strip())
            current = ''
            continue
        current += char
    return None
