# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Wait sets, guard conditions, callbacks and lazy deadline/liveliness events."""

from core import harness
import pytest

PLATFORMS = ['node', 'chromium']


@pytest.mark.parametrize('platform', PLATFORMS)
def test_wait_is_woken_by_a_publish_and_a_timed_wait_times_out_on_time(
        platform):
    run = harness.run(platform, 'wait')
    waiter = harness.results(run, 'waiter')
    why = harness.explain(run)
    assert waiter['timed_out'] == '1', why
    # 200 ms asked: never early (Atomics.wait's own timeout, no polling loop
    # behind it); the upper bound leaves room for a loaded CI machine.
    assert 199.5 <= float(waiter['timed_wait_ms']) < 1000, why
    assert waiter['woken'] == '1' and waiter['taken'] == '1', why


@pytest.mark.parametrize('platform', PLATFORMS)
def test_a_thread_logging_while_main_waits_does_not_deadlock(platform):
    # A pthread's printf is proxied to the main thread, which sleeps in the
    # wait: the proxy rings the doorbell and the wait runs the call.
    run = harness.run(platform, 'threads')
    threads = harness.results(run, 'threads')
    assert threads['guard_ready'] == '1', harness.explain(run)
    assert float(threads['ms']) < 2000, harness.explain(run)
    lines = run['processes']['threads']['lines']
    assert sum('thread line' in line for line in lines) == 50


@pytest.mark.parametrize('platform', PLATFORMS)
def test_new_message_callbacks_count_arrivals_without_taking(platform):
    run = harness.run(platform, 'callbacks')
    cb = harness.results(run, 'callbacks')
    assert cb['callbacks_supported'] == '1', harness.explain(run)
    # 3 messages before the callback was set, 5 after: 8 reported, none taken.
    assert cb['events'] == '8', harness.explain(run)
    assert cb['still_takeable'] == '8'


@pytest.mark.parametrize('platform', PLATFORMS)
def test_deadline_and_liveliness_events_without_timers(platform):
    run = harness.run(platform, 'deadline')
    d = harness.results(run, 'deadline')
    why = harness.explain(run)
    # One message, then silence: the wait wakes by itself at the 50 ms
    # deadline (its timeout is cut to the next expiry). The deadline counts
    # from the publish, the wait's own time from after it (under load the
    # wait starts milliseconds later): the lower bound is on the time since
    # the publish, the upper on the wait.
    assert 49 <= float(d['taken_ms']), why
    assert float(d['first_event_ms']) < 1000, why
    # One missed period per 50 ms of silence (more if the machine was slow
    # to run the wait after it woke).
    periods = int(float(d['taken_ms']) // 50)
    assert 1 <= int(d['offered']) <= periods, why
    assert 1 <= int(d['requested']) <= periods, why
    # MANUAL_BY_TOPIC with a 50 ms lease, not asserted since: lost.
    assert d['liveliness_lost'] == '1', why
    assert (d['alive'], d['not_alive']) == ('0', '1'), why
    assert d['after_assert_alive'] == '1', why
