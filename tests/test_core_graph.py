# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Graph queries from C++ and JS, and the JS tools worker (issue 4)."""

from core import harness
import pytest

PLATFORMS = ['node', 'chromium']
NODE_NAME_NON_EXISTENT = '203'


@pytest.mark.parametrize('platform', PLATFORMS)
def test_graph_queries_nodes_topics_services_endpoints(platform):
    run = harness.run(platform, 'graph')
    why = harness.explain(run)
    g = harness.results(run, 'grapher')
    assert g['nodes'] == '/grapher,/peer', why
    assert g['topics'].startswith('/graph/topic=test_msgs/msg/Bytes'), why
    assert g['services'] == '/graph/srv=test_msgs/srv/Echo', why
    assert g['pub_count'] == '2' and g['pub_depth'] == '7', why
    assert g['sub_count'] == '0', why
    assert g['missing_code'] == NODE_NAME_NON_EXISTENT, why
    assert g['by_node'] == '/graph/srv', why
    peer = harness.results(run, 'peer')
    assert peer['pub_gid_ok'] == '1', why
    # Two nodes with one name: both exist, the second one is warned.
    dup2 = run['processes']['dup2']['lines']
    assert any("WARN node name '/twin' is already in use" in line
               for line in dup2), why
    assert harness.results(run, 'dup2')['nodes'] == '/twin,/twin', why


@pytest.mark.parametrize('platform', PLATFORMS)
def test_runtime_graph_snapshot_and_change_notifications(platform):
    run = harness.run(platform, 'runtime_graph')
    snap = run['extra']['snapshot']
    assert snap['nodes'] == ['/|peer|peer'], harness.explain(run)
    assert '/graph/topic|test_msgs/msg/Bytes|1|0' in snap['topics']
    assert snap['services'] == ['/graph/srv|test_msgs/srv/Echo|1|0']
    assert snap['qos']['depth'] == 7
    assert snap['qos']['reliability'] == 'reliable'
    changes = run['extra']['changes']
    assert any('peer' in nodes for nodes in changes)
    assert 'peer' not in changes[-1]
    assert 'peer' not in run['extra']['final_nodes']


@pytest.mark.parametrize('platform', PLATFORMS)
def test_js_tools_worker_echoes_publishes_and_calls_services(platform):
    run = harness.run(platform, 'tools')
    why = harness.explain(run)
    assert run['extra']['echo_total'] == 500, why
    # Batched: far fewer postMessages than messages.
    assert run['extra']['echo_batches'] < 500, why
    sub = harness.results(run, 'sub')
    assert sub['received'] == '20' and sub['out_of_order'] == '0', why
    assert run['extra']['responses'] == [
        {'index': 100 + i, 'tag': 9, 'len': 36} for i in range(3)], why
