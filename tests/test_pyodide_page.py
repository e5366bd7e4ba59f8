# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Python nodes in the launcher page: Pyodide in a Web Worker, on the page's bus.

`colcon-wasm serve --pyodide` serves the npm package `pyodide` (pinned,
tests/js); the page's "Run Python file…" runs a script with the pure-Python
rclpy of wasm_js beside the demo's C++ nodes (tests/demo_build.py) in
headless Chromium (tests/js/page_session.mjs): a Python talker heard by the
C++ listener, the C++ talker heard by a Python listener.
"""

from pathlib import Path
import re
import sys

sys.path.insert(0, str(Path(__file__).resolve().parent))

import demo_build  # noqa: E402, I100, I202
from humble_build import REPO  # noqa: E402

PYODIDE = REPO / 'tests' / 'js' / 'node_modules' / 'pyodide'
SCRIPTS = REPO / 'tests' / 'data' / 'pyodide'
RCLPY = REPO / 'packages' / 'wasm_js' / 'src' / 'python'


def test_the_browser_file_list_names_every_rclpy_module():
    listed = re.findall(r"'(rclpy/[^']+\.py)'", (RCLPY / 'rclpy_files.mjs').read_text())
    on_disk = sorted(p.relative_to(RCLPY).as_posix() for p in (RCLPY / 'rclpy').rglob('*.py'))
    assert listed == on_disk


def test_python_nodes_in_the_page_talk_to_cpp_nodes():
    from served_page import explain_page
    from served_page import ServedPage
    assert (PYODIDE / 'pyodide.asm.wasm').is_file(), f'run npm ci in {PYODIDE.parent.parent}'
    steps = [
        {'start': 'listener', 'pkg': 'demo_nodes', 'exe': 'listener'},
        {'python': 'py_talker', 'file': str(SCRIPTS / 'talker.py')},
        {'wait': 'listener', 'text': 'I heard: [Hello from Python: 3]', 'timeoutMs': 90000},
        {'start': 'talker', 'pkg': 'demo_nodes', 'exe': 'talker'},
        {'python': 'py_listener', 'file': str(SCRIPTS / 'listener.py')},
        {'wait': 'py_listener', 'regex': r'I heard: \[Hello World: \d+\] count=\d+',
         'count': 2, 'timeoutMs': 90000},
        {'stop': 'py_talker'},
        # the arguments field: the script's own (argparse) and ROS ones, as on a command line
        {'python': 'py_args', 'file': str(SCRIPTS / 'args_talker.py'),
         'args': '--count 2 --ros-args -p greeting:="Hi there" -r talk:=news'},
        {'wait': 'py_args', 'text': '/py_args_talker on /news: count=2 greeting=Hi there',
         'timeoutMs': 90000},
    ]
    with ServedPage(demo_build.demo_install(), args=['--pyodide', PYODIDE]) as page:
        result = page.run(steps, timeout_ms=180000)
    assert result['ok'], explain_page(result)
    talked = [line for line in result['logs']['py_talker']
              if 'Publishing: "Hello from Python' in line]
    heard = [int(n) for n in re.findall(r'I heard: \[Hello from Python: (\d+)\]',
                                        '\n'.join(result['logs']['listener']))]
    assert heard and heard == sorted(heard) and len(heard) <= len(talked), (heard, talked)
    pairs = re.findall(r'I heard: \[Hello World: (\d+)\] count=(\d+)',
                       '\n'.join(result['logs']['py_listener']))
    assert pairs and all(a == b for a, b in pairs), result['logs']['py_listener']
    assert result['states']['py_talker'] == 'stopped', result['states']
    # both started from the page's snapshot of a started Pyodide (the first had it made)
    for name in ('py_talker', 'py_listener'):
        assert result['snapshots'][name] is True, (result['snapshots'], result['logs'][name][:3])


def test_the_python_console_publishes_to_a_cpp_listener():
    """Lines typed into the log dock run in the console; a typo gets a traceback, then on."""
    from served_page import explain_page
    from served_page import ServedPage
    steps = [
        {'start': 'listener', 'pkg': 'demo_nodes', 'exe': 'listener'},
        {'pythonConsole': 'console'},
        {'wait': 'console', 'text': 'rclpy is imported', 'timeoutMs': 90000},
        {'type': 'console', 'line': 'from demo_interfaces.msg import Chatter'},
        {'type': 'console', 'line': "node = rclpy.create_node('repl')"},
        {'type': 'console', 'line': "pub = node.create_publisher(Chatter, 'chatter', 10)"},
        {'type': 'console', 'line': 'pub.get_subscription_count()'},
        {'wait': 'console', 'text': '>>> pub.get_subscription_count()'},
        {'type': 'console', 'line': 'undefined_name'},
        {'wait': 'console', 'text': "NameError: name 'undefined_name' is not defined"},
        {'type': 'console', 'line': 'for i in range(3):'},
        {'type': 'console', 'line': "    pub.publish(Chatter(data=f'typed {i}', count=i))"},
        {'type': 'console', 'line': ''},
        {'wait': 'listener', 'text': 'I heard: [typed 2]', 'timeoutMs': 30000},
        {'stop': 'console'},
    ]
    with ServedPage(demo_build.demo_install(), args=['--pyodide', PYODIDE]) as page:
        result = page.run(steps, timeout_ms=180000)
    assert result['ok'], explain_page(result)
    console = result['logs']['console']
    assert '>>> for i in range(3):' in console and \
        "...     pub.publish(Chatter(data=f'typed {i}', count=i))" in console, console
    assert '1' in console, console  # get_subscription_count(): the C++ listener
    heard = re.findall(r'I heard: \[typed (\d)\]', '\n'.join(result['logs']['listener']))
    assert heard == ['0', '1', '2'], result['logs']['listener']


SET_FROM_THE_PAGE = """(async () => {
  const { ParameterClient } = await import('/wasm_js/page/ros_clients.mjs');
  const s = colconWasm.session;
  const client = new ParameterClient(s.toolsBus(), s.registry, '/py_params');
  const names = await client.list();
  if (!names.includes('greeting')) return false;
  const before = await client.get(['greeting', 'rate']);
  const set = await client.set('greeting', 'from the page');
  const refused = await client.set('rate', 0);
  const after = await client.get(['greeting', 'rate']);
  const plain = (k, v) => (typeof v === 'bigint' ? Number(v) : v);
  return JSON.stringify({ names, before, set, refused, after }, plain);
})().catch((e) => JSON.stringify({ error: String(e && e.stack || e) }))"""


def test_parameters_set_from_the_page_reach_a_python_node():
    """The page's parameter client and an rclcpp AsyncParametersClient use its services."""
    from rclcpp_build import rclcpp_build
    from served_page import explain_page
    from served_page import ServedPage
    import json
    steps = [
        {'python': 'params', 'file': str(SCRIPTS / 'params_node.py')},
        {'wait': 'params', 'text': 'READY', 'timeoutMs': 90000},
        {'until': SET_FROM_THE_PAGE, 'save': 'page', 'timeoutMs': 30000},
        {'wait': 'params', 'text': "PARAM greeting now 'from the page'"},
        {'start': 'reader', 'pkg': 'rmw_wasm_cpp_node_tests', 'exe': 'probe',
         'args': ['param_reader', '/py_params', 'greeting']},
        {'wait': 'reader', 'text': 'PARAM greeting=from the page', 'timeoutMs': 30000},
    ]
    with ServedPage(rclcpp_build().install, args=['--pyodide', PYODIDE]) as page:
        result = page.run(steps, timeout_ms=180000)
    assert result['ok'], explain_page(result)
    seen = json.loads(result['saved']['page'])
    assert 'error' not in seen, seen
    # every rclpy node declares use_sim_time
    assert seen['names'] == ['greeting', 'rate', 'use_sim_time'], seen
    assert [(p['name'], p['value']) for p in seen['before']] == [('greeting', 'hello'),
                                                                 ('rate', 5)], seen
    assert seen['set']['successful'] is True, seen
    assert seen['refused'] == {'successful': False, 'reason': 'rate must be > 0'}, seen
    assert [(p['name'], p['value']) for p in seen['after']] == [
        ('greeting', 'from the page'), ('rate', 5)], seen


def test_without_pyodide_the_page_says_how_to_get_it(tmp_path):
    import json
    import os
    from urllib.request import urlopen
    from served_page import ServedPage
    env = {k: v for k, v in os.environ.items() if k != 'COLCON_WASM_PYODIDE'}
    env['COLCON_WASM_CACHE'] = str(tmp_path)
    env['HOME'] = str(tmp_path)
    page = ServedPage(demo_build.demo_install())
    page.env = env
    with page:
        with urlopen(page.url + 'workspace.json', timeout=10) as response:
            python = json.loads(response.read())['python']
        with urlopen(page.url + 'launcher/app.mjs', timeout=10) as response:
            assert response.status == 200
    assert python['pyodide'] is None, python
    assert 'Python nodes need Pyodide' in python['problem'], python
    assert 'npm install --prefix' in python['problem'], python
