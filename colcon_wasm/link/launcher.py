# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The link launcher of `--wasm` builds (see :mod:`colcon_wasm.link`).

CMake runs it in front of every link command (`RULE_LAUNCH_LINK`)::

    python3 -I -S launcher.py --cache DIR --nm LLVM_NM --cxxfilt LLVM_CXXFILT \
        --bases BASE[:UNDERLAY...] -- em++ <flags> <objects> -o exe.js <libraries>

Anything but an executable link (an archive, a try_compile) runs unchanged.
With `--capture FILE --package PKG --build-dir DIR --install-prefix PREFIX`
it records the link line as a closure file instead of linking
(:mod:`colcon_wasm.link.closure`) and writes an empty output.
"""

import hashlib
import json
import os
import shlex
import subprocess
import sys

if __package__ in (None, ''):
    # run as a script with site packages off: import the sibling modules
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    from colcon_wasm.link import ament_index  # noqa: E402
    from colcon_wasm.link import archive  # noqa: E402
    from colcon_wasm.link import closure  # noqa: E402
    from colcon_wasm.link import report as link_report  # noqa: E402
    from colcon_wasm.link import symbols  # noqa: E402
    from colcon_wasm.link import test_link  # noqa: E402
else:
    from colcon_wasm.link import ament_index
    from colcon_wasm.link import archive
    from colcon_wasm.link import closure
    from colcon_wasm.link import report as link_report
    from colcon_wasm.link import symbols
    from colcon_wasm.link import test_link

"""Outputs that make a link command an executable link."""
EXECUTABLE_SUFFIXES = ('.js', '.mjs', '.html', '.wasm')

USAGE = ('usage: launcher.py --cache DIR --nm LLVM_NM --cxxfilt LLVM_CXXFILT '
         '[--bases B1:B2...] [--capture FILE --package PKG --build-dir DIR '
         '--install-prefix PREFIX] [--test-pre-js FILE] -- LINKER ARGS...')


def say(text):
    """Print a message of the launcher (CMake shows it in the build log)."""
    sys.stderr.write(f'colcon-wasm link: {text}\n')


def parse_command_line(argv):
    """Split the launcher's options from the link command."""
    options = {'--cache': None, '--nm': 'llvm-nm', '--cxxfilt': 'llvm-cxxfilt',
               '--bases': '', '--capture': None, '--package': '',
               '--build-dir': '', '--install-prefix': '', '--test-pre-js': None}
    index = 0
    while index < len(argv) and argv[index] != '--':
        if argv[index] not in options or index + 1 >= len(argv):
            raise SystemExit(f'launcher.py: unknown argument {argv[index]!r}; {USAGE}')
        options[argv[index]] = argv[index + 1]
        index += 2
    command = argv[index + 1:]
    if not command or not options['--cache']:
        raise SystemExit(f'launcher.py: {USAGE}')
    options['bases'] = [b for b in options['--bases'].split(os.pathsep) if b]
    return options, command


class LinkCommand:
    """The inputs and the output of one link command."""

    def __init__(self, command):
        """Read a link command, expanding response files."""
        self.command = list(command)
        self.arguments = []
        for argument in command[1:]:
            if argument.startswith('@') and os.path.isfile(argument[1:]):
                with open(argument[1:], encoding='utf-8') as handle:
                    self.arguments += shlex.split(handle.read())
            else:
                self.arguments.append(argument)
        self.output = None
        self.objects = []
        self.archives = []
        self.whole_archives = set()
        self.compile_only = '-c' in self.arguments
        whole = False
        index = 0
        while index < len(self.arguments):
            argument = self.arguments[index]
            index += 1
            if argument == '-o' and index < len(self.arguments):
                self.output = self.arguments[index]
                index += 1
            elif argument.startswith('-Wl,'):
                for flag in argument[4:].split(','):
                    if flag == '--whole-archive':
                        whole = True
                    elif flag == '--no-whole-archive':
                        whole = False
            elif argument.startswith('-'):
                continue
            elif argument.endswith('.a'):
                self.archives.append(argument)
                if whole:
                    self.whole_archives.add(argument)
            elif argument.endswith(('.o', '.obj')):
                self.objects.append(argument)

    @property
    def is_executable(self):
        """Check if this links an executable (not an archive or an object)."""
        driver = os.path.basename(self.command[0])
        return (not self.compile_only and self.output is not None and
                self.output.endswith(EXECUTABLE_SUFFIXES) and
                driver.startswith(('em++', 'emcc')))

    @property
    def pthread(self):
        """Check if the link uses threads (objects added must match)."""
        return '-pthread' in self.arguments or any(
            a.startswith('-sUSE_PTHREADS') for a in self.arguments)


