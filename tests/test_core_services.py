# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""Services with real request ids (issue 4), in Node.js and Chromium."""

from core import harness
import pytest


@pytest.mark.parametrize('platform', ['node', 'chromium'])
def test_50_concurrent_requests_from_5_clients_get_their_own_responses(
        platform):
    run = harness.run(platform, 'services')
    why = harness.explain(run)
    assert harness.results(run, 'server')['served'] == '50', why
    for i in range(1, 6):
        client = harness.results(run, f'client{i}')
        # Each client checks the echoed index, its own tag, its own gid in
        # the request id and the echoed sequence number of every response.
        assert client == {
            'responses_ok': '10', 'wrong': '0', 'missing': '0'}, why
