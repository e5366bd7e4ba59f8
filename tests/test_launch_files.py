# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Launch files (XML and YAML) into launch plans: argv, labels, errors."""

import textwrap

from colcon_wasm.launch import LaunchError
from colcon_wasm.launch import load_launch_file
from colcon_wasm.launch import plan_items
from colcon_wasm.launch import split_launch_arguments
from colcon_wasm.launch.install_space import InstallSpace
import pytest
import yaml


def _write(path, text):
    path.write_text(textwrap.dedent(text).lstrip(), encoding='utf-8')
    return path


def _params(process):
    """Return ``{name: value}`` of the -p arguments, read back as rcl reads them."""
    argv = process.ros_argv()
    result = {}
    for flag, value in zip(argv, argv[1:]):
        if flag == '-p':
            name, _, text = value.partition(':=')
            result[name] = yaml.safe_load(text)
    return result


TALKER_LISTENER_XML = """
    <launch>
      <arg name="topic" default="chatter" description="the topic"/>
      <arg name="ns" default="demo"/>
      <node pkg="demo_nodes" exec="talker" name="talker" namespace="$(var ns)"
            args="--count 3" output="screen">
        <remap from="chatter" to="$(var topic)"/>
        <param name="rate" value="5"/>
        <param name="greeting" value="hello world"/>
      </node>
      <node pkg="demo_nodes" exec="listener" namespace="/abs">
        <remap from="chatter" to="$(var topic)"/>
      </node>
    </launch>
"""

TALKER_LISTENER_YAML = """
    launch:
    - arg: {name: topic, default: chatter, description: the topic}
    - arg:
        name: ns
        default: demo
    - node:
        pkg: demo_nodes
        exec: talker
        name: talker
        namespace: $(var ns)
        args: --count 3
        output: screen
        remap:
        - {from: chatter, to: $(var topic)}
        param:
        - {name: rate, value: 5}
        - {name: greeting, value: hello world}
    - node:
        pkg: demo_nodes
        exec: listener
        namespace: /abs
        remap:
        - {from: chatter, to: $(var topic)}
"""


@pytest.mark.parametrize('name,text', [
    ('talk.launch.xml', TALKER_LISTENER_XML), ('talk.launch.yaml', TALKER_LISTENER_YAML)])
def test_talker_listener(tmp_path, name, text):
    plan = load_launch_file(_write(tmp_path / name, text), {'topic': 'news'})
    talker, listener = plan.processes
    assert (talker.package, talker.executable) == ('demo_nodes', 'talker')
    assert talker.label == 'talker-1'
    assert listener.label == 'listener-2'
    assert talker.argv() == [
        '--count', '3', '--ros-args', '-r', '__node:=talker', '-r', '__ns:=/demo',
        '-p', 'rate:=5', '-p', 'greeting:=hello world', '-r', 'chatter:=news']
    assert listener.argv() == ['--ros-args', '-r', '__ns:=/abs', '-r', 'chatter:=news']


def test_arguments_default_required_and_choices(tmp_path):
    path = _write(tmp_path / 'a.launch.xml', """
        <launch>
          <arg name="mode" default="fast">
            <choice value="fast"/>
            <choice value="slow"/>
          </arg>
          <arg name="robot"/>
          <node pkg="p" exec="e" name="$(var robot)_$(var mode)"/>
        </launch>
    """)
    assert load_launch_file(path, {'robot': 'r2'}).processes[0].name == 'r2_fast'
    with pytest.raises(LaunchError, match=r"a\.launch\.xml:6: launch argument 'robot' is "
                       r'required: pass robot:=VALUE'):
        load_launch_file(path, {})
    with pytest.raises(LaunchError, match=r":2: launch argument 'mode' is 'medium', but must "
                       r'be one of: fast, slow'):
        load_launch_file(path, {'robot': 'r', 'mode': 'medium'})