class LinkPlan:
    """What the launcher adds to one executable link, and why."""

    def __init__(self, options, link):
        """Prepare a plan for a link command."""
        self.options = options
        self.link = link
        self.cache = options['--cache']
        self.reader = symbols.SymbolReader(options['--nm'], self.cache)
        self.bases = options['bases']
        self.extra_objects = []
        self.extra_archives = []
        self.registrations = {}   # library basename -> [[derived, base], ...]
        self.plugins = []
        self.components = []
        self.warnings = []
        self._seen_archives = set()
        self._base_classes = set()
        self._prefixes = None
        self.hosts_components = False

    def prefixes(self):
        """Get the package prefixes of the install chain (once)."""
        if self._prefixes is None:
            self._prefixes = ament_index.package_prefixes(self.bases)
        return self._prefixes

    def build(self):
        """Decide what to add; returns self."""
        hosts_components = False
        fixed = False
        pluginlib_symbols = []
        for path in self.link.objects:
            for record in self._records(path):
                hosts_components |= record.uses_component_manager
                fixed |= record.fixed_components
                pluginlib_symbols += record.pluginlib
        pending = list(self.link.archives)
        self.hosts_components = hosts_components and not fixed
        if self.hosts_components:
            pending += self._component_archives()
        registration_symbols = {}
        while pending or pluginlib_symbols:
            for path in pending:
                if os.path.basename(path) in self._seen_archives:
                    continue
                self._seen_archives.add(os.path.basename(path))
                for index, record in enumerate(self._records(path)):
                    pluginlib_symbols += record.pluginlib
                    if not record.registrations or path in self.link.whole_archives:
                        continue
                    if record.defines_main:
                        self.warnings.append(
                            f"'{record.name}' in '{path}' registers classes and defines "
                            'main(): its registrations are not linked (move them to a '
                            'source without main())')
                        continue
                    self.extra_objects.append(self._extract(path, index, record.name))
                    registration_symbols.setdefault(
                        os.path.basename(path), []).extend(record.registrations)
            pending = self._plugin_archives(pluginlib_symbols)
            pluginlib_symbols = []
        self._describe_registrations(registration_symbols)
        return self

    def _records(self, path):
        try:
            return self.reader.read(path)
        except (OSError, symbols.SymbolError) as e:
            self.warnings.append(str(e))
            return []

    def _extract(self, path, index, name):
        status = os.stat(path)
        key = hashlib.sha256(json.dumps(
            [os.path.realpath(path), status.st_size, status.st_mtime_ns]).encode()
        ).hexdigest()[:24]
        folder = os.path.join(self.cache, 'members', key)
        destination = os.path.join(folder, f'{index}-{os.path.basename(name)}')
        if not destination.endswith('.o'):
            destination += '.o'
        if not os.path.isfile(destination):
            os.makedirs(folder, exist_ok=True)
            archive.extract_member(path, index, destination)
        return destination

    def _describe_registrations(self, registration_symbols):
        every = [s for names in registration_symbols.values() for s in names]
        try:
            names = symbols.demangle(self.options['--cxxfilt'], every)
        except (OSError, subprocess.CalledProcessError) as e:
            self.warnings.append(f'cannot demangle registrations: {e}')
            names = {}
        for library, mangled in registration_symbols.items():
            classes = []
            for symbol in mangled:
                arguments = symbols.template_arguments(
                    names.get(symbol, ''), 'class_loader::impl::registerPlugin')
                if arguments and len(arguments) == 2 and arguments not in classes:
                    classes.append(arguments)
            self.registrations[library] = classes

    def _plugin_archives(self, pluginlib_symbols):
        """Get the archives of the plugins of every base class pluginlib loads."""
        try:
            names = symbols.demangle(self.options['--cxxfilt'], pluginlib_symbols)
        except (OSError, subprocess.CalledProcessError) as e:
            self.warnings.append(f'cannot demangle pluginlib symbols: {e}')
            return []
        new_bases = set()
        for text in names.values():
            arguments = symbols.template_arguments(text, 'pluginlib::ClassLoader')
            if arguments:
                new_bases.add(arguments[0])
        new_bases -= self._base_classes
        if not new_bases:
            return []
        self._base_classes |= new_bases
        archives = []
        try:
            plugins = ament_index.plugins(self.prefixes())
        except ament_index.AmentIndexError as e:
            self.warnings.append(str(e))
            return []
        for plugin in plugins:
            if plugin.base not in new_bases:
                continue
            found = self._closure(plugin.package, plugin.library,
                                  f"plugin '{plugin.name}' ({plugin.type})")
            if found is not None:
                self.plugins.append(plugin.to_json())
                archives += found
        return archives

    def _component_archives(self):
        archives = []
        for component in ament_index.components(self.prefixes()):
            if component.to_json() in self.components:
                continue  # registered twice (register_nodes and register_node)
            found = self._closure(component.package, component.library,
                                  f"component '{component.class_name}'")
            if found is not None:
                self.components.append(component.to_json())
                archives += found
        return archives

    def _closure(self, package, library, what):
        stem = ament_index.library_stem(library)
        for prefix in self.prefixes():
            path = closure.closure_file(prefix, package, stem)
            if os.path.isfile(path):
                try:
                    archives, _ = closure.read_closure(path, self.bases)
                except closure.ClosureError as e:
                    self.warnings.append(f'{what} is not linked: {e}')
                    return None
                # a library already on the line (perhaps from its build
                # folder) is not added again from the install space
                known = {os.path.basename(a) for a in self.linked_archives()}
                added = []
                for path in archives:
                    if os.path.basename(path) not in known:
                        known.add(os.path.basename(path))
                        added.append(path)
                self.extra_archives += added
                return added
        self.warnings.append(
            f"{what} of package '{package}' is not linked: its library '{library}' has "
            f'no link closure (share/{package}/colcon_wasm/closures/{stem}.json); '
            f"rebuild '{package}' with colcon build --wasm")
        return None

    def linked_archives(self):
        """Get every archive of the final link line, in order."""
        return self.link.archives + self.extra_archives

    def support_objects(self):
        """
        Compile what every executable gets.

        That is the linked-libraries table, and for C++ links the
        uncaught-exception helper.
        """
        libraries = []
        for path in self.linked_archives():
            name = os.path.basename(path)
            if name not in libraries:
                libraries.append(name)
        with_classes = [n for n in libraries if self.registrations.get(n)]
        objects = [self._compiled(table_source(libraries, with_classes), '.c')]
        if os.path.basename(self.link.command[0]).startswith('em++'):
            objects.append(self._compiled(EXCEPTION_TEXT_SOURCE, '.cpp'))
        return objects

    def _compiled(self, source, suffix):
        """Compile a generated source once (cached by content and flags)."""
        flags = ['-pthread'] if self.link.pthread else []
        language = ['-x', 'c'] if suffix == '.c' else []  # em++ takes .c for C++
        key = hashlib.sha256(json.dumps(
            [source, suffix, flags, language, self.link.command[0],
             link_report.launcher_digest()]).encode()).hexdigest()[:24]
        folder = os.path.join(self.cache, 'generated')
        obj = os.path.join(folder, key + '.o')
        if not os.path.isfile(obj):
            os.makedirs(folder, exist_ok=True)
            src = os.path.join(folder, key + suffix)
            with open(src, 'w') as handle:
                handle.write(source)
            staging = f'{obj}.{os.getpid()}.o'
            subprocess.run([self.link.command[0], *language, '-c', src, '-o', staging, '-O2']
                           + flags, check=True)
            os.replace(staging, obj)
        return obj

    def report(self):
        """Describe what was linked (read by the post-processing)."""
        base_classes = sorted(self._base_classes)
        return {
            'schema': link_report.REPORT_SCHEMA,
            'inputs': {
                'launcher': link_report.launcher_digest(),
                'archives': link_report.file_stamps(self.extra_archives),
                'plugin_base_classes': base_classes,
                'hosts_components': self.hosts_components,
                'index': link_report.index_fingerprint(
                    self.prefixes(), base_classes, self.hosts_components),
            },
            'libraries': [os.path.basename(a) for a in self.linked_archives()],
            'registrations': [
                {'library': library, 'class': derived, 'base': base}
                for library, classes in sorted(self.registrations.items())
                for derived, base in classes],
            'plugin_base_classes': base_classes,
            'plugins': self.plugins,
            'components': self.components,
            'warnings': self.warnings,
        }


