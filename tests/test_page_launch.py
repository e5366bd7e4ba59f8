# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Launch files started from the page (issue 36, item 5), in headless Chromium.

``colcon-wasm serve`` lists the packages' launch files; the page reads a
file's arguments into a form and starts it. serve evaluates the file on the
build host with Humble's real launch and launch_ros (the launch overlay,
tests/launch_build.py); the nodes run in the page. Cases:

* demo_robot's ``robot.launch.py``: robot_state_publisher with launch_ros'
  parameters file, arm_motion, and ``rviz2 -d demo.rviz``, which becomes the
  page's 3D view with that file: the robot is drawn; Stop is launch's Ctrl-C;
* ``lifecycle.launch.py``: ChangeState and OnStateTransition through
  launch_ros' node, on the page's bus; ``Shutdown`` on a node's exit ends it;
* ``talker.launch.py topic:=news``: an argument given in the form, Python
  including YAML; the listener hears the talker on /news;
* ``broken.launch.py``: its traceback in the launch's log, exit code 1;
* the demo workspace (no launch_ros): its XML file read by colcon-wasm's
  reader, started from the page.

Driver: tests/js/page_launch.mjs. Screenshots: artifacts/screenshots/launch/.
"""

import json
import subprocess

from humble_build import REPO
import pytest
from served_page import browser_skip_reason
from served_page import CHROMIUM
from served_page import JS
from served_page import ServedPage

SCREENSHOTS = REPO / 'artifacts' / 'screenshots' / 'launch'
ROBOT_DRAWN = ("(() => { const d = window.colconWasm.views['3d'].displays.find((x) => "
               "x.name === 'RobotModel'); return d && d.status().level === 'ok' "
               '&& d.links.size === 6 && d.meshErrors.length === 0; })()')


def _log_has(label_start, text):
    """Return a JS expression: a process of the newest launch, so labelled, logged ``text``."""
    return ('(() => { const all = [...window.colconWasm.session.processes.values()]; '
            "const launch = all.filter((p) => p.kind === 'launch').pop(); "
            'return all.some((p) => p.launch === launch && p.label.startsWith('
            f'{json.dumps(label_start)}) && p.log.some((e) => '
            f'e.text.includes({json.dumps(text)}))); }})()')


def _drive(url, launches, timeout=600):
    completed = subprocess.run(
        ['node', str(JS / 'page_launch.mjs'),
         json.dumps({'url': url, 'chromium': CHROMIUM, 'launches': launches})],
        capture_output=True, text=True, timeout=timeout)
    lines = completed.stdout.strip().splitlines()
    assert lines, f'page_launch.mjs printed nothing: {completed.stderr[-3000:]}'
    return json.loads(lines[-1])


def _explain(out):
    text = []
    for label, lines in out['logs'].items():
        text += [f'[{label}] {line}' for line in lines]
    return f"error: {out['error']}\n" + '\n'.join(text + out['pageErrors'])[-7000:]


@pytest.fixture(scope='module')
def launched():
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    from launch_build import robot_demo_build
    build = robot_demo_build()
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    launches = [
        {'file': 'demo_robot/launch/robot.launch.py', 'until': ROBOT_DRAWN, 'stop': True,
         'values': "window.colconWasm.views['3d'].displays.map((d) => d.name)",
         'screenshot': str(SCREENSHOTS / 'robot_launch.png')},
        {'file': 'launch_cases/launch/lifecycle.launch.py', 'timeoutMs': 120000},
        {'file': 'launch_cases/launch/talker.launch.py', 'args': {'topic': 'news'},
         'until': _log_has('listener-', 'I heard'), 'stop': True},
        {'file': 'launch_cases/launch/broken.launch.py'},
    ]
    with ServedPage(build.install) as served:
        out = _drive(served.url, launches)
    assert out['ok'], _explain(out)
    return {seen['file'].split('/')[-1]: seen for seen in out['checks']['launches']} | {
        '_listed': out['checks']['listed'], '_errors': out['pageErrors']}


def test_the_packages_launch_files_are_listed(launched):
    listed = launched['_listed']
    for file in ('demo_robot/launch/robot.launch.py', 'launch_cases/launch/lifecycle.launch.py',
                 'launch_cases/launch/includes_python.launch.xml',
                 'launch_cases/launch/listener.launch.yaml'):
        assert file in listed, listed
    assert not launched['_errors'], launched['_errors']


def test_the_form_has_the_files_declared_arguments_and_their_defaults(launched):
    form = {f['name']: f for f in launched['robot.launch.py']['form']}
    assert set(form) == {'rate', 'rviz'}, form
    assert form['rate']['placeholder'] == '30.0'
    assert 'joint states per second' in form['rate']['text']


def test_robot_launch_runs_its_nodes_in_the_page_and_rviz_becomes_the_3d_view(launched):
    seen = launched['robot.launch.py']
    labels = sorted(p['label'].rsplit('-', 1)[0] for p in seen['processes'])
    assert labels == ['arm_motion', 'robot_state_publisher'], seen['processes']
    publisher = next(p for p in seen['processes'] if p['label'].startswith('robot_state'))
    assert '--params-file' in publisher['args'], publisher
    # rviz2 -d package://demo_robot/rviz/demo.rviz: its displays are the 3D view's
    assert {'RobotModel', 'Laser', 'Markers'} <= set(seen['values']), seen['values']
    log = '\n'.join(seen['entry']['log'])
    assert '[INFO] [rviz2-3]: process started' in log, log
    # Stop is launch's Ctrl-C: it signals each node, each ends cleanly
    assert 'user interrupted with ctrl-c (SIGINT)' in log, log
    assert "sending signal 'SIGINT' to process[arm_motion-2]" in log, log
    assert 'process[robot_state_publisher-1]' in log and 'finished cleanly' in log, log
    assert all(p['state'] in ('stopped', 'exited') for p in seen['processes']), seen['processes']


def test_lifecycle_transitions_and_shutdown_through_launch_ros_on_the_pages_bus(launched):
    seen = launched['lifecycle.launch.py']
    log = '\n'.join(seen['entry']['log'])
    assert "node 'lc_talker' reached the 'inactive' state, 'activating'." in log, log
    assert "node 'lc_talker' reached the 'active' state, launching 'listener'." in log, log
    assert 'process[exit_after-3] was required: shutting down launched system' in log, log
    assert seen['entry']['state'] == 'exited' and seen['entry']['exit']['code'] == 0, seen['entry']
    labels = {p['label'].rsplit('-', 1)[0] for p in seen['processes']}
    assert labels == {'lifecycle_talker', 'listener', 'exit_after'}, seen['processes']


def test_an_argument_of_the_form_reaches_the_nodes(launched):
    seen = launched['talker.launch.py']
    talker = next(p for p in seen['processes'] if p['label'].startswith('talker-'))
    assert 'chatter:=news' in talker['args'], talker
    listener = next(p for p in seen['processes'] if p['label'].startswith('listener-'))
    assert 'chatter:=news' in listener['args'], listener


def test_a_launch_file_that_raises_shows_its_traceback_and_starts_nothing(launched):
    seen = launched['broken.launch.py']
    # the form says so already: reading the arguments loads the file
    assert "KeyError: 'listener'" in seen['formError'], seen['formError']
    log = '\n'.join(seen['entry']['log'])
    assert 'Traceback (most recent call last):' in log, log
    assert "KeyError: 'listener'" in log, log
    assert seen['entry']['state'] == 'crashed', seen['entry']
    assert seen['entry']['exit']['code'] == 1, seen['entry']
    assert seen['processes'] == []


def test_the_demo_workspaces_xml_launch_file_runs_through_the_reader():
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    with ServedPage(demo_build.demo_install()) as served:
        out = _drive(served.url, [{
            'file': 'demo_nodes/launch/talker_listener.launch.xml', 'args': {'topic': 'news'},
            'until': _log_has('listener-', 'I heard'), 'stop': True}])
    assert out['ok'], _explain(out)
    seen = out['checks']['launches'][0]
    assert [f['name'] for f in seen['form']] == ['topic'], seen['form']
    assert seen['form'][0]['placeholder'] == 'chatter'
    labels = sorted(p['label'].rsplit('-', 1)[0] for p in seen['processes'])
    assert labels == ['listener', 'talker'], seen['processes']
    assert all('chatter:=news' in p['args'] for p in seen['processes']), seen['processes']
    assert seen['entry']['state'] == 'stopped', seen['entry']
