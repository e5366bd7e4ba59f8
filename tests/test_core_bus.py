# Copyright 2026 colcon-wasm contributors
# Licensed under the Apache License, Version 2.0

"""
Unit checks of the bus internals in JavaScript (tests/core/bus_unit.mjs).

They need no build: several BusClients on one SharedArrayBuffer stand for
several processes, and the checks exercise what is hard to reach from C++:
a process dying while it holds the registry lock, zombie rings, buffer
growth, block quarantine, the QoS rules table and the limits' errors.
"""

from pathlib import Path
import subprocess

import pytest

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / 'packages' / 'wasm_js' / 'src'

CHECKS = [
    'lock_stolen_from_dead_owner',
    'async_lockers_all_proceed',
    'killed_mid_mutation_leaves_nothing_half_visible',
    'zombie_ring_is_drained_then_freed',
    'dying_writer_is_still_read',
    'bus_grows_for_large_messages',
    'stale_views_after_another_thread_grew_the_bus',
    'large_copies_keep_every_byte',
    'freed_blocks_wait_before_reuse',
    'qos_compatibility_rules',
    'limits_give_clear_errors',
    'request_ids_route_responses',
    'lifespan_expired_messages_are_skipped',
    'best_effort_overrun_counts_lost',
    'keep_all_blocks_then_times_out',
    'blocked_writer_goes_on_when_its_reader_stops_mid_batch',
]


@pytest.mark.parametrize('check', CHECKS)
def test_bus_unit(check):
    done = subprocess.run(
        ['node', str(HERE / 'core' / 'bus_unit.mjs'), str(SRC), check],
        capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.strip() == 'ok'
