# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The Foxglove server's parameters and ROS 2 schemas, with rclcpp nodes.

npm `@foxglove/ws-protocol`'s FoxgloveClient (tests/js/foxglove_client.mjs)
gets, sets and watches the parameters of rmw_wasm_cpp_node_tests' probe
(an rclcpp node of the Humble build, tests/rclcpp_build.py) through its rcl
parameter services and /parameter_events: of `launch --foxglove`, and of
`serve --foxglove` with the probe in a page (headless Chromium). On
127.0.0.1, every wait bounded.
"""

from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
import re
import sys
import textwrap
import time

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from rclcpp_build import rclcpp_build  # noqa: E402, I100, I202
from rosbridge_launch import BackgroundLaunch  # noqa: E402
from rosbridge_launch import node_script  # noqa: E402

URL = re.compile(r'foxglove server listening on (ws://\S+)')


@pytest.fixture(scope='module')
def server(tmp_path_factory):
    """Run the probe's param_talker (an rclcpp node) with a Foxglove server."""
    install = rclcpp_build().install
    path = tmp_path_factory.mktemp('foxglove_rclcpp') / 'params.launch.yaml'
    path.write_text(textwrap.dedent("""
        launch:
        - node: {pkg: rmw_wasm_cpp_node_tests, exec: probe, args: param_talker, name: talker}
    """).lstrip(), encoding='utf-8')
    with BackgroundLaunch(install, '--foxglove', '127.0.0.1:0', path, duration=120,
                          url_pattern=URL) as run:
        run.wait_for('NAME /talker TOPIC /chatter', timeout=90)
        yield run


def _check_params(r, node):
    """Check what the `params` mode of foxglove_client.mjs got of ``node``'s greeting."""
    assert {'parameters', 'parametersSubscribe'} <= set(r['info']['capabilities'])
    assert f'{node}.greeting' in r['all'] and f'{node}.period_ms' in r['all'], r['all']
    assert r['before'] == [{'name': f'{node}.greeting', 'value': 'hello'}]
    assert r['after'] == [{'name': f'{node}.greeting', 'value': 'hi from foxglove'}]
    assert {'name': f'{node}.greeting', 'value': 'hi from foxglove'} in r['updates'], r
    assert not [s for s in r['status'] if s.get('level', 0) >= 1], r['status']
    # Foxglove's decoder read /parameter_events from the advertised rosbag2-style schema
    assert '\nMSG: builtin_interfaces/Time\n' in r['eventsSchema']
    assert '\nMSG: rcl_interfaces/ParameterValue\n' in r['eventsSchema']
    event = next(e for e in r['events'] if e['changed'])
    assert event['node'] == node and event['stamp']['sec'] > 0
    assert event['changed'][0]['name'] == 'greeting'
    assert event['changed'][0]['value']['string_value'] == 'hi from foxglove'


def _check_param_errors(errors, node):
    """Check what the `paramErrors` mode of foxglove_client.mjs got of ``node``."""
    # a node the graph does not have: an error status with the request's id, and the values
    status, values = errors['unknown']['status'], errors['unknown']['values']
    assert status['level'] == 2 and '/nobody_here' in status['message'], status
    assert 'no node /nobody_here' in status['message'], status
    assert values['parameters'] == [], values
    assert "'no_dot_here' is not <node>.<parameter>" in errors['badName']['message']
    assert errors['badName']['level'] == 2
    assert 'is no ROS 2 parameter value' in errors['badValue']['message'], errors['badValue']
    # the node refused a string for an integer parameter: its reason, and the value it kept
    refused = errors['refused']
    assert refused['status']['level'] == 2 and 'period_ms' in refused['status']['message']
    assert refused['values']['parameters'] == [{'name': f'{node}.period_ms',
                                                'value': 100}], refused
    assert "needs 'parameterNames'" in errors['notAList']['message'], errors['notAList']
    # and the connection is still up
    assert [p['name'] for p in errors['stillUp']['parameters']] == [f'{node}.greeting'], errors
    # unsubscribed from greeting: its last change was set, but not sent as an update
    assert errors['setUnwatched']['parameters'] == [{'name': f'{node}.greeting',
                                                     'value': 'not watched'}]
    updates = errors['updates']
    assert {'name': f'{node}.greeting', 'value': 'watched'} in updates, updates
    assert {'name': f'{node}.period_ms', 'value': 250} in updates, updates
    assert not [u for u in updates if u.get('value') == 'not watched'], updates