def _c_string(text):
    return '"' + text.replace('\\', '\\\\').replace('"', '\\"') + '"'


def table_source(libraries, with_classes):
    """Get the C source of the linked-libraries table."""
    def array(name, items):
        body = ''.join(f'  {_c_string(i)},\n' for i in items)
        return f'static const char * const {name}[] = {{\n{body}  0}};\n'
    return (
        '/* Generated by the colcon-wasm link launcher: the libraries linked into\n'
        ' * this executable, which rcutils_load_shared_library() "loads". */\n'
        + array('colcon_wasm_libraries', libraries)
        + array('colcon_wasm_class_libraries', with_classes)
        + 'const char * const * colcon_wasm_linked_libraries(void)\n'
        '{\n  return colcon_wasm_libraries;\n}\n'
        'const char * const * colcon_wasm_linked_class_libraries(void)\n'
        '{\n  return colcon_wasm_class_libraries;\n}\n')


"""
The text of an uncaught C++ exception, for the crash report (C++ links only).

Emscripten throws the thrown object's address: one that nothing catches
reaches the runtime as a bare number. wasm_js' host calls this with that
address and the exception's type_info (from Emscripten's ExceptionInfo) to
report what a native std::terminate prints: the type and what().
"""
EXCEPTION_TEXT_SOURCE = r"""// Generated by colcon-wasm (colcon_wasm/link/launcher.py).
#include <emscripten/emscripten.h>
#include <cxxabi.h>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <typeinfo>

extern "C" int __cxa_can_catch(
  const std::type_info * catch_type, const std::type_info * thrown_type, void ** thrown);

extern "C" EMSCRIPTEN_KEEPALIVE char * colcon_wasm_exception_text(
  void * thrown, const std::type_info * type)
{
  std::string text = "(unknown type)";
  if (type != nullptr) {
    int status = 0;
    char * name = abi::__cxa_demangle(type->name(), nullptr, nullptr, &status);
    text = (status == 0 && name != nullptr) ? name : type->name();
    std::free(name);
    void * adjusted = thrown;
    if (thrown != nullptr && __cxa_can_catch(&typeid(std::exception), type, &adjusted)) {
      text += "\n";
      text += static_cast<const std::exception *>(adjusted)->what();
    }
  }
  return strdup(text.c_str());
}
"""


