# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python launch files, run by Humble's own launch and launch_ros on the build host.

The launch build (tests/launch_build.py) holds Humble's last launch 1.0.14 and
launch_ros 0.19.14, xacro, robot_state_publisher, rclcpp's component
containers and the fixtures ``demo_nodes_cpp`` and ``launch_cases``
(tests/ros_fixtures). The files run are the unmodified examples of
ros2launch (from the control-stack snapshot) and the fixture's, which use
what real robot launch files use: xacro in ``Command``, ``open()`` at load
time, a GUI node behind ``IfCondition``, ``OnProcessExit``, ``TimerAction``,
``respawn``, lifecycle transitions, ``Shutdown`` on a node's exit, composable
nodes, and includes between Python, XML and YAML.
"""

import os
from pathlib import Path
import re
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from launch_build import launch_build  # noqa: E402, I100
from launch_build import upstream_examples  # noqa: E402
from launch_until import run_until  # noqa: E402


def _launch(build, *items, until=None, duration=30):
    command = [demo_build.venv_tool('colcon-wasm'), 'launch', '--install-base', build.install,
               '--duration', str(duration), *items]
    return run_until(command, until=until, env=dict(os.environ, USER='tester'))


def _seen(*patterns):
    return lambda out: all(re.search(p, out) for p in patterns)


def _share(build, package):
    return build.install / package / 'share' / package


# ------------------------------------------------------------- upstream files

def test_ros2launch_example_runs_unmodified():
    build = launch_build()
    code, out = _launch(build, upstream_examples() / 'example.launch.py', 'node_prefix:=my_',
                        until=_seen(r'\[listener-2\] .*\[my_listener\]: I heard: \[Hello World'))
    assert '[INFO] [talker-1]: process started with pid' in out, out
    assert re.search(r"\[talker-1\] .*\[my_talker\]: Publishing: 'Hello World: \d+'", out), out
    assert re.search(r'\[listener-2\] .*\[my_listener\]: I heard: \[Hello World: \d+\]', out), out
    # stopped as Ctrl-C stops ros2 launch: SIGINT to each node, which ends cleanly
    assert "[INFO] [talker-1]: sending signal 'SIGINT' to process[talker-1]" in out, out
    assert re.search(r'\[INFO\] \[talker-1\]: process has finished cleanly \[pid \d+\]', out), out
    assert code == 0, out


def test_ros2launch_include_example_with_its_default_argument_from_the_environment():
    build = launch_build()
    code, out = _launch(build, upstream_examples() / 'includes_example.launch.py',
                        until=_seen(r'\[FOOlistener\]: I heard'))
    assert f'Including launch file located at: {upstream_examples()}/example.launch.py' in out, \
        out
    assert re.search(r"\[FOOtalker\]: Publishing: 'Hello World", out), out
    assert code == 0, out


# ------------------------------------------------------- a robot description

def test_robot_launch_file_xacro_open_gui_condition_events_timer_and_respawn():
    build = launch_build()
    code, out = _launch(
        build, 'launch_cases', 'robot.launch.py', 'arm_length:=0.8',
        '--echo', '/robot_description',
        until=_seen(r'\[phoenix\]: phoenix 1(.|\n)*\[phoenix\]: phoenix 1(.|\n)*'
                    r'\[phoenix\]: phoenix 1', r'\[second\]: second 1', 'after 1.5 s',
                    r'<link name="arm">'))
    # open() of a share file at load time
    assert 'robot name from the config: two_link_arm' in out, out
    # xacro ran on the build host with the argument: robot_state_publisher publishes the result
    assert re.search(r'<origin xyz="0 0 0\.45"', out), out
    assert '<box size="0.05 0.05 0.8"/>' in out, out
    # the GUI node is behind IfCondition(gui), false by default
    assert 'joint_state_publisher_gui' not in out, out
    # OnProcessExit chains the second node after the first
    first_exit = out.index('first has exited: starting second')
    assert out.index('[first]: first 2') < first_exit < out.index('[second]: second 1'), out
    assert re.search(r'\[INFO\] \[exit_after-\d+\]: process has finished cleanly', out), out
    # respawn: the node that exits with 3 is started again after its delay
    assert re.search(r'\[ERROR\] \[exit_after-\d+\]: process has died \[pid \d+, exit code 3',
                     out), out
    assert len(re.findall(r'\[phoenix\]: phoenix 1', out)) >= 3, out
    assert code == 1, out  # a node died (with exit code 3): the status says so


def test_a_gui_node_is_left_out_with_a_note_and_the_launch_goes_on():
    build = launch_build()
    code, out = _launch(build, 'launch_cases', 'robot.launch.py', 'gui:=true',
                        until=_seen('joint_state_publisher_gui is not started',
                                    r'\[second\]: second 1'))
    assert re.search(
        r'joint_state_publisher_gui/joint_state_publisher_gui is not started: '
        r'joint_state_publisher_gui is a Qt program, with no WebAssembly build; '
        r'the launch goes on without it', out), out
    assert re.search(r'\[joint_state_publisher_gui-\d+\]: process has finished cleanly', out), out


def test_lifecycle_node_transitions_and_shutdown_on_a_nodes_exit():
    build = launch_build()
    code, out = _launch(build, 'launch_cases', 'lifecycle.launch.py', duration=60)
    # launch_ros' ROS node, on the launch's bus, drives the transitions
    assert '[lc_talker]: on_configure() is called.' in out, out
    assert "node 'lc_talker' reached the 'inactive' state, 'activating'." in out, out
    assert '[lc_talker]: on_activate() is called.' in out, out
    assert "node 'lc_talker' reached the 'active' state, launching 'listener'." in out, out
    assert re.search(r'\[listener\]: I heard: \[Lifecycle HelloWorld #\d+\]', out), out
    # Shutdown() on the stopper's exit ends the launch before its duration
    assert '[stopper]: exiting with code 0' in out, out
    assert 'stopping the launch after' not in out, out
    assert code == 0, out


def test_composable_node_container_and_load_composable_nodes():
    build = launch_build()
    code, out = _launch(build, 'launch_cases', 'composition.launch.py',
                        until=_seen("case listener heard: 'Hello", 'nope'))
    assert re.search(r"Loaded node '/talker' in container '/my_container'", out), out
    assert re.search(r"Loaded node '/listener' in container '/my_container'", out), out
    assert re.search(r"Failed to load node 'nope' of type 'composition_cases::Nope' in container "
                     r"'/my_container'", out), out


def test_includes_xml_to_python_to_yaml():
    build = launch_build()
    launch_file = _share(build, 'launch_cases') / 'launch' / 'includes_python.launch.xml'
    code, out = _launch(build, launch_file,
                        until=_seen(r'\[yaml_listener\]: I heard: \[Hello World'))
    assert re.search(r'\[yaml_listener\]: I heard: \[Hello World: \d+\]', out), out
    assert code == 0, out


# ----------------------------------------------------------------- errors

def test_a_launch_file_that_raises_gives_its_traceback_and_starts_nothing():
    build = launch_build()
    code, out = _launch(build, 'launch_cases', 'broken.launch.py')
    path = _share(build, 'launch_cases') / 'launch' / 'broken.launch.py'
    assert f'{path}: loading the launch file failed:' in out, out
    assert f'File "{path}", line 11, in generate_launch_description' in out, out
    assert "KeyError: 'listener'" in out, out
    assert 'process started' not in out, out
    assert code == 1, out


def test_unknown_and_missing_arguments_list_the_files_arguments(tmp_path):
    build = launch_build()
    code, out = _launch(build, 'launch_cases', 'robot.launch.py', 'arm_lenght:=2')
    assert "no launch argument named 'arm_lenght'" in out, out
    assert "Arguments (pass arguments as '<name>:=<value>'):" in out, out
    assert "'arm_length':\n        Length of the arm link (m)\n        (default: '0.5')" in out, \
        out
    assert code == 1, out
    required = tmp_path / 'needs.launch.py'
    required.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import DeclareLaunchArgument\n\n\n'
        'def generate_launch_description():\n'
        "    return LaunchDescription([DeclareLaunchArgument('robot', description='Which')])\n")
    code, out = _launch(build, required)
    assert "the required launch argument 'robot' is not given" in out, out
    assert "'robot':\n        Which" in out, out
    assert code == 1, out


def test_show_args_and_print_plan():
    build = launch_build()
    code, out = _launch(build, '--show-args', 'launch_cases', 'robot.launch.py')
    assert code == 0, out
    assert "'gui':\n        Start the GUI\n        (default: 'false')" in out, out
    code, out = _launch(build, '--print-plan', 'launch_cases', 'robot.launch.py')
    assert code == 0, out
    assert "ExecInPkg(pkg='robot_state_publisher', exec='robot_state_publisher')" in out, out
    assert 'process started' not in out, out


def test_a_command_that_fails_names_the_command_and_its_output(tmp_path):
    build = launch_build()
    launch_file = tmp_path / 'fails.launch.py'
    launch_file.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import LogInfo\n'
        'from launch.substitutions import Command\n\n\n'
        'def generate_launch_description():\n'
        '    return LaunchDescription([LogInfo(msg=Command(\n'
        "        ['sh -c \"echo oops >&2; exit 4\"']))])\n")
    code, out = _launch(build, launch_file)
    assert 'executed command failed' in out, out
    assert 'oops' in out, out
    assert code == 1, out


def test_without_launch_ros_the_error_says_what_to_build(tmp_path):
    install = demo_build.demo_install()
    launch_file = tmp_path / 'x.launch.py'
    launch_file.write_text('def generate_launch_description():\n    return None\n')
    command = [demo_build.venv_tool('colcon-wasm'), 'launch', '--install-base', install,
               launch_file]
    code, out = run_until(command)
    assert "Python launch files run with Humble's launch and launch_ros" in out, out
    assert 'colcon build --wasm --packages-up-to launch launch_ros launch_xml launch_yaml' \
        in out, out
    assert code == 1, out
