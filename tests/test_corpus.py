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

from corpus_build import corpus_build
from corpus_build import CORPUS_UP_TO
from corpus_scenarios import ARM
from corpus_scenarios import config
from corpus_scenarios import run_scenario
from corpus_scenarios import STATIC_SENSOR
import pytest
from served_page import explain_page
from served_page import ServedPage


@pytest.fixture(scope='module')
def build():
    """Get the (cached) corpus overlay."""
    return corpus_build()


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


@pytest.mark.parametrize('scenario', [
    'static_transform', 'robot_state_publisher', 'diagnostic_aggregator'])
def test_runs_in_node(build, tmp_path, scenario):
    missing, out = run_scenario(scenario, build.install, tmp_path)
    assert not missing, f'missing {missing} in:\n{out[-4000:]}'


def test_the_three_in_chromium(build):
    urdf = config(build.install, 'two_link.urdf').read_text()
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
             'args': ['--ros-args', '--params-file',
                      str(config(build.install, 'analyzers.yaml'))]},
            {'start': 'diag', 'pkg': 'corpus_probe', 'exe': 'corpus_probe',
             'args': ['diagnostics']},
            {'wait': 'diag', 'text': 'AGG /Robot/Motors/motor_left level=1 motor hot'},
        ])
    assert result['ok'], explain_page(result)
