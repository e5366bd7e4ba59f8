# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's 3D view (issue 37) with real nodes, in headless Chromium.

robot_state_publisher of the corpus build runs in the page with a fixture
URDF (tests/data/scene/demo_arm.urdf: a red base, a blue arm on a revolute
joint); an .rviz file is opened by hand; the page publishes joint states,
markers, a scan and a 100k-point cloud. The canvas' pixels are read where
the robot and the markers must be (tests/js/page_3d.mjs). Screenshots go to
artifacts/screenshots/3d/.
"""

import json
import os
from pathlib import Path
import signal
import subprocess
import sys
import time

from corpus_build import corpus_build
from humble_build import REPO
import pytest
from served_page import browser_skip_reason
from served_page import CHROMIUM
from served_page import JS
from served_page import ServedPage

DATA = REPO / 'tests' / 'data' / 'scene'
SCREENSHOTS = REPO / 'artifacts' / 'screenshots' / '3d'


def _blue(rgb):
    return rgb[2] > 60 and rgb[2] > 1.8 * max(rgb[0], rgb[1])


def _red(rgb):
    return rgb[0] > 60 and rgb[0] > 1.8 * max(rgb[1], rgb[2])


def _green(rgb):
    return rgb[1] > 60 and rgb[1] > 1.8 * max(rgb[0], rgb[2])


def _yellow(rgb):
    return min(rgb[0], rgb[1]) > 100 and rgb[2] < 0.6 * min(rgb[0], rgb[1])


def _drive(script, options, timeout=300, note=None):
    """Run a tests/js page driver with its options; return its JSON result, asserted ok."""
    completed = subprocess.run(['node', str(JS / script), json.dumps(options)],
                               capture_output=True, text=True, timeout=timeout)
    lines = completed.stdout.strip().splitlines()
    assert lines, f'{script} printed nothing: {completed.stderr[-3000:]}'
    out = json.loads(lines[-1])
    assert out['ok'], json.dumps(out, indent=1)[-6000:] + (note()[-3000:] if note else '')
    return out


@pytest.fixture(scope='module')
def result(tmp_path_factory):
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    build = corpus_build()
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    with ServedPage(build.install) as served:
        out = _drive('page_3d.mjs', {
            'url': served.url, 'chromium': CHROMIUM, 'urdf': str(DATA / 'demo_arm.urdf'),
            'rviz': str(DATA / 'demo_arm.rviz'), 'screenshots': str(SCREENSHOTS),
            'userDataDir': str(tmp_path_factory.mktemp('chromium'))}, timeout=400)
    print('page_3d stats:', json.dumps(out['stats']))
    return out


def test_rviz_file_gives_fixed_frame_displays_and_lists_what_it_cannot_show(result):
    rviz = result['checks']['rviz']
    assert rviz['fixedFrame'] == 'base_link'
    assert rviz['displays'] == [
        'RobotModel:RobotModel:/robot_description', 'TF:TF:null', 'Marker:Markers:/demo_markers',
        'LaserScan:Scan:/scan', 'PointCloud2:Cloud:/points']
    assert rviz['unsupported'] == [{'cls': 'rviz_default_plugins/Camera', 'name': 'Front camera'}]
    assert 'Front camera (rviz_default_plugins/Camera)' in rviz['notes']


def test_robot_model_says_which_link_has_no_transform(result):
    before = result['checks']['beforeJointStates']
    assert before['level'] == 'error', before
    assert before['text'] == 'No transform from [arm] to [base_link]'
    assert result['checks']['robotStatus'] == {'level': 'ok', 'text': 'demo_arm: 2 links'}


def test_robot_is_drawn_where_the_urdf_puts_it_and_moves_with_the_joint(result):
    arm0, arm90, base = (p['rgb'] for p in result['checks']['at0'])
    assert _blue(arm0), result['checks']['at0']
    assert not _blue(arm90), result['checks']['at0']
    assert _red(base), result['checks']['at0']
    arm0, arm90, base = (p['rgb'] for p in result['checks']['at90'])
    assert _blue(arm90), result['checks']['at90']
    assert not _blue(arm0), result['checks']['at90']
    assert _red(base), result['checks']['at90']


def test_tf_tree_lists_the_frames(result):
    assert result['checks']['tfTree'] == ['base_link', 'arm']


def test_marker_array_add_and_deleteall(result):
    assert result['checks']['markerStatus']['text'] == '1 markers (demo: 1)'
    assert _green(result['checks']['markerAdded'][0]['rgb']), result['checks']['markerAdded']
    deleted = result['checks']['markerDeleted']
    assert not _green(deleted[0]['rgb']), deleted


def test_laser_scan_points_are_drawn(result):
    assert result['checks']['scanStatus'] == {'level': 'ok', 'text': '181 points'}
    assert _yellow(result['checks']['scan'][0]['rgb']), result['checks']['scan']


def test_100k_point_cloud_is_drawn_and_the_page_answers_clicks(result):
    cloud = result['stats']['cloud']
    assert cloud['points'] == 100000, cloud
    assert cloud['status'] == {'level': 'ok', 'text': '100000 points'}
    # the clicks were handled (each toggled the TF display); how fast: bench/page
    assert len(cloud['clicks']) >= 3, cloud


def test_log_dock_splitter_gives_the_canvas_room(result):
    before, after = result['checks']['splitter']['before'], result['checks']['splitter']['after']
    assert after['dock'] < before['dock'] - 80, result['checks']['splitter']
    assert after['canvas'] > before['canvas'] + 80, result['checks']['splitter']


def test_no_sideways_scrolling_at_developer_widths(result):
    for width, seen in result['stats']['widths'].items():
        assert seen['scrollWidth'] <= seen['innerWidth'], (width, seen)
        assert seen['canvas']['width'] > 300 and seen['canvas']['height'] > 300, (width, seen)
    assert not result['pageErrors'], result['pageErrors']


def robot_demo_link(install):
    """Return the query of the robot demo's one link (docs/launcher.md) for an install space."""
    from urllib.parse import quote
    share = install / 'demo_robot' / 'share' / 'demo_robot'
    params = share / 'config' / 'robot_state_publisher.yaml'
    runs = [f'robot_state_publisher/robot_state_publisher --ros-args --params-file {params}',
            'demo_robot/arm_motion']
    return '?' + '&'.join(f'run={quote(r)}' for r in runs) + \
        '&rviz=' + quote('package://demo_robot/rviz/demo.rviz')