def capture(options, link):
    """Record the link line as a closure and write an empty output."""
    bases = options['bases']
    entries = []
    for path in link.archives:
        entry = closure.relative_entry(
            path, bases=bases, build_dir=options['--build-dir'],
            install_prefix=options['--install-prefix'])
        if entry not in entries:
            entries.append(entry)
    flags = [a for a in link.arguments if a.startswith('-l')]
    library = entries[0].get('base_path') or entries[0].get('absolute') if entries else ''
    closure.write_closure(options['--capture'], library=library,
                          package=options['--package'], entries=entries, flags=flags)
    with open(link.output, 'w') as handle:
        handle.write('// colcon-wasm: link closure capture, not an executable\n')
    return 0


def main(argv=None):
    """Run one link command (replaces this process for the real link)."""
    options, command = parse_command_line(sys.argv[1:] if argv is None else argv)
    link = LinkCommand(command)
    if options['--capture'] and link.is_executable:
        return capture(options, link)
    tests = bool(options['--test-pre-js']) and link.is_executable and \
        test_link.is_test_link(link)
    if tests:
        # a gtest/gmock executable of a --wasm-tests build: a Node.js test program
        command = command + test_link.test_link_flags(link, options['--test-pre-js'])
    if not link.is_executable or not link.archives:
        # archives, objects, try_compile checks: nothing is loaded there
        if tests:
            return test_link.run_test_link(command, link.output)
        os.execvp(command[0], command)
    plan = LinkPlan(options, link).build()
    for warning in plan.warnings:
        say(f'{link.output}: {warning}')
    added = plan.extra_objects + plan.support_objects()
    first_object = next((i for i, a in enumerate(command)
                         if a in link.objects or a.startswith('@')), len(command))
    final = command[:first_object] + added + command[first_object:] + plan.extra_archives
    with open(link.output + link_report.REPORT_SUFFIX, 'w') as handle:
        json.dump(plan.report(), handle, indent=1)
        handle.write('\n')
    sys.stdout.flush()
    sys.stderr.flush()
    if tests:
        return test_link.run_test_link(final, link.output)
    os.execvp(final[0], final)


if __name__ == '__main__':
    sys.exit(main())
