# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The pieces of Python launch files that run without a build.

rclpy's name validation against rmw's rules, the shim's environment,
parameter files and path mapping, the front's arguments, the GUI note, the
host link's wire values, and the host prefix of an install space.
"""

import json
import os
from pathlib import Path
import sys

from colcon_wasm.launch.python_launch import front
from colcon_wasm.launch.python_launch import gui_shim
from colcon_wasm.launch.python_launch import node_shim
import pytest

REPO = Path(__file__).resolve().parents[1]
RCLPY_FOLDER = str(REPO / 'packages' / 'wasm_js' / 'src' / 'python')


@pytest.fixture(scope='module')
def rclpy_modules():
    """
    Import colcon-wasm's rclpy as the build host does, for this module only.

    It is taken off sys.path and sys.modules again after them, so that no other
    test of the session (third-party clients that probe for an rclpy) meets it.
    """
    import importlib
    sys.path.insert(0, RCLPY_FOLDER)
    try:
        yield {name: importlib.import_module(f'rclpy.{name}') for name in (
            '_host_link', 'validate_full_topic_name', 'validate_namespace', 'validate_node_name')}
    finally:
        sys.path.remove(RCLPY_FOLDER)
        for name in [n for n in sys.modules if n == 'rclpy' or n.startswith('rclpy.')]:
            del sys.modules[name]


@pytest.fixture
def validate_namespace(rclpy_modules):
    return rclpy_modules['validate_namespace'].validate_namespace


@pytest.fixture
def validate_node_name(rclpy_modules):
    return rclpy_modules['validate_node_name'].validate_node_name


@pytest.fixture
def validate_full_topic_name(rclpy_modules):
    return rclpy_modules['validate_full_topic_name'].validate_full_topic_name


@pytest.fixture
def host_link(rclpy_modules):
    return rclpy_modules['_host_link']


@pytest.mark.parametrize('namespace, message, index', [
    ('/', None, 0),
    ('/robot/arm_1', None, 0),
    ('', 'namespace must not be empty', 0),
    ('robot', "namespace must be absolute, it must lead with a '/'", 0),
    ('/robot/', "namespace must not end with a '/', unless only a '/'", 6),
    ('/ro-bot',
     "namespace must not contain characters other than alphanumerics, '_', or '/'", 3),
    ('/a//b', "namespace must not contain repeated '/'", 3),
    ('/a/1b', 'namespace must not have a token that starts with a number', 3),
    ('/' + 'a' * 245, "namespace should not exceed '245'", 244),
])
def test_validate_namespace_as_rmw(validate_namespace, namespace, message, index):
    if message is None:
        assert validate_namespace(namespace) is True
        return
    with pytest.raises(Exception) as info:
        validate_namespace(namespace)
    assert type(info.value).__name__ == 'InvalidNamespaceException'
    assert str(info.value) == (f'Invalid namespace: {message}:\n'
                               f"  '{namespace}'\n   {' ' * index}^")


@pytest.mark.parametrize('name, message, index', [
    ('talker_1', None, 0),
    ('', 'node name must not be empty', 0),
    ('9lives', 'node name must not start with a number', 0),
    ('my-node', "node name must not contain characters other than alphanumerics or '_'", 2),
    ('a' * 256, "node name length should not exceed '255'", 254),
])
def test_validate_node_name_as_rmw(validate_node_name, name, message, index):
    if message is None:
        assert validate_node_name(name) is True
        return
    with pytest.raises(Exception, match=r'^Invalid node name: ') as info:
        validate_node_name(name)
    assert message in str(info.value)
    assert str(info.value).endswith(f"   {' ' * index}^")


def test_validate_full_topic_name_for_services_raises_the_service_exception(
        validate_full_topic_name):
    assert validate_full_topic_name('/a/b') is True
    with pytest.raises(Exception) as info:
        validate_full_topic_name('a', is_service=True)
    assert type(info.value).__name__ == 'InvalidServiceNameException'
    assert "topic name must be absolute, it must lead with a '/'" in str(info.value)


def _config(tmp_path):
    return {
        'socket': str(tmp_path / 'bus.sock'),
        'host_prefix': str(tmp_path / 'prefix'),
        'shares': {'pkg': '/ws/install_wasm/pkg/share/pkg'},
        'ament_prefix_path': '/ws/install_wasm/pkg',
        'mounted': ['/ws/install_wasm'],
        'base_environment': {'HOME': '/root', 'AMENT_PREFIX_PATH': str(tmp_path / 'prefix'),
                             'PATH': '/bin', 'ROS_DOMAIN_ID': '3'},
    }


def test_shim_gives_real_paths_and_what_the_launch_set(tmp_path):
    config = _config(tmp_path)
    real = node_shim._real_paths(config)
    assert real(f'{tmp_path}/prefix/share/pkg/urdf/r.urdf') == \
        '/ws/install_wasm/pkg/share/pkg/urdf/r.urdf'
    assert real(f'file://{tmp_path}/prefix/share/other/x') == \
        f'file://{tmp_path}/prefix/share/other/x'  # not a package of the install: as it is
    environ = dict(config['base_environment'], PATH='/other', MY_VAR='1', HOME='/root')
    env = node_shim.node_environment(config, real, environ)
    # the launch's own variables and the ROS ones; host-only ones never
    assert env == {'MY_VAR': '1', 'ROS_DOMAIN_ID': '3',
                   'AMENT_PREFIX_PATH': '/ws/install_wasm/pkg'}


def test_shim_reads_the_parameter_files_outside_the_views(tmp_path):
    params = tmp_path / 'launch_params_x'
    params.write_text('/**:\n  ros__parameters:\n    rate: 2\n')
    files = node_shim.parameter_files(
        ['--ros-args', '--params-file', str(params), '--params-file',
         '/ws/install_wasm/pkg/share/pkg/p.yaml'], ['/ws/install_wasm'])
    assert files == {str(params): params.read_text()}
    with pytest.raises(SystemExit, match='cannot read the parameters file'):
        node_shim.parameter_files(['--params-file', str(tmp_path / 'gone')], [])


@pytest.mark.parametrize('event, status', [
    ({'code': 0, 'crashed': False, 'reason': ''}, 0),
    ({'code': 3, 'crashed': False, 'reason': ''}, 3),
    ({'code': None, 'crashed': False, 'reason': 'stopped'}, 0),
    ({'code': None, 'crashed': True, 'reason': 'RuntimeError: unreachable'}, 1),
    ({'code': 7, 'crashed': True, 'reason': 'abort'}, 7),
])
def test_shim_exit_status(event, status):
    assert node_shim._status(event) == status


def test_shim_without_a_launch_says_so(tmp_path, capsys):
    config = _config(tmp_path)
    config['processes'] = {'pkg/exe': {'label': 'exe'}}
    path = tmp_path / 'launch.json'
    path.write_text(json.dumps(config))
    assert node_shim.main([str(path), 'pkg/exe']) == 1
    assert "cannot reach the launch's bus" in capsys.readouterr().err


def test_front_parses_arguments_as_ros2_launch():
    assert front.parse_arguments(['a:=1', 'b:=x:=y', 'a:=2']) == {'a': '2', 'b': 'x:=y'}
    for bad in ('a', ':=1', 'a:='):
        with pytest.raises(front.FrontError, match='malformed launch argument'):
            front.parse_arguments([bad])


def test_gui_note_names_the_display_file():
    text = gui_shim.note('rviz2/rviz2', 'RViz is a Qt and OpenGL program', ['-d', 'a.rviz'])
    assert text.startswith('[colcon-wasm] rviz2/rviz2 is not started: RViz is a Qt and OpenGL')
    assert 'its display file a.rviz is not shown headless' in text
    text = gui_shim.note('rviz2/rviz2', 'RViz', ['-d', '/tmp/p/share/demo_robot/rviz/demo.rviz'])
    assert 'its display file package://demo_robot/rviz/demo.rviz: the page shows it' in text
    assert '/?rviz=package://demo_robot/rviz/demo.rviz' in text


def test_host_link_wire_values(host_link):
    assert host_link._to_wire({'a': 2 ** 60, 'b': b'\x01\x02', 'c': [1.5, True, None]}) == \
        {'a': {'$int': str(2 ** 60)}, 'b': [1, 2], 'c': [1.5, True, None]}
    answer = host_link._wrap({'value': {'stamp': {'$int': str(2 ** 62)}, 'ids': [1]},
                              'id': {'gid': [1, 2]}})
    assert answer.value.to_py() == {'stamp': 2 ** 62, 'ids': [1]}
    assert answer.id == {'gid': [1, 2]}


def test_host_prefix_of_an_install(tmp_path):
    sys.path.insert(0, str(REPO / 'tests'))
    import demo_build
    from colcon_wasm.launch.install_space import InstallSpace
    from colcon_wasm.launch.python_launch import HostLaunch
    install_space = InstallSpace(demo_build.demo_install())
    description = {'types': []}
    launch = HostLaunch(tmp_path / 'x.launch.py', {'a': '1'})
    launch.prepare(description, install_space, None,
                   runtime_python=REPO / 'packages' / 'wasm_js' / 'src' / 'python')
    try:
        root = launch.prefix.root
        shim = root / 'lib' / 'demo_nodes' / 'talker'
        assert os.access(shim, os.X_OK)
        assert 'node_shim.py' in shim.read_text()
        assert (root / 'share' / 'demo_nodes').resolve() == \
            install_space.package('demo_nodes').share.resolve()
        assert (root / 'share' / 'ament_index' / 'resource_index' / 'packages' /
                'demo_nodes').is_file()
        # GUI programs the install lacks stand in, with their reason
        assert 'Qt and OpenGL' in (root / 'lib' / 'rviz2' / 'rviz2').read_text()
        env = launch.front_environment()
        assert env['AMENT_PREFIX_PATH'] == str(root)
        config = json.loads(launch.prefix.config_path.read_text())
        assert config['processes']['demo_nodes/talker']['js'].endswith('talker.js')
        assert description['control']['socket'] == config['socket']
    finally:
        os.close(launch.ready)
        os.close(launch.ready_for_host)
        launch.cleanup()


def test_a_missing_host_tool_is_named_with_its_package():
    import logging
    record = logging.LogRecord('launch', logging.ERROR, __file__, 1,
                               'Caught exception in launch (see debug for traceback): '
                               "executable 'xacro' not found on the PATH", None, None)
    assert front.MissingToolHint().filter(record)
    assert "'xacro' comes from the package 'xacro': build it into the install space " \
        "('colcon build --wasm --packages-up-to xacro')" in record.msg
