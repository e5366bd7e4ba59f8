# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's Graph tab (issue 37 item 6): rqt_graph's picture of the bus.

The layout's unit tests (tests/js/test_graph_layout.mjs, node --test), then
the demo workspace's talker and listener in Chromium: the tab draws
/talker -> /chatter -> /listener, "Nodes only" draws one labelled edge, a
double click on the topic opens it in the Topics tab; the Parameters tab
counts only nodes with parameter services (issue 37's "Parameters 5" for
nodes that have none). (The Debug filter's
topics, /rosout and /parameter_events, come from rclcpp nodes, which the
demo's are not: the unit tests cover it.) Screenshots at
1024, 1440 and 2560 px go to artifacts/screenshots/graph/.
"""

import subprocess

from humble_build import REPO
import pytest
from served_page import browser_skip_reason
from served_page import explain_page
from served_page import JS
from served_page import ServedPage

SCREENSHOTS = REPO / 'artifacts' / 'screenshots' / 'graph'


def test_graph_layout_units():
    completed = subprocess.run(['node', '--test', str(JS / 'test_graph_layout.mjs')],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stdout[-4000:] + completed.stderr[-2000:]
    assert '# pass 5' in completed.stdout, completed.stdout[-2000:]


def test_graph_tab_draws_talker_chatter_listener_and_its_filters():
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    demo = {'pkg': 'demo_nodes'}
    probe = (JS / 'graph_probe.js').read_text()
    with ServedPage(demo_build.demo_install()) as served:
        result = served.run([
            dict(demo, start='talker', exe='talker', args=[]),
            dict(demo, start='listener', exe='listener', args=[]),
            dict(demo, start='robot_talker', exe='talker',
                 args=['--ros-args', '-r', '__ns:=/robot1']),
            {'wait': 'listener', 'text': 'I heard'},
            {'until': probe},
            {'until': '(document.querySelector("[data-tab=graph]").click(), true)'},
            {'until': 'graphProbe.labels("node") === "/listener,/robot1/talker,/talker" '
                      '&& graphProbe.labels("topic")', 'save': 'topics'},
            # the namespace /robot1 is framed, its talker and topic inside
            {'until': 'graphProbe.group()', 'save': 'group'},
            # a click shows the talker in the inspector
            {'until': 'graphProbe.press("n:/talker")'},
            {'until': 'graphProbe.inspector()', 'save': 'inspector'},
            {'until': 'graphProbe.edges() === 3 && 3', 'save': 'edges'},
            {'until': '(() => { const t = document.querySelector("[data-tab=graph] .count"); '
                      'return t && t.textContent; })()', 'save': 'count'},
            # the demo's nodes have no parameter services: the Parameters tab counts none
            {'until': 'document.querySelector("[data-tab=parameters] .count").textContent',
             'save': 'parameterNodes'},
            *({'screenshot': str(SCREENSHOTS / f'graph_{w}.png'), 'width': w}
              for w in (1024, 1440, 2560)),
            {'until': 'graphProbe.widths()', 'save': 'widths'},
            # Nodes only: one edge /talker -> /listener, labelled /chatter
            {'until': 'graphProbe.option("topics")'},
            {'until': 'graphProbe.labels("topic") === "" && graphProbe.edgeLabels()',
             'save': 'nodesOnly'},
            # back to topics as boxes
            {'until': 'graphProbe.option("topics")'},
            {'until': 'graphProbe.labels("topic") === "/chatter,/robot1/chatter"'},
            # the listener stops: it leaves the graph, with its edge
            {'stop': 'listener'},
            {'until': 'graphProbe.labels("node") === "/robot1/talker,/talker" '
                      '&& graphProbe.edges()', 'save': 'edgesAfterStop'},
            # a double click on /chatter opens it in the Topics tab
            {'until': 'graphProbe.press("t:/chatter", "dblclick")'},
            {'until': '!document.querySelector("section[data-view=topics]").hidden && '
                      'colconWasm.views.topics.selected', 'save': 'opened'},
        ], query='#graph')
    assert result['ok'], explain_page(result)
    saved = result['saved']
    # talker -> /chatter -> listener (the demo's nodes publish nothing else but debug topics)
    assert saved['topics'] == '/chatter,/robot1/chatter', saved
    assert saved['edges'] == 3, saved
    assert saved['count'] == '3', saved
    assert saved['parameterNodes'] == '0', saved
    assert saved['group'] == {'name': '/robot1',
                              'inside': ['n:/robot1/talker', 't:/robot1/chatter']}, saved
    assert 'publishes (1)/chatter' in saved['inspector'], saved
    assert saved['edgesAfterStop'] == 2, saved
    assert saved['nodesOnly'] == '/chatter', saved  # the /robot1 talker has no listener
    assert saved['opened'] == '/chatter', saved
    widths = saved['widths']
    assert widths['w'] <= widths['inner'] and widths['svg'] > 200, widths
    assert not result['pageErrors'], result['pageErrors']