def test_groups_namespaces_let_and_conditions(tmp_path):
    path = _write(tmp_path / 'g.launch.xml', """
        <launch>
          <arg name="with_b" default="false"/>
          <let name="base" value="robot"/>
          <group>
            <push-ros-namespace namespace="$(var base)"/>
            <let name="base" value="changed_in_group"/>
            <node pkg="p" exec="a" namespace="arm"/>
            <node pkg="p" exec="b" if="$(var with_b)"/>
            <node pkg="p" exec="c" unless="$(var with_b)"/>
          </group>
          <node pkg="p" exec="d" name="$(var base)"/>
          <group scoped="false">
            <push_ros_namespace namespace="/top"/>
          </group>
          <node pkg="p" exec="e" exec_name="custom"/>
          <node pkg="p" exec="f" if="$(not $(var with_b))"/>
        </launch>
    """)
    processes = load_launch_file(path).processes
    assert [p.executable for p in processes] == ['a', 'c', 'd', 'e', 'f']
    assert processes[0].namespace == '/robot/arm'
    assert processes[1].namespace == '/robot'
    assert processes[2].name == 'robot'  # the group's let did not leak
    assert processes[3].namespace == '/top'  # the unscoped group's push did
    assert [p.label for p in processes] == ['a-1', 'c-2', 'd-3', 'custom-4', 'f-5']
    with_b = load_launch_file(path, {'with_b': 'true'}).processes
    assert [p.executable for p in with_b] == ['a', 'b', 'd', 'e']


def test_include_with_arguments_and_find_pkg_share(tmp_path):
    share = tmp_path / 'install' / 'my_pkg' / 'share' / 'my_pkg'
    (share / 'launch').mkdir(parents=True)
    _write(share / 'launch' / 'inner.launch.yaml', """
        launch:
        - arg: {name: who}
        - node: {pkg: my_pkg, exec: greeter, name: $(var who)}
    """)
    outer = _write(tmp_path / 'outer.launch.xml', """
        <launch>
          <include file="$(find-pkg-share my_pkg)/launch/inner.launch.yaml">
            <arg name="who" value="alice"/>
          </include>
          <include file="$(find-pkg-share my_pkg)/launch/inner.launch.yaml">
            <arg name="who" value="bob"/>
          </include>
        </launch>
    """)
    install = InstallSpace(tmp_path / 'install')
    plan = load_launch_file(outer, install_space=install)
    assert [p.name for p in plan.processes] == ['alice', 'bob']
    assert [p.label for p in plan.processes] == ['greeter-1', 'greeter-2']
    with pytest.raises(LaunchError, match=r"outer\.launch\.xml:2: package 'my_pkg' is not in "
                       r'the install space'):
        load_launch_file(outer, install_space=InstallSpace(tmp_path))


def test_include_loop_is_an_error(tmp_path):
    _write(tmp_path / 'a.launch.xml', '<launch><include file="b.launch.xml"/></launch>')
    _write(tmp_path / 'b.launch.xml', '<launch><include file="a.launch.xml"/></launch>')
    with pytest.raises(LaunchError, match='include each other in a loop'):
        load_launch_file(tmp_path / 'a.launch.xml')


def test_parameter_files_become_node_scoped_parameters(tmp_path):
    _write(tmp_path / 'params.yaml', """
        /**:
          ros__parameters:
            use_sim_time: false
        talker:
          ros__parameters:
            rate: 2.5
            topics: {chatter: news, list: [1, 2]}
        my_ns:
          my_node:
            ros__parameters:
              word: '100'
    """)
    path = _write(tmp_path / 'p.launch.xml', """
        <launch>
          <node pkg="p" exec="talker" name="talker">
            <param from="$(dirname)/params.yaml"/>
          </node>
        </launch>
    """)
    process = load_launch_file(path).processes[0]
    argv = process.ros_argv()
    assert argv[argv.index('-p') + 1] == 'use_sim_time:=false'
    assert 'talker:rate:=2.5' in argv
    assert 'talker:topics.chatter:=news' in argv
    assert 'talker:topics.list:=[1, 2]' in argv
    assert "my_node:word:='100'" in argv