def test_foxglove_gets_sets_and_watches_an_rclcpp_parameter(server):
    """Check getParameters (one, all), setParameters with an id, and its update."""
    r = node_script('foxglove_client.mjs', 'params', server.url, '/talker', 'greeting',
                    '"hi from foxglove"')
    _check_params(r, '/talker')


def test_foxglove_bad_parameter_requests_and_unsubscribing(server):
    """Each bad parameter request gets an error status with its id; unsubscribed names rest."""
    errors = node_script('foxglove_client.mjs', 'paramErrors', server.url, '/talker', 'greeting',
                         'period_ms')
    _check_param_errors(errors, '/talker')


def test_foxglove_time_from_clock(server):
    """Once /clock is published, clients get the time capability and its TIME messages."""
    r = node_script('foxglove_client.mjs', 'clock', server.url)
    assert 'time' in r['after'], r
    times = [int(t) for t in r['times']]
    assert all(t % 1000000000 == 500 and t // 1000000000 > 1000 for t in times), times
    assert times == sorted(times)


def test_serve_foxglove_time_from_clock(tmp_path):
    """Serve --foxglove: /clock from a relay client or a Foxglove client gives the time."""
    from urllib.parse import urlsplit
    from served_page import ServedPage
    install = rclcpp_build().install
    with ServedPage(install, args=['--foxglove', '127.0.0.1:0']) as served:
        relay = f'ws://{urlsplit(served.url).netloc}/rosbridge'
        # published by a rosbridge client of serve's relay (as a page's node would), then
        # by a Foxglove client (clientPublish)
        results = [node_script('foxglove_client.mjs', 'clock', served.foxglove_url, relay)]
        # the relay's graph forgets the first publisher's /clock (catalog: once a second)
        time.sleep(2.5)
        results.append(node_script('foxglove_client.mjs', 'clock', served.foxglove_url))
    for r in results:
        assert 'time' not in r['before'], r
        assert 'time' in r['after'], r
        times = [int(t) for t in r['times']]
        assert all(t % 1000000000 == 500 and t // 1000000000 > 1000 for t in times), times
        assert times == sorted(times)


def test_serve_foxglove_parameters_of_a_page_node(tmp_path):
    """
    Serve --foxglove: the parameters of an rclcpp node in a page, through the relay.

    The page's rosbridge client advertises the node's parameter services to
    the relay and publishes /parameter_events there; the Foxglove server
    calls the node's services and hears its events. Then bad requests, each
    an error status with its id, and unsubscribing.
    """
    from served_page import explain_page
    from served_page import param_talker_tab
    from served_page import ServedPage
    install = rclcpp_build().install
    # the page runs until the Foxglove clients publish "foxglove is done"
    tab = param_talker_tab('foxglove is done')
    with ServedPage(install, args=['--foxglove', '127.0.0.1:0']) as served:
        with ThreadPoolExecutor(1) as pool:
            page = pool.submit(served.run, tab, 180000)
            try:
                r = node_script('foxglove_client.mjs', 'params', served.foxglove_url,
                                '/param_talker', 'greeting', '"hi from foxglove"',
                                '/probe_listener', timeout=90)
                errors = node_script('foxglove_client.mjs', 'paramErrors',
                                     served.foxglove_url, '/param_talker', 'greeting',
                                     'period_ms', timeout=90)
            finally:
                node_script('foxglove_client.mjs', 'publish', served.foxglove_url, '/chatter',
                            'std_msgs/msg/String', '{"data": "foxglove is done"}', timeout=30)
            result = page.result(timeout=300)
    assert result['ok'], explain_page(result)
    _check_params(r, '/param_talker')
    assert '/probe_listener.use_sim_time' in r['all'], r['all']
    _check_param_errors(errors, '/param_talker')
