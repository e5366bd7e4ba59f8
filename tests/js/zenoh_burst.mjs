// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A burst of large messages from the gateway's zenoh-pico session, for
 * tests/test_zenoh_large.py: opens a session (bridges/zenoh/session.mjs,
 * the install's zenoh_session module) to a router, declares a RELIABLE
 * (congestion control BLOCK) publisher, waits until it matches a
 * subscriber, then puts `count` messages of `size` bytes (each starting
 * with its index, u32 little-endian) in zenoh-pico batches of 50, as the
 * gateway does, and prints {"sent": count, "failed": puts refused}.
 *
 *   node zenoh_burst.mjs '{"endpoint", "module", "key", "size", "count"}'
 */

import { NodeWebSocket } from '../../packages/wasm_js/src/bridges/rosbridge/ws_node.mjs';
import { nodeModuleFactory } from '../../packages/wasm_js/src/bridges/zenoh/launch.mjs';
import { ZenohSession } from '../../packages/wasm_js/src/bridges/zenoh/session.mjs';

const o = JSON.parse(process.argv[2]);
const session = await ZenohSession.open({
  endpoint: o.endpoint, createModule: await nodeModuleFactory(o.module), WebSocket: NodeWebSocket,
  onClosed: (error) => { console.error(`session closed: ${error.message}`); process.exit(3); },
});
let matched = false;
const publisher = session.publisher(o.key, { reliable: true, onMatching: (m) => { matched = m; } });
const deadline = Date.now() + 30000;
while (!matched && Date.now() < deadline) await new Promise((resolve) => setTimeout(resolve, 50));
const payload = new Uint8Array(o.size).fill(0x5a);
let failed = 0;
for (let i = 0; i < o.count; i += 50) {
  session.batch(() => {
    for (let j = i; j < Math.min(o.count, i + 50); j++) {
      new DataView(payload.buffer).setUint32(0, j, true);
      if (publisher.put(payload) !== 0) failed += 1;
    }
  });
  await new Promise((resolve) => setImmediate(resolve));
}
await new Promise((resolve) => setTimeout(resolve, 1000));
console.log(JSON.stringify({ sent: o.count, failed }));
session.close();
process.exit(0);
