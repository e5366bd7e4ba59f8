# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
The core without pthreads (`colcon build --wasm --wasm-no-pthread`).

The same test nodes, built without threads: messages, services and waits
work the same; new-data callbacks, which need a listener thread, say so.
"""

from core import harness
import pytest

UNSUPPORTED = '3'


@pytest.fixture(scope='module')
def nopthread():
    return harness.build(colcon_args=['--wasm-no-pthread'])


def test_no_pthread_build_has_no_worker_script(nopthread):
    assert nopthread.core_node.is_file()
    assert not (nopthread.bin / 'core_node.worker.js').exists()


@pytest.mark.parametrize('scenario', ['lossless', 'services', 'wait'])
def test_no_pthread_delivery_services_and_waits(nopthread, scenario):
    run = harness.run_node(nopthread, scenario)
    assert run['ok'], harness.explain(run)
    for name, proc in run['processes'].items():
        assert proc['exit']['code'] in (0, None), (name, harness.explain(run))
    if scenario == 'lossless':
        sub = harness.results(run, 'sub')
        assert (sub['received'], sub['out_of_order']) == ('100000', '0')


@pytest.fixture(scope='module')
def nopthread_browser(nopthread):
    reason = harness.browser_skip_reason()
    if reason:
        pytest.skip(reason)
    browser = harness.Browser(
        [('/wasm_js/', nopthread.share), ('/nodes/', nopthread.bin),
         ('/core/', harness.HERE)], plain=[('/plain/', harness.HERE)])
    yield browser
    browser.close()


def test_no_pthread_build_runs_in_chromium_without_failed_loads(
        nopthread_browser):
    # The Runtime prefetches an executable's scripts; a build without
    # threads has no .worker.js, and the page must not ask for one.
    run = nopthread_browser.run('services')
    assert run['ok'], harness.explain(run)
    for name, proc in run['processes'].items():
        assert proc['exit']['code'] in (0, None), (name, harness.explain(run))
    failed = [line for line in run['console']
              if 'Failed to load resource' in line or 'pageerror' in line]
    assert failed == [], harness.explain(run)


def test_no_pthread_node_whose_main_traps_is_reported_crashed(
        nopthread, nopthread_browser):
    # Without threads main() runs straight from the module's instantiation.
    harness.assert_trap_reported(harness.run_node(nopthread, 'trap'))
    harness.assert_trap_reported(nopthread_browser.run('trap'))


def test_no_pthread_callbacks_are_unsupported_with_a_reason(nopthread):
    run = harness.run_node(nopthread, 'callbacks')
    r = harness.results(run, 'callbacks')
    assert r['callbacks_supported'] == '0', harness.explain(run)
    assert r['code'] == UNSUPPORTED
    message = run['processes']['callbacks']['messages'][0]
    assert 'need a listener thread: build with pthreads' in message, message
    assert '--wasm-no-pthread' in message
