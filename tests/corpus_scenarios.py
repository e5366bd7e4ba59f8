# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The corpus executables' runs, shared by tests/test_corpus.py and bench/corpus.

Each scenario is a launch file (for `colcon-wasm launch` in Node.js) and the
lines its output must hold.
"""

from pathlib import Path
import subprocess
import sys

COLCON_WASM = Path(sys.executable).parent / 'colcon-wasm'

"""The transforms two_link.urdf gives for shoulder=0.5 (rad, about z)."""
STATIC_SENSOR = 'TF /tf_static base_link->sensor 0.100 0.000 0.200 0.000 0.000 0.000 1.000'
ARM = 'TF /tf base_link->arm 0.000 0.000 0.500 0.000 0.000 0.247 0.969'


def config(install, name):
    """Get a data file corpus_probe installs (share/corpus_probe/config/)."""
    return Path(install) / 'corpus_probe' / 'share' / 'corpus_probe' / 'config' / name


def static_transform(install, folder):
    """static_transform_publisher, heard by tf2_echo."""
    return ("""<launch>
  <node pkg="tf2_ros" exec="static_transform_publisher"
        args="--x 1 --y 2 --z 3 --yaw 0.5 --frame-id world --child-frame-id robot"/>
  <node pkg="tf2_ros" exec="tf2_echo" args="world robot"/>
</launch>""", ['- Translation: [1.000, 2.000, 3.000]',
               '- Rotation: in RPY (radian) [0.000, -0.000, 0.500]'])


def robot_state_publisher(install, folder):
    """robot_state_publisher with a URDF and joint states; /tf and /tf_static heard."""
    urdf = config(install, 'two_link.urdf').read_text()
    params = Path(folder) / 'rsp.yaml'
    params.write_text('robot_state_publisher:\n  ros__parameters:\n    robot_description: |\n'
                      + ''.join(f'      {line}\n' for line in urdf.splitlines()))
    return (f"""<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="robot_state_publisher">
    <param from="{params}"/>
  </node>
  <node pkg="corpus_probe" exec="corpus_probe" args="joint_states shoulder=0.5"/>
  <node pkg="corpus_probe" exec="corpus_probe" args="tf"/>
</launch>""", ['got segment arm', STATIC_SENSOR, ARM])


def diagnostic_aggregator(install, folder):
    """diagnostic_aggregator with its analyzers (pluginlib) from a YAML file."""
    return (f"""<launch>
  <node pkg="diagnostic_aggregator" exec="aggregator_node" name="analyzers">
    <param from="{config(install, 'analyzers.yaml')}"/>
  </node>
  <node pkg="corpus_probe" exec="corpus_probe" args="diagnostics"/>
</launch>""", ["Initialized analyzer 'Motors' with path '/Robot/Motors'",
               'AGG /Robot/Motors/motor_left level=1 motor hot',
               'AGG /Robot/Sensors/imu level=0 imu fine', 'AGG /Robot level=1 Warning'])


"""Scenario name: (function, the executables it runs, seconds)."""
SCENARIOS = {
    'static_transform': (static_transform,
                         ['tf2_ros/static_transform_publisher', 'tf2_ros/tf2_echo'], 5),
    'robot_state_publisher': (robot_state_publisher,
                              ['robot_state_publisher/robot_state_publisher'], 6),
    'diagnostic_aggregator': (diagnostic_aggregator,
                              ['diagnostic_aggregator/aggregator_node'], 6),
}


def run_scenario(name, install, folder):
    """
    Launch a scenario in Node.js.

    :returns: (missing expected lines, the output)
    """
    make, _, seconds = SCENARIOS[name]
    text, expected = make(install, folder)
    path = Path(folder) / f'{name}.launch.xml'
    path.write_text(text)
    done = subprocess.run(
        [str(COLCON_WASM), 'launch', '--install-base', str(install), str(path),
         '--duration', str(seconds)], capture_output=True, text=True, timeout=180)
    out = done.stdout + done.stderr
    return [line for line in expected if line not in out], out
