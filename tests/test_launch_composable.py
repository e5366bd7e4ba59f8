# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Composable nodes in launch files: node_container, composable_node, load_composable_node.

The parse tests check the LoadNode requests that launch files become (as
launch_ros builds them) and the file:line errors, without running anything.
The run tests launch real XML and YAML files against a real container: the
`static_container` of tests/rmw/rmw_wasm_cpp_node_tests, which hosts the
components Talker (publishes "component says N" on chatter) and Listener
(logs "component heard: ..."), from the Humble build of tests/rclcpp_build.py.
"""

import json
from pathlib import Path
import re
import subprocess
import sys
import textwrap
import time

from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import load_launch_file
from colcon_wasm.launch.command import execute
from colcon_wasm.launch.install_space import InstallSpace
from colcon_wasm.launch.runner import host_plan
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from rclcpp_build import rclcpp_build  # noqa: E402, I100

TESTS = 'rmw_wasm_cpp_node_tests'
TALKER = TESTS + '::Talker'
LISTENER = TESTS + '::Listener'
LOADER = '[launch_ros.actions.load_composable_nodes]'


def _write(path, text):
    path.write_text(textwrap.dedent(text).lstrip(), encoding='utf-8')
    return path


def _value(parameter):
    """Return ``(type, value)`` of an rcl_interfaces/msg/Parameter of a request."""
    value = dict(parameter['value'])
    kind = value.pop('type')
    (field, item), = value.items()
    return kind, item


# ------------------------------------------------------------------ parsing

CONTAINER_XML = """
    <launch>
      <arg name="ns" default="robot"/>
      <arg name="with_listener" default="true"/>
      <node_container pkg="rmw_wasm_cpp_node_tests" exec="static_container"
                      name="my_container" namespace="" args="--flag">
        <remap from="rosout" to="rosout"/>
        <param name="use_sim_time" value="false"/>
        <composable_node pkg="rmw_wasm_cpp_node_tests" plugin="rmw_wasm_cpp_node_tests::Talker"
                         name="talker" namespace="$(var ns)">
          <remap from="chatter" to="/$(var ns)/news"/>
          <param name="use_sim_time" value="true"/>
          <param name="rate" value="5"/>
          <param name="gain" value="0.5"/>
          <param name="label" value="$(var ns)"/>
          <param name="ids" value="[1, 2, 3]"/>
          <param name="names" value="a,b" value-sep=","/>
          <param name="filter">
            <param name="size" value="3"/>
          </param>
          <param from="params.yaml"/>
          <extra_arg name="use_intra_process_comms" value="true"/>
        </composable_node>
        <composable_node pkg="rmw_wasm_cpp_node_tests" plugin="rmw_wasm_cpp_node_tests::Listener"
                         name="skipped" unless="true"/>
      </node_container>
      <group>
        <push-ros-namespace namespace="pushed"/>
        <load_composable_node target="/my_container" if="$(var with_listener)">
          <composable_node pkg="rmw_wasm_cpp_node_tests"
                           plugin="rmw_wasm_cpp_node_tests::Listener" name="listener">
            <remap from="chatter" to="/$(var ns)/news"/>
          </composable_node>
        </load_composable_node>
      </group>
    </launch>