# The frontend test of launch_ros (Humble: test_launch_ros/frontend/
# test_node_frontend.py), its first node, with the values it expects.
UPSTREAM_XML = r"""
<launch>
    <let name="a_string" value="\'[2, 5, 8]\'"/>
    <let name="a_list" value="[2, 5, 8]"/>
    <let name="my_value" value="100"/>
    <node pkg="demo_nodes_py" exec="talker_qos" output="screen" name="my_talker" namespace="my_ns" exec_name="my_talker_process" args="--number_of_cycles 1" ros_args="--log-level info">
        <param name="param1" value="ads"/>
        <param name="param_group1">
            <param name="param_group2">
                <param name="param2" value="2"/>
            </param>
            <param name="param3" value="2, 5, 8" value-sep=", "/>
            <param name="param4" value="$(var a_list)"/>
            <param name="param5" value="$(var a_string)"/>
            <param name="param6" value="2., 5., 8." value-sep=", "/>
            <param name="param7" value="'2', '5', '8'" value-sep=", "/>
            <param name="param8" value="&quot;'2'&quot;, &quot;'5'&quot;, &quot;'8'&quot;" value-sep=", "/>
            <param name="param9" value="\'2\', \'5\', \'8\'" value-sep=", "/>
            <param name="param10" value="&quot;'asd'&quot;, &quot;'bsd'&quot;, &quot;'csd'&quot;" value-sep=", "/>
            <param name="param11" value="'\asd', '\bsd', '\csd'" value-sep=", "/>
            <param name="param12" value="''"/>
            <param name="param13" value="$(var my_value)" type="str"/>
            <param name="param14" value="'2', '5', '8'" value-sep=", " type="list_of_str"/>
            <param name="param15" value="2, 5, 8" value-sep=", " type="list_of_str"/>
        </param>
        <param from="PARAMS"/>
        <env name="var" value="1"/>
        <remap from="foo" to="bar"/>
        <remap from="baz" to="foobar"/>
    </node>
</launch>
"""  # noqa: E501

UPSTREAM_YAML = r"""
launch:
    - let:
        name: 'a_string'
        value: "'[2, 5, 8]'"
    - let:
        name: 'a_list'
        value: '[2, 5, 8]'
    - let:
        name: 'my_value'
        value: '100'
    - node:
        pkg: demo_nodes_py
        exec: talker_qos
        output: screen
        name: my_talker
        namespace: my_ns
        exec_name: my_talker_process
        args: '--number_of_cycles 1'
        ros_args: '--log-level info'
        param:
            -   name: param1
                value: ads
            -   name: param_group1
                param:
                -   name: param_group2
                    param:
                    -   name: param2
                        value: 2
                -   name: param3
                    value: [2, 5, 8]
                -   name: param4
                    value: $(var a_list)
                -   name: param5
                    value: $(var a_string)
                -   name: param6
                    value: [2., 5., 8.]
                -   name: param7
                    value: ['2', '5', '8']
                -   name: param8
                    value: ["'2'", "'5'", "'8'"]
                -   name: param9
                    value: ["\\'2\\'", "\\'5\\'", "\\'8\\'"]
                -   name: param10
                    value: ["'asd'", "'bsd'", "'csd'"]
                -   name: param11
                    value: ['\asd', '\bsd', '\csd']
                -   name: param12
                    value: ''
                -   name: param13
                    value: '$(var my_value)'
                    type: str
                -   name: param14
                    value: ["'2'", "'5'", "'8'"]
                    type: list_of_str
                -   name: param15
                    value: ['2', '5', '8']
                    type: list_of_str
            -   from: PARAMS
        env:
            -   name: var
                value: '1'
        remap:
            -   from: "foo"
                to: "bar"
            -   from: "baz"
                to: "foobar"
"""


@pytest.mark.parametrize('name,text', [
    ('up.launch.xml', UPSTREAM_XML), ('up.launch.yaml', UPSTREAM_YAML)])
def test_launch_ros_frontend_test_gives_the_same_values(tmp_path, name, text):
    params_file = _write(tmp_path / 'params.yaml', """
        my_ns:
          my_node:
            ros__parameters:
              param_from_file_1: 1
              param_from_file_2: 'asd'
    """)
    path = _write(tmp_path / name, text.replace('PARAMS', str(params_file)))
    process = load_launch_file(path).processes[0]
    assert process.label == 'my_talker_process-1'
    assert process.arguments == ['--number_of_cycles', '1']
    assert process.env == {'var': '1'}
    argv = process.argv()
    assert argv[:5] == ['--number_of_cycles', '1', '--ros-args', '--log-level', 'info']
    assert argv[-4:] == ['-r', 'foo:=bar', '-r', 'baz:=foobar']
    params = _params(process)
    assert params == {
        'param1': 'ads',
        'param_group1.param_group2.param2': 2,
        'param_group1.param3': [2, 5, 8],
        'param_group1.param4': [2, 5, 8],
        'param_group1.param5': '[2, 5, 8]',
        'param_group1.param6': [2., 5., 8.],
        'param_group1.param7': ['2', '5', '8'],
        'param_group1.param8': ["'2'", "'5'", "'8'"],
        'param_group1.param9': ["'2'", "'5'", "'8'"],
        'param_group1.param10': ["'asd'", "'bsd'", "'csd'"],
        'param_group1.param11': ['asd', 'bsd', 'csd'],
        'param_group1.param12': '',
        'param_group1.param13': '100',
        'param_group1.param14': ["'2'", "'5'", "'8'"],
        'param_group1.param15': ['2', '5', '8'],
        'my_node:param_from_file_1': 1,
        'my_node:param_from_file_2': 'asd',
    }


