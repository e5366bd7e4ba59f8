# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The page's Graph tab (issue 37 item 6): rqt_graph's picture of the bus.

The layout's unit tests (tests/js/test_graph_layout.mjs, node --test), then
the demo workspace's talker and listener in Chromium: the tab draws
/talker -> /chatter -> /listener, "Nodes only" draws one labelled edge, a
double click on the topic opens it in the Topics tab. (The Debug filter's
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
SVG = "document.querySelector('section[data-view=graph] svg.graph')"


def test_graph_layout_units():
    completed = subprocess.run(['node', '--test', str(JS / 'test_graph_layout.mjs')],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stdout[-4000:] + completed.stderr[-2000:]
    assert '# pass 4' in completed.stdout, completed.stdout[-2000:]


def _labels(kind):
    return (f"[...{SVG}.querySelectorAll('.graph-vertex.{kind} text')]"
            '.map((t) => t.textContent).sort().join(",")')


def test_graph_tab_draws_talker_chatter_listener_and_its_filters():
    reason = browser_skip_reason()
    if reason:
        pytest.skip(reason)
    import demo_build
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    demo = {'pkg': 'demo_nodes'}
    with ServedPage(demo_build.demo_install()) as served:
        result = served.run([
            dict(demo, start='talker', exe='talker', args=[]),
            dict(demo, start='listener', exe='listener', args=[]),
            {'wait': 'listener', 'text': 'I heard'},
            {'until': "(document.querySelector('[data-tab=graph]').click(), true)"},
            {'until': f"{SVG} && {_labels('node')} === '/listener,/talker' && {_labels('topic')}",
             'save': 'topics'},
            {'until': f"{SVG}.querySelectorAll('path.graph-edge').length", 'save': 'edges'},
            {'until': "(() => { const t = document.querySelector('[data-tab=graph] .count'); "
                      'return t && t.textContent; })()', 'save': 'count'},
            *({'screenshot': str(SCREENSHOTS / f'graph_{w}.png'), 'width': w}
              for w in (1024, 1440, 2560)),
            {'until': '(() => { const s = ' + SVG + '; const r = s.getBoundingClientRect(); '
                      'return {w: document.documentElement.scrollWidth, '
                      'inner: innerWidth, svg: r.width}; })()', 'save': 'widths'},
            # Nodes only: one edge /talker -> /listener, labelled /chatter
            {'until': "(document.querySelector('[data-option=topics]').click(), true)"},
            {'until': f"{SVG} && {SVG}.querySelectorAll('.graph-vertex.topic').length === 0 "
                      f"&& [...{SVG}.querySelectorAll('.graph-edge-label')]"
                      ".map((t) => t.textContent).join(',')", 'save': 'nodesOnly'},  # noqa: Q000
            # back to topics as boxes
            {'until': "(document.querySelector('[data-option=topics]').click(), true)"},
            {'until': f"{SVG} && {SVG}.querySelectorAll('.graph-vertex.topic').length === 1"},
            # a double click on /chatter opens it in the Topics tab
            {'until': f"(() => {{ const g = [...{SVG}.querySelectorAll('.graph-vertex.topic')]"
                      ".find((v) => v.textContent.endsWith('/chatter')); if (!g) return null; "
                      "g.dispatchEvent(new MouseEvent('dblclick', {bubbles: true})); "
                      'return true; })()'},
            {'until': "!document.querySelector('section[data-view=topics]').hidden && "
                      'colconWasm.views.topics.selected', 'save': 'opened'},
        ], query='#graph')
    assert result['ok'], explain_page(result)
    saved = result['saved']
    # talker -> /chatter -> listener (the demo's nodes publish nothing else but debug topics)
    assert saved['topics'] == '/chatter', saved
    assert saved['edges'] == 2, saved
    assert saved['count'] == '2', saved
    assert saved['nodesOnly'] == '/chatter', saved
    assert saved['opened'] == '/chatter', saved
    widths = saved['widths']
    assert widths['w'] <= widths['inner'] and widths['svg'] > 200, widths
    assert not result['pageErrors'], result['pageErrors']
