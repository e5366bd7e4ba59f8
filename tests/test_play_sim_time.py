# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
`launch --play BAG --clock` drives an rclcpp node with `use_sim_time`.

A bag written by the third-party `rosbags` (std_msgs/String, 100 ms apart,
starting at a known time long past) is played with `--clock`; the probe of
rmw_wasm_cpp_node_tests (tests/rclcpp_build.py) runs `sim_time` with
`use_sim_time: true` and logs `node->now()` once the time comes from
/clock: it must be the bag's time, not the wall clock's.
"""

from pathlib import Path
import re
import subprocess
import sys
import textwrap

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rclcpp_build import rclcpp_build  # noqa: E402, I100, I202

STRING = 'std_msgs/msg/String'
START_NS = 1_600_000_000_000_000_000
COUNT = 40
GAP_NS = 100_000_000


def _write_bag(path):
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import get_typestore, Stores
    typestore = get_typestore(Stores.ROS2_HUMBLE)
    String = typestore.types[STRING]
    with Writer(path, version=8, storage_plugin=StoragePlugin.MCAP) as writer:
        connection = writer.add_connection('/bag_chatter', STRING, typestore=typestore)
        for i in range(COUNT):
            writer.write(connection, START_NS + i * GAP_NS,
                         typestore.serialize_cdr(String(data=f'bag {i}'), STRING))


def test_clock_from_a_bag_drives_a_use_sim_time_rclcpp_node(tmp_path):
    install = rclcpp_build().install
    bag = tmp_path / 'bag'
    _write_bag(bag)
    launch = tmp_path / 'sim.launch.yaml'
    launch.write_text(textwrap.dedent("""
        launch:
        - node:
            pkg: rmw_wasm_cpp_node_tests
            exec: probe
            args: sim_time
            name: sim_time
            param:
            - {name: use_sim_time, value: true}
    """).lstrip(), encoding='utf-8')
    command = [str(Path(sys.executable).parent / 'colcon-wasm'), 'launch', '--install-base',
               str(install), '--duration', '40', '--play', str(bag), '--clock', '50',
               str(launch)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=180)
    output = done.stdout + done.stderr
    assert 'USE_SIM_TIME true' in output, output
    match = re.search(r'SIM_TIME (\d+\.\d)', output)
    assert match, output
    seconds = float(match.group(1))
    first, last = START_NS / 1e9, (START_NS + (COUNT - 1) * GAP_NS) / 1e9
    assert first <= seconds <= last + 0.1, (seconds, first, last, output)