def test_substitutions(tmp_path):
    path = _write(tmp_path / 's.launch.xml', """
        <launch>
          <arg name="n" default="3"/>
          <node pkg="p" exec="e" args="$(eval '$(var n) * 2') $(env COLCON_WASM_TEST_ENV) \
$(env COLCON_WASM_UNSET fallback) '$(var n) quoted' $(anon x) $(and true $(not false))"/>
        </launch>
    """)
    process = load_launch_file(path, environ={'COLCON_WASM_TEST_ENV': 'from-env'}).processes[0]
    assert process.arguments[:5] == ['6', 'from-env', 'fallback', '3 quoted', process.arguments[4]]
    assert process.arguments[4].startswith('x_')
    assert process.arguments[5] == 'true'


@pytest.mark.parametrize('name,text,message', [
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n</launch>\n',
     r'bad\.launch\.xml:3: not valid XML: mismatched tag'),
    ('bad.launch.yaml', 'launch:\n- node: {pkg: p, exec: e\n',
     r'bad\.launch\.yaml:3: not valid YAML'),
    ('bad.launch.yaml', 'nodes:\n- node: {pkg: p}\n',
     r"one top-level key 'launch'"),
    ('bad.launch.xml', '<robot/>\n', r':1: the root tag is <robot>, expected <launch>'),
    ('bad.launch.xml', '<launch>\n\n  <executable cmd="ls"/>\n</launch>\n',
     r':3: <executable> is not supported by colcon-wasm launch'),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" nmae="x"/>\n</launch>\n',
     r":2: unexpected attribute 'nmae' in <node>"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n    <remapp/>\n  </node>\n'
     '</launch>\n', r':3: unexpected tag <remapp> inside <node>'),
    ('bad.launch.xml', '<launch>\n  <node exec="e"/>\n</launch>\n',
     r":2: <node> needs the attribute 'pkg'"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" name="$(var nope)"/>\n</launch>\n',
     r":2: launch configuration 'nope' is not set"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" name="$(command ls)"/>\n</launch>\n',
     r':2: \$\(command\) is not supported'),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" name="$(var x"/>\n</launch>\n',
     r':2: substitution \$\(var \.\.\. is not closed'),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" name="9lives"/>\n</launch>\n',
     r":2: node name '9lives' is not valid"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" respawn="true"/>\n</launch>\n',
     r":2: the <node> attribute 'respawn' is not supported"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e">\n'
     '    <param name="x" value="a" type="int"/>\n  </node>\n</launch>\n',
     r":3: parameter 'x': 'a' is not a int"),
    ('bad.launch.xml', '<launch>\n  <node pkg="p" exec="e" if="maybe"/>\n</launch>\n',
     r":2: a condition must be true/false or 1/0, got 'maybe'"),
    ('bad.launch.py', 'print()\n', r"Python launch files are not read here: Humble's launch runs"),
])
def test_errors_name_the_file_and_line(tmp_path, name, text, message):
    path = tmp_path / name
    path.write_text(text, encoding='utf-8')
    with pytest.raises(LaunchError, match=message) as info:
        load_launch_file(path, environ={})
    assert str(info.value).startswith(str(path))


def test_yaml_error_lines_point_at_the_attribute(tmp_path):
    path = _write(tmp_path / 'l.launch.yaml', """
        launch:
        - node:
            pkg: p
            exec: e
            name: $(var missing)
    """)
    with pytest.raises(LaunchError, match=r"l\.launch\.yaml:5: launch configuration 'missing'"):
        load_launch_file(path)


def test_items_and_launch_arguments():
    plan = plan_items(['demo_nodes/talker', 'demo_nodes/listener', 'demo_nodes/talker'])
    assert [p.label for p in plan.processes] == ['talker-1', 'listener-2', 'talker-3']
    assert plan.processes[0].argv() == []
    with pytest.raises(LaunchError, match="'talker' is neither a launch file nor a PKG/EXE"):
        plan_items(['talker'])
    assert split_launch_arguments(['a.launch.xml', 'x:=1', 'y:=a:=b', 'p/e']) == (
        ['a.launch.xml', 'p/e'], {'x': '1', 'y': 'a:=b'})
