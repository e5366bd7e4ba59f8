# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The link launcher's parts (colcon_wasm/link/), on real Emscripten objects.

The whole launcher is exercised by every build test; these check its parts
where a build would hide a mistake: archive members (duplicate names),
llvm-nm records, closures that move with their install base, the ament
index, and when a link is stale.
"""

import json
import os
from pathlib import Path
import shutil
import subprocess
import time

from colcon_wasm.link import ament_index
from colcon_wasm.link import archive
from colcon_wasm.link import closure
from colcon_wasm.link import launcher
from colcon_wasm.link import report
from colcon_wasm.link import symbols
from colcon_wasm.toolchain import find_emscripten
import pytest


@pytest.fixture(scope='module')
def emscripten():
    """Get the Emscripten the builds use (skips when there is none)."""
    try:
        return find_emscripten()
    except Exception as e:  # noqa: B902
        pytest.skip(f'no Emscripten: {e}')


def _compile(emscripten, folder, name, code):
    source = folder / f'{name}.cpp'
    source.write_text(code)
    output = folder / f'{name}.cpp.o'
    subprocess.run([str(emscripten.bin_dir / 'em++'), '-c', str(source), '-o', str(output)],
                   check=True, env=dict(os.environ, **emscripten.environment()))
    return output


def test_archive_members_keep_duplicate_names_apart(emscripten, tmp_path):
    one = tmp_path / 'one'
    two = tmp_path / 'two'
    one.mkdir()
    two.mkdir()
    first = _compile(emscripten, one, 'same', 'int first() { return 1; }\n')
    second = _compile(emscripten, two, 'same', 'int second() { return 2; }\n')
    lib = tmp_path / 'libdup.a'
    subprocess.run([str(emscripten.bin_dir / 'emar'), 'qc', str(lib), str(first), str(second)],
                   check=True, env=dict(os.environ, **emscripten.environment()))
    members = archive.read_members(str(lib))
    assert [m[0] for m in members] == ['same.cpp.o', 'same.cpp.o']
    out = tmp_path / 'second.o'
    archive.extract_member(str(lib), 1, str(out))
    assert out.read_bytes() == second.read_bytes()
    records = symbols.SymbolReader(
        str(emscripten.llvm_tool('llvm-nm')), str(tmp_path / 'cache')).read(str(lib))
    assert len(records) == 2 and all(not r.registrations for r in records)


def test_registrations_and_main_are_recognized(emscripten, tmp_path):
    # the shape of a class_loader registration object: a definition of
    # class_loader::impl::registerPlugin<Derived, Base>
    obj = _compile(emscripten, tmp_path, 'reg', """