"""

CONTAINER_YAML = """
    launch:
    - arg: {name: ns, default: robot}
    - arg: {name: with_listener, default: 'true'}
    - node_container:
        pkg: rmw_wasm_cpp_node_tests
        exec: static_container
        name: my_container
        namespace: ''
        args: --flag
        remap:
        - {from: rosout, to: rosout}
        param:
        - {name: use_sim_time, value: false}
        composable_node:
        - pkg: rmw_wasm_cpp_node_tests
          plugin: rmw_wasm_cpp_node_tests::Talker
          name: talker
          namespace: $(var ns)
          remap:
          - {from: chatter, to: /$(var ns)/news}
          param:
          - {name: use_sim_time, value: true}
          - {name: rate, value: 5}
          - {name: gain, value: 0.5}
          - {name: label, value: $(var ns)}
          - {name: ids, value: [1, 2, 3]}
          - {name: names, value: [a, b]}
          - name: filter
            param:
            - {name: size, value: 3}
          - {from: params.yaml}
          extra_arg:
          - {name: use_intra_process_comms, value: 'true'}
        - pkg: rmw_wasm_cpp_node_tests
          plugin: rmw_wasm_cpp_node_tests::Listener
          name: skipped
          unless: 'true'
    - group:
        children:
        - push-ros-namespace: {namespace: pushed}
        - load_composable_node:
            target: /my_container
            if: $(var with_listener)
            composable_node:
            - pkg: rmw_wasm_cpp_node_tests
              plugin: rmw_wasm_cpp_node_tests::Listener
              name: listener
              remap:
              - {from: chatter, to: /$(var ns)/news}
