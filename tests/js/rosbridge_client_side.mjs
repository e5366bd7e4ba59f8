// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A Runtime with the rosbridge client (bridges/rosbridge/client.mjs) and a
 * JS publisher of RELIABLE KEEP_ALL std_msgs/String "seq N" on /chatter at
 * 50 Hz, for the reconnection test (tests/test_rosbridge_client.py):
 *
 *   node rosbridge_client_side.mjs URL RUNTIME_DIR SECONDS TYPES.json...
 *
 * prints `PUBLISHED N` every 25 messages, the client's log lines, and at
 * the end one JSON line with the client's counters.
 */

import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';

const [url, runtimeDir, seconds, ...typeFiles] = process.argv.slice(2);
const src = new URL('../../packages/wasm_js/src/', import.meta.url);
const { Runtime } = await import(pathToFileURL(`${runtimeDir}/runtime.mjs`).href);
const { TypeRegistry } = await import(new URL('cdr.mjs', src).href);
const { RosbridgeClient } = await import(new URL('bridges/rosbridge/client.mjs', src).href);
const { NodeWebSocket } = await import(new URL('bridges/rosbridge/ws_node.mjs', src).href);

const registry = new TypeRegistry(typeFiles.map((f) => JSON.parse(readFileSync(f, 'utf-8'))));
const runtime = await Runtime.create({});
const client = await RosbridgeClient.start({
  runtime, registry, url, WebSocket: NodeWebSocket,
  log: (level, text) => console.log(`[${level.toUpperCase()}] [rosbridge]: ${text}`),
});
const tools = await runtime.tools();
const node = await tools.createNode('js_talker');
const pub = await tools.advertise({
  topic: '/chatter', type: 'std_msgs/msg/String', node,
  qos: { history: 'keep_all', reliability: 'reliable', durability: 'volatile' },
});
await new Promise((r) => setTimeout(r, 500)); // the bridge sees the publisher and listens to it
const end = Date.now() + Number(seconds) * 1000;
let n = 0;
while (Date.now() < end) {
  await pub.publish(registry.encode('std_msgs/msg/String', { data: `seq ${n}` }));
  if (n % 25 === 0) console.log(`PUBLISHED ${n}`);
  n++;
  await new Promise((r) => setTimeout(r, 20));
}
console.log(`PUBLISHED ${n - 1} LAST`);
await new Promise((r) => setTimeout(r, 1500)); // the last messages leave
console.log(JSON.stringify({ ok: true, published: n, stats: client.stats() }));
await client.close();
await runtime.close();
process.exit(0);
