# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
TRANSIENT_LOCAL across the Zenoh gateway, with real Humble packages.

tf2_ros' static_transform_publisher latches /tf_static (TRANSIENT_LOCAL,
depth 1) and tf2_echo subscribes to it; the other side is a Zenoh peer
(tests/zenoh_peers.py) with zenoh.ext's advanced publisher or subscriber,
declared as rmw_zenoh declares them for TRANSIENT_LOCAL. Each side joins
after the other published: only the caches carry the transform. zenoh-pico
(from the corpus) and the gateway are built as an overlay of the cached
corpus build (tests/corpus_build.py), cached the same way.
"""

import re
import time

from corpus_build import corpus_build
from humble_build import humble_build
import pytest
from rosbridge_launch import BackgroundLaunch
from test_zenoh_gateway import CONNECTED
import zenoh_peers
from zenoh_peers import RmwZenohPeer
from zenoh_peers import ZenohRouter

TF_MESSAGE = 'tf2_msgs/msg/TFMessage'
STATIC_ARGS = ('--x', '1', '--y', '2', '--z', '3', '--yaw', '0.5', '--frame-id', 'world',
               '--child-frame-id', 'robot')


@pytest.fixture(scope='module')
def install():
    """Build zenoh-pico and the gateway on the corpus build (tf2_ros)."""
    pytest.importorskip('zenoh', reason='eclipse-zenoh is missing: pip install -e .[test]')
    build = humble_build(up_to=('zenoh_pico', 'zenoh_wasm_gateway'), skip=(), extra={},
                         corpus=('eclipse-zenoh/zenoh-pico',), underlay=corpus_build(),
                         snapshot=False)
    return build.install


@pytest.fixture
def router():
    """Run a router with tcp and ws listeners on loopback."""
    with ZenohRouter() as r:
        yield r


def _typestore():
    from rosbags.typesys import get_typestore
    from rosbags.typesys import Stores
    return get_typestore(Stores.ROS2_HUMBLE)


def _static_transform_cdr():
    store = _typestore()
    t = store.types
    message = t['tf2_msgs/msg/TFMessage'](transforms=[t['geometry_msgs/msg/TransformStamped'](
        header=t['std_msgs/msg/Header'](stamp=t['builtin_interfaces/msg/Time'](sec=5, nanosec=0),
                                        frame_id='world'),
        child_frame_id='robot', transform=t['geometry_msgs/msg/Transform'](
            translation=t['geometry_msgs/msg/Vector3'](x=1.0, y=2.0, z=3.0),
            rotation=t['geometry_msgs/msg/Quaternion'](x=0.0, y=0.0, z=0.24740395925452294,
                                                       w=0.9689124217106447)))])
    return bytes(store.serialize_cdr(message, TF_MESSAGE))


def test_a_latched_transform_reaches_a_late_zenoh_subscriber(install, router):
    run = BackgroundLaunch(install, '--zenoh', router.tcp, duration=60, wait_url=False,
                           command='run',
                           after=('tf2_ros', 'static_transform_publisher', *STATIC_ARGS))
    with run:
        run.wait_for(CONNECTED, timeout=60)
        run.wait_for("from 'world' to 'robot'", timeout=60)
        time.sleep(1.0)  # the one publication is over: only the gateway's cache has it
        peer = RmwZenohPeer(router.tcp)
        key = zenoh_peers.data_key('/tf_static', TF_MESSAGE)
        try:
            peer.listen_transient_local(key, 1)
            deadline = time.monotonic() + 20
            while not peer.samples(key) and time.monotonic() < deadline:
                time.sleep(0.2)
            samples = peer.samples(key)
            tokens = [t for t in peer.tokens() if '%tf_static' in t]
        finally:
            peer.close()
    assert samples, f'no /tf_static sample from the cache; output:\n{run.output()[-3000:]}'
    message = _typestore().deserialize_cdr(samples[0][1], TF_MESSAGE)
    (transform,) = message.transforms
    assert (transform.header.frame_id, transform.child_frame_id) == ('world', 'robot')
    assert (transform.transform.translation.x, transform.transform.translation.z) == (1.0, 3.0)
    assert zenoh_peers.parse_attachment(samples[0][2])[0] == 1
    # the publisher's token says TRANSIENT_LOCAL, depth 1 (rmw_zenoh's QoS text)
    assert any(t.endswith('/tf2_msgs::msg::dds_::TFMessage_/TypeHashNotSupported/:1:,1:,:,:,,')
               for t in tokens), tokens


def test_a_latched_zenoh_transform_reaches_a_late_tf2_echo(install, router):
    peer = RmwZenohPeer(router.tcp)
    try:
        node = peer.announce_node('py_static_broadcaster')
        publish = peer.advertise('py_static_broadcaster', node, '/tf_static', TF_MESSAGE,
                                 transient_local_depth=1)
        publish(_static_transform_cdr())
        time.sleep(1.0)
        run = BackgroundLaunch(install, '--zenoh', router.tcp, duration=60, wait_url=False,
                               command='run', after=('tf2_ros', 'tf2_echo', 'world', 'robot'))
        with run:
            run.wait_for(CONNECTED, timeout=60)
            run.wait_for(re.compile(r'- Translation: \[1\.000, 2\.000, 3\.000\]'), timeout=60)
            run.wait_for(re.compile(r'- Rotation: in RPY \(radian\) \[0\.000, -0\.000, 0\.500\]'),
                         timeout=20)
    finally:
        peer.close()


def test_an_action_goal_feedback_and_result_cross_the_router(install, router):
    """Run rclcpp's minimal action server and client, each in its own launch, via the router."""
    server = BackgroundLaunch(install, '--zenoh', router.tcp, duration=90, wait_url=False,
                              command='run',
                              after=('examples_rclcpp_minimal_action_server',
                                     'action_server_not_composable'))
    with server:
        server.wait_for(CONNECTED, timeout=60)
        client = BackgroundLaunch(install, '--zenoh', router.tcp, duration=90, wait_url=False,
                                  command='run',
                                  after=('examples_rclcpp_minimal_action_client',
                                         'action_client_not_composable_with_feedback'))
        with client:
            client.wait_for(CONNECTED, timeout=60)
            client.wait_for(re.compile(r'Next number in sequence received: \d+'), timeout=60)
            client.wait_for('result received', timeout=60)
        server.wait_for('Goal Succeeded', timeout=30)