namespace class_loader { namespace impl {
template<typename D, typename B> void registerPlugin(const char *) {}
}}
namespace demo { struct Derived {}; }
struct Base {};
static int proxy = (class_loader::impl::registerPlugin<demo::Derived, Base>("x"), 0);
int main() { return proxy; }
""")
    record = symbols.SymbolReader(
        str(emscripten.llvm_tool('llvm-nm')), str(tmp_path / 'cache')).read(str(obj))[0]
    assert record.defines_main
    assert len(record.registrations) == 1
    names = symbols.demangle(str(emscripten.llvm_tool('llvm-cxxfilt')), record.registrations)
    assert symbols.template_arguments(
        names[record.registrations[0]], 'class_loader::impl::registerPlugin') == \
        ['demo::Derived', 'Base']


def test_template_arguments_and_library_stems():
    text = 'pluginlib::ClassLoader<ns::Base<int, std::map<a, b> > >::ClassLoader(x)'
    assert symbols.template_arguments(text, 'pluginlib::ClassLoader') == \
        ['ns::Base<int, std::map<a, b> >']
    assert symbols.template_arguments('f(int)', 'pluginlib::ClassLoader') is None
    for name in ('foo', 'libfoo', 'lib/libfoo.so', 'libfoo.a', 'foo.dll'):
        assert ament_index.library_stem(name) == 'foo', name


def test_nm_output_is_split_per_member():
    text = '\nfirst.o:\n00000001 T main\n         U x\n\nsecond.o:\n' \
        '00000002 W _ZN12class_loader4impl14registerPluginI1D1BEEvv\n' \
        '         U _ZN17rclcpp_components16ComponentManagerC1Ev\n'
    first, second = symbols.parse_nm_output(text, 'x.a')
    assert (first.name, first.defines_main, first.registrations) == ('first.o', True, [])
    assert second.registrations and second.uses_component_manager


def _install_base(root, package, files):
    base = root / 'install_wasm'
    for relative, text in files.items():
        path = base / package / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return base


def test_closures_move_with_their_install_base(tmp_path):
    base = _install_base(tmp_path / 'ws', 'greeters', {'lib/libgreeters.a': '!<arch>\n'})
    _install_base(tmp_path / 'ws', 'pluginlib', {'lib/libpluginlib.a': '!<arch>\n'})
    build_dir = tmp_path / 'ws' / 'build_wasm' / 'greeters'
    build_dir.mkdir(parents=True)
    entries = [
        closure.relative_entry(str(build_dir / 'libgreeters.a'), bases=[str(base)],
                               build_dir=str(build_dir),
                               install_prefix=str(base / 'greeters')),
        closure.relative_entry(str(base / 'pluginlib' / 'lib' / 'libpluginlib.a'),
                               bases=[str(base)], build_dir=str(build_dir),
                               install_prefix=str(base / 'greeters')),
        closure.relative_entry('/usr/lib/libsystem.a', bases=[str(base)],
                               build_dir=str(build_dir),
                               install_prefix=str(base / 'greeters')),
    ]
    assert entries == [{'base_path': 'greeters/lib/libgreeters.a'},
                       {'base_path': 'pluginlib/lib/libpluginlib.a'},
                       {'absolute': '/usr/lib/libsystem.a'}]
    path = tmp_path / 'closure.json'
    closure.write_closure(str(path), library='greeters/lib/libgreeters.a',
                          package='greeters', entries=entries[:2], flags=[])
    moved = tmp_path / 'elsewhere'
    shutil.move(str(base), str(moved))
    archives, _ = closure.read_closure(str(path), [str(moved)])
    assert archives == [str(moved / 'greeters/lib/libgreeters.a'),
                        str(moved / 'pluginlib/lib/libpluginlib.a')]
    (moved / 'pluginlib' / 'lib' / 'libpluginlib.a').unlink()
    with pytest.raises(closure.ClosureError) as error:
        closure.read_closure(str(path), [str(moved)])
    assert "needs 'pluginlib/lib/libpluginlib.a'" in str(error.value)
    assert "library 'greeters/lib/libgreeters.a' of package 'greeters'" in str(error.value)


def test_ament_index_plugins_and_components(tmp_path):
    index = 'share/ament_index/resource_index'
    base = _install_base(tmp_path, 'greeters', {
        f'{index}/base_pkg__pluginlib__plugin/greeters': 'share/greeters/plugins.xml\n',
        'share/greeters/plugins.xml': (
            '<class_libraries><library path="greeters">'
            '<class name="g/Hello" type="g::Hello" base_class_type="b::Greeter"/>'
            '</library><library path="lib/libother">'
            '<class type="g::Other" base_class_type="b::Other"/></library></class_libraries>'),
        f'{index}/rclcpp_components/greeters': 'g::Node;lib/libnodes.a\ng::Two;lib/libnodes.a\n',
    })
    prefixes = ament_index.package_prefixes([str(base)])
    assert prefixes == [str(base / 'greeters')]
    plugins = [p.to_json() for p in ament_index.plugins(prefixes)]
    assert plugins == [
        {'name': 'g/Hello', 'type': 'g::Hello', 'base': 'b::Greeter', 'library': 'greeters',
         'package': 'greeters'},
        {'name': 'g::Other', 'type': 'g::Other', 'base': 'b::Other', 'library': 'lib/libother',
         'package': 'greeters'}]
    assert [c.class_name for c in ament_index.components(prefixes)] == ['g::Node', 'g::Two']
    (base / 'greeters' / 'share/greeters/plugins.xml').write_text('<library')
    with pytest.raises(ament_index.AmentIndexError) as error:
        ament_index.plugins(prefixes)
    assert 'plugins.xml' in str(error.value) and "package 'greeters'" in str(error.value)


def test_link_command_reads_response_files(tmp_path):
    rsp = tmp_path / 'objects1.rsp'
    rsp.write_text('a.cpp.o "b c.cpp.o"\n')
    link = launcher.LinkCommand([
        '/usr/bin/em++', '-O2', f'@{rsp}', '-o', 'exe.js', 'liba.a',
        '-Wl,--whole-archive', 'libw.a', '-Wl,--no-whole-archive', '-pthread'])
    assert link.is_executable and link.pthread
    assert link.objects == ['a.cpp.o', 'b c.cpp.o']
    assert link.archives == ['liba.a', 'libw.a'] and link.whole_archives == {'libw.a'}
    assert not launcher.LinkCommand(['/usr/bin/emar', 'qc', 'lib.a', 'x.o']).is_executable


def test_table_source_is_valid_and_escaped():
    source = launcher.table_source(['liba.a', 'lib"q".a'], ['liba.a'])
    assert '"lib\\"q\\".a",' in source
    assert 'colcon_wasm_linked_libraries(void)' in source
    assert 'colcon_wasm_linked_class_libraries(void)' in source


def test_a_link_is_stale_when_an_added_archive_or_the_index_changes(tmp_path):
    base = _install_base(tmp_path, 'nodes', {
        'lib/libnodes.a': 'v1',
        'share/ament_index/resource_index/rclcpp_components/nodes': 'n::A;lib/libnodes.a\n'})
    prefixes = ament_index.package_prefixes([str(base)])
    archive_path = str(base / 'nodes' / 'lib' / 'libnodes.a')
    data = {'schema': report.REPORT_SCHEMA, 'inputs': {
        'launcher': report.launcher_digest(),
        'archives': report.file_stamps([archive_path]), 'plugin_base_classes': [],
        'hosts_components': True, 'index': report.index_fingerprint(prefixes, [], True)}}
    build = tmp_path / 'build'
    build.mkdir()
    (build / 'container.js').write_text('')
    (build / ('container.js' + report.REPORT_SUFFIX)).write_text(json.dumps(data))
    assert report.stale_links(str(build), [str(base)]) == []
    index = base / 'nodes' / 'share/ament_index/resource_index/rclcpp_components/nodes'
    index.write_text('n::A;lib/libnodes.a\nn::B;lib/libnodes.a\n')
    assert report.stale_links(str(build), [str(base)]) == [
        (str(build / 'container.js'), 'the plugins or components of the ament index changed')]
    index.write_text('n::A;lib/libnodes.a\n')
    time.sleep(0.01)
    Path(archive_path).write_text('v2, longer')
    stale = report.stale_links(str(build), [str(base)])
    assert stale and 'libnodes.a' in stale[0][1]
