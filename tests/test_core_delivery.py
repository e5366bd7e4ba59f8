# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Delivery semantics of the middleware core (issue 4).

Each test runs a scenario of tests/core/scenarios.mjs with real test nodes
(tests/core/nodes, built by the real `colcon build --wasm` and Emscripten),
once in Node.js worker_threads and once in headless Chromium on a page
served with COOP/COEP. Payloads carry their index, origin and a byte
pattern, so the receivers check order and content themselves.
"""

from core import harness
import pytest

PLATFORMS = ['node', 'chromium']


def _assert_all_delivered(run, count):
    """Check that 'sub' got all `count` messages intact, in order, and both exited 0."""
    sub = harness.results(run, 'sub')
    why = harness.explain(run)
    assert sub.get('received') == str(count), why
    assert (sub['bad'], sub['out_of_order'], sub['lost']) == ('0', '0', '0'), why
    assert 'timeout' not in sub, why
    assert harness.exit_of(run, 'pub')['code'] == 0, why
    assert harness.exit_of(run, 'sub')['code'] == 0, why


@pytest.mark.parametrize('platform', PLATFORMS)
def test_100000_messages_arrive_lossless_and_in_order(platform):
    _assert_all_delivered(harness.run(platform, 'lossless'), 100000)


@pytest.mark.parametrize('platform', PLATFORMS)
def test_messages_of_changing_sizes_arrive_intact_in_a_reused_buffer(platform):
    _assert_all_delivered(harness.run(platform, 'varying_sizes'), 600)


@pytest.mark.parametrize('platform', PLATFORMS)
def test_large_messages_grow_the_bus_and_arrive_intact(platform):
    run = harness.run(platform, 'large_messages')
    _assert_all_delivered(run, 12)
    bus = run['extra']['bus']
    assert bus['bytes_after'] > bus['bytes_before'], harness.explain(run)
    # Where the bus is a WebAssembly.Memory, both executables copied with
    # memory.copy; else with TypedArray.set().
    assert run['extra']['memory_copy'] == {'pub': bus['memory'], 'sub': bus['memory']}
    if platform == 'chromium':
        # Chromium has multi-memory: the bus is a shared WebAssembly.Memory.
        assert bus['memory'], harness.explain(run)


@pytest.mark.parametrize('platform', PLATFORMS)
def test_one_publisher_fans_out_to_four_subscribers(platform):
    run = harness.run(platform, 'fanout')
    assert harness.results(run, 'pub')['matched'] == '4', harness.explain(run)
    for name in ('s1', 's2', 's3', 's4'):
        sub = harness.results(run, name)
        assert sub['received'] == '2000', harness.explain(run)
        assert (sub['bad'], sub['out_of_order']) == ('0', '0'), harness.explain(run)


@pytest.mark.parametrize('platform', PLATFORMS)
def test_slow_keep_last_5_reader_receives_the_newest_5(platform):
    run = harness.run(platform, 'keep_last')
    sub = harness.results(run, 'sub')
    # The publisher sent 0..19 before the reader looked; KEEP_LAST(5) keeps 15..19.
    assert sub['indices'] == '15,16,17,18,19', harness.explain(run)
    assert sub['received'] == '5'
    # A RELIABLE reader's own history replacing samples is not "lost".
    assert sub['lost'] == '0'


@pytest.mark.parametrize('platform', PLATFORMS)
def test_transient_local_late_joiner_receives_the_history(platform):
    run = harness.run(platform, 'transient_local')
    late = harness.results(run, 'late')
    # The publisher (TRANSIENT_LOCAL, depth 5) sent 0..9 before the reader existed.
    assert late['indices'] == '5,6,7,8,9', harness.explain(run)
    # A VOLATILE reader that joins late gets nothing of the past.
    volatile = harness.results(run, 'volatile')
    assert volatile['received'] == '0', harness.explain(run)
    assert volatile['timeout'] == '1'
