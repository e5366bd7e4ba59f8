# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
roslibpy (PyPI, a third-party rosbridge client) against a rosbridge server.

    python rosbridge_roslibpy.py PORT

prints one JSON line with what it saw (tests/test_rosbridge_server.py
asserts it). Its own process, as roslibpy's twisted reactor runs once per
process.
"""

import json
import sys
import time

import roslibpy


def main(port):
    """Subscribe, publish, call a service (int64), read the graph, get and set a parameter."""
    ros = roslibpy.Ros(host='127.0.0.1', port=port)
    ros.run(timeout=10)
    out = {'connected': ros.is_connected}
    heard = []
    chatter = roslibpy.Topic(ros, '/chatter', 'std_msgs/msg/String')
    chatter.subscribe(lambda m: heard.append(m['data']))
    add = roslibpy.Service(ros, '/add', 'example_interfaces/srv/AddTwoInts')
    out['sum'] = add.call(roslibpy.ServiceRequest({'a': 2 ** 62, 'b': 7}), timeout=10)['sum']
    publisher = roslibpy.Topic(ros, '/chatter', 'std_msgs/msg/String')
    for i in range(10):
        publisher.publish(roslibpy.Message({'data': f'from roslibpy {i}'}))
        time.sleep(0.05)
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and not any(h.startswith('hello') for h in heard):
        time.sleep(0.1)
    out['heard'] = heard
    out['topics'] = ros.get_topics()
    out['nodes'] = ros.get_nodes()
    out['type'] = ros.get_topic_type('/chatter')
    # the parameters of the C++ talker (rosapi's parameter services; /talker:period_ms)
    out['params'] = ros.get_params()
    period = roslibpy.Param(ros, '/talker:period_ms')
    out['period'] = period.get(timeout=10)
    period.set(300, timeout=10)
    out['period_set'] = period.get(timeout=10)
    ros.terminate()
    return out


if __name__ == '__main__':
    print(json.dumps(main(int(sys.argv[1]))), flush=True)
