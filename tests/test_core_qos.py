# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""QoS matching, domains, and bad input (issue 4)."""

from core import harness
import pytest

PLATFORMS = ['node', 'chromium']
RELIABILITY = '16'  # rmw_qos_policy_kind_t RMW_QOS_POLICY_RELIABILITY
BAD_ALLOC = '10'
INVALID_ARGUMENT = '11'


@pytest.mark.parametrize('platform', PLATFORMS)
def test_incompatible_qos_pair_does_not_match_and_both_sides_get_events(
        platform):
    run = harness.run(platform, 'incompatible')
    why = harness.explain(run)
    for side in ('pub', 'sub'):
        r = harness.results(run, side)
        assert r['event_ready'] == '1', why
        assert (r['total'], r['change'], r['policy']) == (
            '1', '1', RELIABILITY), why
        assert r['matched'] == '0', why


@pytest.mark.parametrize('platform', PLATFORMS)
def test_separate_domains_never_see_each_other(platform):
    run = harness.run(platform, 'domains')
    sub = harness.results(run, 'sub')
    assert sub['received'] == '0' and sub['publishers'] == '0', (
        harness.explain(run))
    assert harness.results(run, 'pub')['matched'] == '0'
    assert 'pub@8' in run['extra']['domains']


@pytest.mark.parametrize('platform', PLATFORMS)
def test_oversized_and_malformed_input_get_clear_errors(platform):
    run = harness.run(platform, 'errors')
    r = harness.results(run, 'errors')
    why = harness.explain(run)
    assert r['oversized_code'] == BAD_ALLOC, why
    for key in ('null_code', 'bad_topic_code', 'bad_type_code',
                'bad_node_code', 'bad_qos_code'):
        assert r[key] == INVALID_ARGUMENT, (key, why)
    messages = '\n'.join(run['processes']['errors']['messages'])
    assert 'exceeds the bus maximum of 4194304 bytes' in messages
    assert 'maxMessageBytes' in messages
    assert 'invalid topic name "no slash/x"' in messages
    assert 'invalid node name "1bad-name"' in messages
    assert 'unknown reliability policy 42' in messages
    # The bus is not corrupted: a normal message and one of exactly the
    # maximum size still go through.
    assert (r['after_errors_ok'], r['max_ok']) == ('1', '1'), why
    js = run['extra']['js_errors']
    assert 'must be a Uint8Array, got string' in js['string_payload']['message']
    assert js['string_payload']['code'] == int(INVALID_ARGUMENT)
    assert 'invalid topic name "bad topic"' in js['bad_topic']['message']
    assert 'invalid QoS reliability "sometimes"' in js['bad_qos']['message']
    assert js['oversized']['code'] == int(BAD_ALLOC)
    assert run['extra']['js_roundtrip'] == [[1, 2, 3]]
