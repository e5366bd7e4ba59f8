# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""colcon-wasm launch/run: arguments to plans, plans against an install space."""

import io
import json
from pathlib import Path

from colcon_wasm.launch import LaunchError
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.command import make_plan
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.install_space import InstallSpaceError
from colcon_wasm.launch.runner import host_plan
import pytest


@pytest.fixture
def install(tmp_path):
    """Write an isolated install space: demo_nodes (talker, listener), a launch file."""
    base = tmp_path / 'install_wasm'
    prefix = base / 'demo_nodes'
    lib = prefix / 'lib' / 'demo_nodes'
    lib.mkdir(parents=True)
    executables = []
    for name in ('talker', 'listener'):
        (lib / (name + '.js')).write_text('// glue')
        executables.append({'name': name, 'js': f'lib/demo_nodes/{name}.js',
                            'files': [], 'uses_bus': True, 'pthread': True})
    share = prefix / 'share' / 'demo_nodes'
    (share / 'colcon_wasm').mkdir(parents=True)
    (share / 'colcon_wasm' / 'manifest.json').write_text(json.dumps(
        {'schema': 1, 'package': 'demo_nodes', 'executables': executables}))
    (share / 'launch').mkdir()
    (share / 'launch' / 'pair.launch.xml').write_text(
        '<launch>\n  <arg name="topic" default="chatter"/>\n'
        '  <node pkg="demo_nodes" exec="talker"><remap from="chatter" to="$(var topic)"/></node>\n'
        '  <node pkg="demo_nodes" exec="listener"><remap from="chatter" to="$(var topic)"/>'
        '</node>\n</launch>\n')
    types = base / 'demo_interfaces' / 'share' / 'demo_interfaces' / 'colcon_wasm'
    types.mkdir(parents=True)
    (types / 'types.json').write_text('{}')
    return base


def test_items_launch_file_and_package_launch_file(install):
    plan = make_plan(['demo_nodes/talker', 'demo_nodes/listener'], str(install))
    assert [p.label for p in plan.processes] == ['talker-1', 'listener-2']
    share_file = install / 'demo_nodes' / 'share' / 'demo_nodes' / 'launch' / 'pair.launch.xml'
    plan = make_plan([str(share_file), 'topic:=news'], str(install))
    assert plan.processes[0].argv() == ['--ros-args', '-r', 'chatter:=news']
    plan = make_plan(['demo_nodes', 'pair.launch.xml', 'topic:=x'], str(install))
    assert plan.processes[1].argv() == ['--ros-args', '-r', 'chatter:=x']


@pytest.mark.parametrize('values,message', [
    ([], 'name a launch file or PKG/EXE items'),
    (['talker'], "'talker' is neither a launch file nor a PKG/EXE item"),
    (['missing.launch.xml'], "launch file 'missing.launch.xml' does not exist"),
    (['demo_nodes/talker', 'x:=1'], r'launch arguments \(x:=1\) need a launch file'),
    (['demo_nodes', 'nope.launch.xml'],
     "package 'demo_nodes' has no launch file 'nope.launch.xml'"),
    (['other', 'x.launch.xml'], "package 'other' is not in the install space"),
])
def test_bad_arguments_are_clear(install, values, message):
    with pytest.raises((LaunchError, InstallSpaceError), match=message):
        make_plan(values, str(install))


def test_host_plan_has_absolute_paths_and_types(install):
    plan = make_plan(['demo_nodes/talker'], str(install))
    description = host_plan(plan, InstallSpace(install), duration=2.5, echo=['/chatter'])
    process = description['processes'][0]
    assert process['js'] == str(install / 'demo_nodes' / 'lib' / 'demo_nodes' / 'talker.js')
    assert process['label'] == 'talker-1' and process['args'] == []
    assert description['duration'] == 2.5 and description['echo'] == ['/chatter']
    assert description['types'] == [str(
        install / 'demo_interfaces' / 'share' / 'demo_interfaces' / 'colcon_wasm' / 'types.json')]


def test_print_plan(install):
    out = io.StringIO()
    plan = make_plan(['demo_nodes', 'pair.launch.xml'], str(install))
    assert execute(plan, install_base=str(install), print_plan=True, command='t', out=out) == 0
    lib = install / 'demo_nodes' / 'lib' / 'demo_nodes'
    assert out.getvalue().splitlines() == [
        f"[talker-1] {lib / 'talker.js'} --ros-args -r chatter:=chatter",
        f"[listener-2] {lib / 'listener.js'} --ros-args -r chatter:=chatter"]


def test_unknown_executable_names_the_launch_file_line(install, tmp_path):
    launch = tmp_path / 'bad.launch.yaml'
    launch.write_text('launch:\n- node: {pkg: demo_nodes, exec: talker}\n'
                      '- node: {pkg: demo_nodes, exec: talkr}\n')
    plan = make_plan([str(launch)], str(install))
    err = io.StringIO()
    assert execute(plan, install_base=str(install), print_plan=True, command='colcon-wasm launch',
                   out=io.StringIO(), err=err) == 1
    assert err.getvalue() == (
        f"colcon-wasm launch: {launch}:3: package 'demo_nodes' has no executable 'talkr' "
        '(it has: talker, listener)\n')


def test_missing_install_space(tmp_path):
    err = io.StringIO()
    plan = make_plan(['demo_nodes/talker'], str(tmp_path / 'nowhere'))
    assert execute(plan, install_base=str(tmp_path / 'nowhere'), command='colcon-wasm run',
                   err=err) == 1
    assert f"no install space at '{tmp_path / 'nowhere'}'" in err.getvalue()
    assert "run 'colcon build --wasm'" in err.getvalue()


def test_broken_manifest_is_reported(install):
    manifest = install / 'demo_nodes' / 'share' / 'demo_nodes' / 'colcon_wasm' / 'manifest.json'
    manifest.write_text('{"schema": 99}')
    with pytest.raises(InstallSpaceError, match='has schema 99, this colcon-wasm reads schema 1'):
        InstallSpace(install).executable('demo_nodes', 'talker')
    manifest.write_text('{not json')
    with pytest.raises(InstallSpaceError, match="cannot read the manifest '.*manifest.json'"):
        InstallSpace(install).executable('demo_nodes', 'talker')
    assert Path(manifest).exists()