"""

PARAMS_YAML = """
    /**:
      ros__parameters:
        shared: 1
        gain: 0.25
    robot:
      talker:
        ros__parameters:
          gain: 2.0
          mixed: [1, 2.5]
    other:
      ros__parameters:
        not_for_the_talker: true
"""


@pytest.mark.parametrize('name,text', [
    ('c.launch.xml', CONTAINER_XML), ('c.launch.yaml', CONTAINER_YAML)])
def test_container_and_load_requests(tmp_path, name, text):
    _write(tmp_path / 'params.yaml', PARAMS_YAML)
    plan = load_launch_file(_write(tmp_path / name, text))
    container, = plan.processes
    assert container.argv() == [
        '--flag', '--ros-args', '-r', '__node:=my_container', '-r', '__ns:=/',
        '-p', 'use_sim_time:=false', '-r', 'rosout:=rosout']
    own, loaded = plan.loads
    assert (own.target, own.service, own.containers) == (
        '/my_container', '/my_container/_container/load_node', [container])
    talker, = own.to_json()['requests']  # 'skipped' is unless="true"
    assert own.to_json()['containers'] == ['static_container-1']
    assert {k: talker[k] for k in ('package_name', 'plugin_name', 'node_name', 'node_namespace',
                                   'log_level', 'remap_rules')} == {
        'package_name': TESTS, 'plugin_name': TALKER, 'node_name': 'talker',
        'node_namespace': '/robot', 'log_level': 0, 'remap_rules': ['chatter:=/robot/news']}
    parameters = [(p['name'], _value(p)) for p in talker['parameters']]
    assert parameters == [
        ('use_sim_time', (1, True)), ('rate', (2, '5')), ('gain', (3, 0.5)),
        ('label', (4, 'robot')), ('ids', (7, ['1', '2', '3'])), ('names', (9, ['a', 'b'])),
        ('filter.size', (2, '3')),
        # params.yaml: '/**' then the talker's own section (it wins), not 'other'
        ('shared', (2, '1')), ('gain', (3, 2.0)), ('mixed', (8, [1.0, 2.5]))]
    assert [(p['name'], _value(p)) for p in talker['extra_arguments']] == [
        ('use_intra_process_comms', (1, True))]
    # load_composable_node: the pushed namespace applies, the container is found by name
    assert loaded.containers == [container]
    listener, = loaded.to_json()['requests']
    assert (listener['node_name'], listener['node_namespace'], listener['remap_rules'],
            listener['parameters'], listener['extra_arguments']) == (
        'listener', '/pushed', ['chatter:=/robot/news'], [], [])
    assert loaded.to_json()['where'] == \
        f'<load_composable_node> at {tmp_path / name}:{loaded.where[1]}'


def test_conditions_and_a_container_of_another_launch(tmp_path):
    path = _write(tmp_path / 'c.launch.xml', CONTAINER_XML)
    _write(tmp_path / 'params.yaml', PARAMS_YAML)
    plan = load_launch_file(path, {'with_listener': 'false'})
    assert [load.target for load in plan.loads] == ['/my_container']
    path = _write(tmp_path / 'l.launch.xml', """
        <launch>
          <load_composable_node target="elsewhere/box">
            <composable_node pkg="p" plugin="p::A" name="a" if="false"/>
            <composable_node pkg="p" plugin="p::B" name="b"/>
          </load_composable_node>
          <load_composable_node target="/cell/box">
            <composable_node pkg="p" plugin="p::C" name="c"/>
          </load_composable_node>
          <node pkg="rclcpp_components" exec="component_container" name="box" namespace="cell"/>
        </launch>
    """)
    plan = load_launch_file(path)
    other, here = plan.loads
    assert (other.target, other.service, other.containers) == (
        'elsewhere/box', '/elsewhere/box/_container/load_node', [])
    assert [n.name for n in other.nodes] == ['b']
    assert other.to_json()['requests'][0]['node_namespace'] == ''
    # a plain <node> of this launch with the target's name is the container too
    assert here.containers == plan.processes
    assert here.to_json()['containers'] == ['component_container-1']


def test_print_plan_shows_the_loads(tmp_path, capsys):
    _write(tmp_path / 'params.yaml', PARAMS_YAML)
    plan = load_launch_file(_write(tmp_path / 'c.launch.xml', CONTAINER_XML))
    install = tmp_path / 'install_wasm'
    _fake_install(install, types=True)
    assert execute(plan, install_base=install, print_plan=True, command='test') == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith('[static_container-1] ')
    assert lines[1].startswith(f'[load_node /my_container] {TESTS} {TALKER} --ros-args -r '
                               'chatter:=/robot/news -r __node:=talker -r __ns:=/robot '
                               '-p use_sim_time:=true -p rate:=5'), lines
    assert lines[1].endswith('-e use_intra_process_comms:=true')
    assert lines[2] == (f'[load_node /my_container] {TESTS} {LISTENER} --ros-args -r '
                        'chatter:=/robot/news '
                        '-r __node:=listener -r __ns:=/pushed')


def _fake_install(base, *, types):
    """Write an install space with the container executable, with or without LoadNode types."""
    prefix = base / TESTS
    (prefix / 'lib' / TESTS).mkdir(parents=True)
    (prefix / 'lib' / TESTS / 'static_container.js').write_text('// glue')
    (prefix / 'share' / TESTS / 'colcon_wasm').mkdir(parents=True)
    (prefix / 'share' / TESTS / 'colcon_wasm' / 'manifest.json').write_text(json.dumps({
        'schema': 1, 'package': TESTS, 'executables': [
            {'name': 'static_container', 'js': f'lib/{TESTS}/static_container.js'}]}))
    for package in ('composition_interfaces', 'rcl_interfaces'):
        share = base / package / 'share' / package / 'colcon_wasm'
        share.mkdir(parents=True)
        if types:
            (share / 'types.json').write_text('{}')


def test_loads_need_the_composition_interfaces_types(tmp_path):
    _write(tmp_path / 'params.yaml', PARAMS_YAML)
    path = _write(tmp_path / 'c.launch.xml', CONTAINER_XML)
    plan = load_launch_file(path)
    _fake_install(tmp_path / 'install_wasm', types=False)
    with pytest.raises(LaunchError) as error:
        host_plan(plan, InstallSpace(tmp_path / 'install_wasm'))
    assert str(error.value).startswith(f'{path}:4: loading composable nodes calls '
                                       'composition_interfaces/srv/LoadNode')
    assert "colcon build --wasm --packages-up-to composition_interfaces'" in str(error.value)


NODE = '<composable_node pkg="p" plugin="p::A" name="a"'


@pytest.mark.parametrize('body,line,message', [
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n'
     '  <composable_node pkg="p" plugin="p::A" name="a" namspace="x"/>\n</node_container>', 3,
     "unexpected attribute 'namspace' in <composable_node>: it is misspelled or not supported"),
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n'
     '  <composable_node pkg="p" name="a"/>\n</node_container>', 3,
     "<composable_node> needs the attribute 'plugin'"),
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n'
     '  <composable_node pkg="p" plugin="p::A"/>\n</node_container>', 3,
     "<composable_node> needs the attribute 'name'"),
    ('<node_container pkg="p" exec="c" name="c">\n  ' + NODE + '/>\n</node_container>', 2,
     "<node_container> needs the attribute 'namespace'"),
    ('<node_container pkg="p" exec="c" namespace="">\n  ' + NODE + '/>\n</node_container>', 2,
     "<node_container> needs the attribute 'name'"),
    ('<node_container pkg="p" exec="c" name="c" namespace="/" respawn="true"/>', 2,
     "the <node_container> attribute 'respawn' is not supported"),
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n  ' + NODE + '>\n'
     '    <env name="A" value="1"/>\n  </composable_node>\n</node_container>', 4,
     'unexpected tag <env> inside <composable_node>'),
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n  ' + NODE + '>\n'
     '    <extra_arg name="use_intra_process_comms"/>\n  </composable_node>\n'
     '</node_container>', 4, "<extra_arg> needs the attribute 'value'"),
    ('<node_container pkg="p" exec="c" name="c" namespace="/">\n  ' + NODE + '>\n'
     '    <param name="v" value="[1, 2.5]"/>\n  </composable_node>\n</node_container>', 4,
     "parameter 'v': [1, 2.5] mixes types"),
    ('<load_composable_node target="/c"/>', 2,
     '<load_composable_node> needs at least one <composable_node>'),
    ('<load_composable_node target="/c" container="x">\n  ' + NODE + '/>\n'
     '</load_composable_node>', 2, "unexpected attribute 'container' in <load_composable_node>"),
    ('<load_composable_node target="/c/9box">\n  ' + NODE + '/>\n</load_composable_node>', 2,
     "target '/c/9box': the container name '9box' is not valid"),
    ('<load_composable_node target="/c">\n  <composable_node pkg="p" plugin="p::A" '
     'name="a-b"/>\n</load_composable_node>', 3, "composable node name 'a-b' is not valid"),
    ('<composable_node pkg="p" plugin="p::A" name="a"/>', 2,
     '<composable_node> is not supported by colcon-wasm launch'),
])
def test_xml_errors_name_file_and_line(tmp_path, body, line, message):
    path = _write(tmp_path / 'bad.launch.xml', '<launch>\n' + body + '\n</launch>\n')
    with pytest.raises(LaunchError) as error:
        load_launch_file(path)
    assert str(error.value).startswith(f'{path}:{line}: {message}'), str(error.value)


@pytest.mark.parametrize('entry,line,message', [
    ("- node_container: {pkg: p, exec: c, name: c, namespace: '', composable_node: "
     '[{pkg: p, plugin: p::A, name: a, extra_arg: [{name: use_intra_process_comms, '
     'value: true}]}]}', 2,
     "<extra_arg name='use_intra_process_comms'>: write the value as a string (value: 'true')"),
    ("- node_container: {pkg: p, exec: c, name: c, namespace: '', composable_node: "
     '[{pkg: p, plugin: p::A, name: a, remaps: [{from: a, to: b}]}]}', 2,
     "unexpected tag 'remaps' in <composable_node>"),
    ('- load_composable_node: {target: /c, composable_node: [{pkg: p, plugin: p::A, '
     "name: a, extra_arg: [{name: x, value: '{a: 1}'}]}]}", 2,
     "extra argument 'x': '{a: 1}' is not a bool"),
])
def test_yaml_errors_name_file_and_line(tmp_path, entry, line, message):
    path = _write(tmp_path / 'bad.launch.yaml', 'launch:\n' + entry + '\n')
    with pytest.raises(LaunchError) as error:
        load_launch_file(path)
    assert str(error.value).startswith(f'{path}:{line}: {message}'), str(error.value)


# -------------------------------------------------------------- running them

@pytest.fixture(scope='module')
def install():
    """Get the (cached) Humble build with rmw_wasm_cpp_node_tests' static_container."""
    return rclcpp_build().install


def launch(install, *args, timeout=120):
    """Run colcon-wasm launch; return (exit status, stdout, stderr, seconds)."""
    started = time.monotonic()
    result = subprocess.run(
        [str(demo_build.venv_tool('colcon-wasm')), 'launch', '--install-base', str(install),
         *map(str, args)], capture_output=True, text=True, timeout=timeout)
    return result.returncode, result.stdout, result.stderr, time.monotonic() - started


RUN_XML = """
    <launch>
      <arg name="ns" default="robot"/>
      <node_container pkg="rmw_wasm_cpp_node_tests" exec="static_container"
                      name="my_container" namespace="">
        <composable_node pkg="rmw_wasm_cpp_node_tests" plugin="rmw_wasm_cpp_node_tests::Talker"
                         name="talker" namespace="$(var ns)">
          <remap from="chatter" to="news"/>
          <param name="use_sim_time" value="true"/>
          <extra_arg name="use_intra_process_comms" value="true"/>
        </composable_node>
      </node_container>
      <load_composable_node target="/my_container">
        <composable_node pkg="rmw_wasm_cpp_node_tests"
                         plugin="rmw_wasm_cpp_node_tests::Listener"
                         name="listener" namespace="$(var ns)">
          <remap from="chatter" to="news"/>
        </composable_node>
      </load_composable_node>
      <node pkg="rmw_wasm_cpp_node_tests" exec="probe" name="read_talker"
            args="param_reader /$(var ns)/talker use_sim_time"/>
    </launch>
"""

RUN_YAML = """
    launch:
    - node_container:
        pkg: rmw_wasm_cpp_node_tests
        exec: static_container
        name: box
        namespace: /cell
        param:
        - {name: use_sim_time, value: true}
        composable_node:
        - pkg: rmw_wasm_cpp_node_tests
          plugin: rmw_wasm_cpp_node_tests::Talker
          name: speaker
          remap:
          - {from: chatter, to: /cell/words}
          param:
          - {from: params.yaml}
    - load_composable_node:
        target: /cell/box
        composable_node:
        - pkg: rmw_wasm_cpp_node_tests
          plugin: rmw_wasm_cpp_node_tests::Listener
          name: hearer
          namespace: /cell
          remap:
          - {from: chatter, to: words}
    - node:
        pkg: rmw_wasm_cpp_node_tests
        exec: probe
        name: read_speaker
        args: param_reader /speaker use_sim_time
"""


def test_xml_container_loads_both_components_with_names_remaps_and_parameters(
        install, tmp_path):
    path = _write(tmp_path / 'composed.launch.xml', RUN_XML)
    code, out, err, _ = launch(install, '--duration', '5', '--echo', '/robot/news', path)
    assert code == 0, out + err
    loaded = re.findall(r'^\[INFO\] \[launch_ros\.actions\.load_composable_nodes\]: '
                        r"Loaded node '(\S+)' in container '(\S+)'$", out, re.MULTILINE)
    assert loaded == [('/robot/talker', '/my_container'), ('/robot/listener', '/my_container')]
    # the remapped topic carries the talker's messages; the listener (named, namespaced) hears
    assert re.search(r'^\[echo /robot/news\]\ndata: component says \d+\n---$', out,
                     re.MULTILINE), out
    assert re.search(r'^\[static_container-1\] \[INFO\] \[[\d.]+\] \[robot\.listener\]: '
                     r'component heard: component says \d+$', err, re.MULTILINE), err
    # the parameter reached the talker as a bool (a string would have failed its load)
    assert re.search(r'\[read_talker\]: PARAM use_sim_time=true$', err, re.MULTILINE), err


def test_yaml_container_with_a_parameter_file_and_load_composable_node(
        install, tmp_path):
    _write(tmp_path / 'params.yaml', """
        /**:
          ros__parameters:
            use_sim_time: false
        speaker:
          ros__parameters:
            use_sim_time: true
    """)
    path = _write(tmp_path / 'composed.launch.yaml', RUN_YAML)
    code, out, err, _ = launch(install, '--duration', '5', '--echo', '/cell/words', path)
    assert code == 0, out + err
    assert f"{LOADER}: Loaded node '/speaker' in container '/cell/box'" in out, out
    assert f"{LOADER}: Loaded node '/cell/hearer' in container '/cell/box'" in out, out
    assert re.search(r'^\[echo /cell/words\]\ndata: component says \d+$', out, re.MULTILINE)
    assert re.search(r'\[cell\.hearer\]: component heard: component says \d+$', err,
                     re.MULTILINE), err
    # the speaker's section of the file over '/**' (a ComponentManager has no parameter
    # services of its own, so its -p is checked by the parse tests only)
    assert re.search(r'\[read_speaker\]: PARAM use_sim_time=true$', err, re.MULTILINE), err


def test_failed_loads_are_reported_and_make_the_exit_status_non_zero(install, tmp_path):
    path = _write(tmp_path / 'failing.launch.xml', """
        <launch>
          <node_container pkg="rmw_wasm_cpp_node_tests" exec="static_container"
                          name="my_container" namespace="/">
            <composable_node pkg="rmw_wasm_cpp_node_tests"
                             plugin="rmw_wasm_cpp_node_tests::Nope" name="nope"/>
            <composable_node pkg="rmw_wasm_cpp_node_tests"
                             plugin="rmw_wasm_cpp_node_tests::Talker" name="talker">
              <extra_arg name="use_intra_process_comms" value="1"/>
            </composable_node>
            <composable_node pkg="rmw_wasm_cpp_node_tests"
                             plugin="rmw_wasm_cpp_node_tests::Listener" name="listener"/>
          </node_container>
        </launch>
    """)
    code, out, err, _ = launch(install, '--duration', '4', path)
    assert code == 1, out + err
    assert re.search(
        r"^\[ERROR\] \[launch_ros\.actions\.load_composable_nodes\]: Failed to load node 'nope' "
        r"of type 'rmw_wasm_cpp_node_tests::Nope' in container '/my_container': \S.*$",
        err, re.MULTILINE), err
    # the container refuses an extra argument of the wrong type: the type reached it
    assert (f"{LOADER}: Failed to load node 'talker' of type '{TALKER}' in container "
            "'/my_container': Extra component argument 'use_intra_process_comms' must be a "
            'boolean') in err, err
    # the other nodes still load, and the launch goes on until --duration
    assert f"{LOADER}: Loaded node '/listener' in container '/my_container'" in out, out
    assert '[INFO] [static_container-1]: process stopped' in out, out


def test_a_container_that_never_appears_times_out(install, tmp_path):
    path = _write(tmp_path / 'nowhere.launch.xml', """
        <launch>
          <load_composable_node target="/nowhere">
            <composable_node pkg="p" plugin="p::A" name="a"/>
            <composable_node pkg="p" plugin="p::B" name="b"/>
          </load_composable_node>
        </launch>
    """)
    code, out, err, seconds = launch(install, '--load-timeout', '2', path)
    assert code == 1, out + err
    assert (f"{LOADER}: Failed to load node 'a' of type 'p::A' in container '/nowhere': the "
            "service '/nowhere/_container/load_node' did not appear within 2 s "
            f"(<load_composable_node> at {path}:2): is '/nowhere' a running component "
            'container? --load-timeout S waits longer') in err, err
    assert "Failed to load node 'b' of type 'p::B' in container '/nowhere'" in err, err
    assert seconds < 30
