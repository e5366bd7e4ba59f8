// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The tools process (packages/wasm_js/src/tools_process/) and TRANSIENT_LOCAL:
// a subscription that joins after a latched publisher published gets the
// writer's history in its first batch (the bridges' taps of /tf_static,
// /robot_description, the page's echo). Run by tests/test_tools_history.py
// with `node --test`.

import assert from 'node:assert/strict';
import { test } from 'node:test';

import { Runtime } from '../../packages/wasm_js/src/runtime.mjs';

const TYPE = 'demo_interfaces/msg/Chatter';
const LATCHED = { history: 'keep_last', depth: 2, reliability: 'reliable', durability: 'transient_local' };

function chatter(count) {
  return new Uint8Array([0, 1, 0, 0, 3, 0, 0, 0, 104, 105, 0, 0, count, 0, 0, 0]);
}

function until(predicate, ms) {
  return new Promise((resolve, reject) => {
    const start = Date.now();
    const tick = () => {
      if (predicate()) resolve();
      else if (Date.now() - start > ms) reject(new Error(`not within ${ms} ms`));
      else setTimeout(tick, 10);
    };
    tick();
  });
}

test('a late TRANSIENT_LOCAL subscription of the tools process gets the history', async () => {
  const runtime = await Runtime.create({});
  try {
    const tools = await runtime.tools();
    const pub = await tools.advertise({ topic: '/latched', type: TYPE, qos: LATCHED });
    for (const n of [1, 2, 3]) await pub.publish(chatter(n));
    const got = [];
    const sub = await tools.subscribe({ topic: '/latched', type: TYPE, qos: LATCHED }, (batch) => got.push(...batch));
    await until(() => got.length >= 2, 5000);
    // the writer keeps its depth (2): the last two, in order
    assert.deepEqual(got.map((m) => m.data[12]), [2, 3]);
    const volatile = [];
    const late = await tools.subscribe({ topic: '/latched', type: TYPE, qos: { ...LATCHED, durability: 'volatile' } },
      (batch) => volatile.push(...batch));
    await pub.publish(chatter(4));
    await until(() => volatile.length >= 1 && got.length >= 3, 5000);
    assert.deepEqual(volatile.map((m) => m.data[12]), [4]); // a volatile one: nothing of the past
    await sub.close();
    await late.close();
  } finally {
    await runtime.close();
  }
});