def test_robot_demo_link_shows_the_arm_moving_in_3d():
    from launch_build import robot_demo_build
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    build = robot_demo_build()
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    with ServedPage(build.install) as served:
        out = _drive('page_robot_demo.mjs', {
            'url': served.url + robot_demo_link(build.install), 'chromium': CHROMIUM,
            'screenshot': str(SCREENSHOTS / 'robot_demo_1440.png')})
    checks = out['checks']
    print('robot demo:', json.dumps(checks))
    assert checks['status']['RobotModel'] == {'level': 'ok', 'text': 'demo_arm: 6 links'}
    assert checks['status']['Laser'] == {'level': 'ok', 'text': '2160 points'}
    assert checks['meshes'] == 2, 'the upper arm and the gripper are STL meshes of demo_robot'
    assert set(checks['frames']) >= {'base_link', 'turret', 'upper_arm', 'forearm', 'gripper',
                                     'laser_frame'}
    moved = sum((a - b) ** 2 for a, b in zip(checks['gripperBefore'], checks['gripperAfter']))
    assert moved > 1e-4, 'the arm moves: arm_motion swings its joints'
    # the column of displays folds away (a 1024 px window wants the width), kept per install
    fold = checks['fold']
    assert fold['folded'] > fold['before'] + 250, fold
    assert fold['afterReload'] is True and fold['unfolded'] is True, fold


def test_python_launch_robot_is_seen_in_the_page_over_rosbridge(tmp_path):
    """`colcon-wasm launch demo_robot robot.launch.py --rosbridge`: its rviz2 note's link works."""
    from launch_build import robot_demo_build
    from zenoh_peers import free_port
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    build = robot_demo_build()
    port = free_port()
    output = tmp_path / 'launch.txt'
    with open(output, 'w') as sink:
        launch = subprocess.Popen(
            [str(Path(sys.executable).parent / 'colcon-wasm'), 'launch', '--install-base',
             str(build.install), 'demo_robot', 'robot.launch.py', '--rosbridge',
             f'127.0.0.1:{port}', '--duration', '150'], stdout=sink, stderr=subprocess.STDOUT,
            start_new_session=True)
    try:
        deadline = time.monotonic() + 90
        while 'rosbridge server listening' not in output.read_text():
            assert launch.poll() is None and time.monotonic() < deadline, output.read_text()
            time.sleep(0.2)
        with ServedPage(build.install) as served:
            out = _drive('page_robot_demo.mjs', {
                'url': f'{served.url}?rosbridge=ws://127.0.0.1:{port}'
                       '&rviz=package://demo_robot/rviz/demo.rviz',
                'chromium': CHROMIUM,
                'screenshot': str(SCREENSHOTS / 'robot_launch_rosbridge_1440.png')},
                note=output.read_text)
    finally:
        # Ctrl-C, as a terminal sends it: to the launch's process group
        os.killpg(launch.pid, signal.SIGINT)
        launch.wait(60)
    note = output.read_text()
    assert out['checks']['status']['RobotModel'] == {'level': 'ok', 'text': 'demo_arm: 6 links'}
    assert out['checks']['status']['Laser'] == {'level': 'ok', 'text': '2160 points'}
    assert 'its display file package://demo_robot/rviz/demo.rviz: the page shows it' in note
