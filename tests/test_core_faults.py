# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""A node's worker dies; the graph heals and the others go on (issue 4)."""

from core import harness
import pytest

PLATFORMS = ['node', 'chromium']


@pytest.mark.parametrize('platform', PLATFORMS)
def test_worker_killed_mid_stream_graph_updated_others_continue(platform):
    run = harness.run(platform, 'kill')
    why = harness.explain(run)
    survivor = harness.results(run, 'survivor')
    assert run['extra']['graph_before'] == ['other', 'survivor', 'victim']
    assert run['extra']['graph_after'] == ['other', 'survivor'], why
    assert survivor['publisher_gone'] == '1' and survivor['publishers'] == '1'
    # 2000 more messages from the other publisher after the kill.
    assert int(survivor['continued']) >= 2000, why
    # The reader saw the writer's liveliness go (alive count dropped by one).
    assert survivor['liveliness_drop'] == '1', why
    assert survivor['nodes'] == 'other,survivor', why
    assert harness.exit_of(run, 'victim')['reason'] == 'stopped'


@pytest.mark.parametrize('platform', PLATFORMS)
def test_crashing_node_reported_with_reason_others_continue(platform):
    run = harness.run(platform, 'crash')
    why = harness.explain(run)
    victim = harness.exit_of(run, 'victim')
    assert victim['crashed'] and victim['code'] != 0, why
    # "aborted: ..." (from the abort hook) or "uncaught error: Aborted(...)"
    # (the worker's error event), whichever reaches the runtime first.
    assert 'abort' in victim['reason'].lower(), why
    assert run['extra']['graph_after'] == ['other', 'survivor'], why
    assert int(harness.results(run, 'survivor')['continued']) >= 2000, why


@pytest.mark.parametrize('platform', PLATFORMS)
def test_node_whose_main_traps_is_reported_crashed(platform):
    # A trap has no abort hook: only the error it throws out of main() tells.
    harness.assert_trap_reported(harness.run(platform, 'trap'))


@pytest.mark.parametrize('platform', PLATFORMS)
def test_keep_all_writer_blocked_by_a_reader_that_dies_goes_on(platform):
    run = harness.run(platform, 'blocked_writer')
    why = harness.explain(run)
    # The reader never takes: the RELIABLE KEEP_ALL writer blocks once its
    # 16-slot history is full instead of dropping...
    assert run['extra']['writer_blocked'], why
    # ...and finishes as soon as the reader's worker is gone.
    writer = harness.results(run, 'writer')
    assert writer['published'] == '200', why
    assert run['extra']['unblocked_ms'] < 5000, why
