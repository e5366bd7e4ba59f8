# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Real Humble packages, unmodified, built as an overlay and run (issue 14).

tests/corpus_build.py builds geometry2, robot_state_publisher with urdf,
urdfdom, kdl_parser and orocos KDL, message_filters, diagnostics and angles
on the cached rclcpp build. Three of their executables run here, in Node.js
through `colcon-wasm launch` and in Chromium through the page of
`colcon-wasm serve`:

* tf2_ros' static_transform_publisher, heard by tf2_echo;
* robot_state_publisher with a URDF as its robot_description parameter,
  publishing /tf_static, and /tf from /joint_states (its URDF parser is a
  pluginlib plugin of urdf);
* diagnostic_aggregator loading its analyzers (pluginlib plugins) from a
  YAML parameters file of the install space.
"""

from pathlib import Path
import subprocess
import sys

from corpus_build import CORPUS_UP_TO
from corpus_build import corpus_build
import pytest
from served_page import explain_page
from served_page import ServedPage

COLCON_WASM = Path(sys.executable).parent / 'colcon-wasm'

"""The transforms two_link.urdf gives for shoulder=0.5 (rad, about z)."""
STATIC_SENSOR = 'TF /tf_static base_link->sensor 0.100 0.000 0.200 0.000 0.000 0.000 1.000'
ARM = 'TF /tf base_link->arm 0.000 0.000 0.500 0.000 0.000 0.247 0.969'


@pytest.fixture(scope='module')
def build():
    """Get the (cached) corpus overlay."""
    return corpus_build()


def _launch(build, tmp_path, text, seconds):
    path = tmp_path / 'test.launch.xml'
    path.write_text(text)
    done = subprocess.run(
        [str(COLCON_WASM), 'launch', '--install-base', str(build.install), str(path),
         '--duration', str(seconds)], capture_output=True, text=True, timeout=180)
    return done, done.stdout + done.stderr


def _config(build, name):
    return build.install / 'corpus_probe' / 'share' / 'corpus_probe' / 'config' / name


def test_every_listed_package_was_built(build):
    assert set(CORPUS_UP_TO) <= set(build.packages)
    assert {'tinyxml_vendor', 'orocos_kdl', 'urdfdom'} <= set(build.packages)
    # TinyXML 1 built from Debian's source package (here, or in the underlay
    # when that already has it)
    from colcon_wasm.launch.install_space import InstallSpace
    tinyxml = InstallSpace(build.install).package('tinyxml')
    assert (tinyxml.prefix / 'lib' / 'libtinyxml.a').is_file()
    assert (tinyxml.prefix / 'include' / 'tinyxml.h').read_text().count('TIXML_USE_STL') >= 2
    # the middleware and the core come from the underlay
    assert 'rclcpp' not in build.packages and 'rmw_wasm_cpp' not in build.packages


def test_static_transform_publisher_heard_by_tf2_echo_in_node(build, tmp_path):
    done, out = _launch(build, tmp_path, '''<launch>
  <node pkg="tf2_ros" exec="static_transform_publisher"
        args="--x 1 --y 2 --z 3 --yaw 0.5 --frame-id world --child-frame-id robot"/>
  <node pkg="tf2_ros" exec="tf2_echo" args="world robot"/>
</launch>''', 5)
    assert '- Translation: [1.000, 2.000, 3.000]' in out, out[-3000:]
    assert '- Rotation: in RPY (radian) [0.000, -0.000, 0.500]' in out


def test_robot_state_publisher_in_node(build, tmp_path):
    urdf = _config(build, 'two_link.urdf').read_text()
    params = tmp_path / 'rsp.yaml'
    params.write_text('robot_state_publisher:\n  ros__parameters:\n    robot_description: |\n'
                      + ''.join(f'      {line}\n' for line in urdf.splitlines()))
    done, out = _launch(build, tmp_path, f'''<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="robot_state_publisher">
    <param from="{params}"/>
  </node>
  <node pkg="corpus_probe" exec="corpus_probe" args="joint_states shoulder=0.5"/>
  <node pkg="corpus_probe" exec="corpus_probe" args="tf"/>
</launch>''', 6)
    assert 'got segment arm' in out, out[-3000:]
    assert STATIC_SENSOR in out, out[-3000:]
    assert ARM in out, out[-3000:]


def test_diagnostic_aggregator_loads_its_analyzers_in_node(build, tmp_path):
    done, out = _launch(build, tmp_path, f'''<launch>
  <node pkg="diagnostic_aggregator" exec="aggregator_node" name="analyzers">
    <param from="{_config(build, 'analyzers.yaml')}"/>
  </node>
  <node pkg="corpus_probe" exec="corpus_probe" args="diagnostics"/>
</launch>''', 6)
    assert "Initialized analyzer 'Motors' with path '/Robot/Motors'" in out, out[-3000:]
    assert 'AGG /Robot/Motors/motor_left level=1 motor hot' in out, out[-3000:]
    assert 'AGG /Robot/Sensors/imu level=0 imu fine' in out
    assert 'AGG /Robot level=1 Warning' in out


def test_the_three_in_chromium(build):
    urdf = _config(build, 'two_link.urdf').read_text()
    with ServedPage(build.install) as page:
        result = page.run([
            {'start': 'stp', 'pkg': 'tf2_ros', 'exe': 'static_transform_publisher',
             'args': ['--x', '1', '--y', '2', '--z', '3', '--frame-id', 'world',
                      '--child-frame-id', 'robot']},
            {'start': 'echo', 'pkg': 'tf2_ros', 'exe': 'tf2_echo', 'args': ['world', 'robot']},
            {'wait': 'echo', 'text': '- Translation: [1.000, 2.000, 3.000]'},
            {'start': 'rsp', 'pkg': 'robot_state_publisher', 'exe': 'robot_state_publisher',
             'args': ['--ros-args', '-p', f'robot_description:={urdf}']},
            {'start': 'joints', 'pkg': 'corpus_probe', 'exe': 'corpus_probe',
             'args': ['joint_states', 'shoulder=0.5']},
            {'start': 'tf', 'pkg': 'corpus_probe', 'exe': 'corpus_probe', 'args': ['tf']},
            {'wait': 'tf', 'text': STATIC_SENSOR},
            {'wait': 'tf', 'text': ARM},
            {'start': 'agg', 'pkg': 'diagnostic_aggregator', 'exe': 'aggregator_node',
             'args': ['--ros-args', '--params-file', str(_config(build, 'analyzers.yaml'))]},
            {'start': 'diag', 'pkg': 'corpus_probe', 'exe': 'corpus_probe',
             'args': ['diagnostics']},
            {'wait': 'diag', 'text': 'AGG /Robot/Motors/motor_left level=1 motor hot'},
        ])
    assert result['ok'], explain_page(result)
