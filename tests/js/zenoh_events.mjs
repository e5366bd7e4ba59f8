// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A local subscription behind the Zenoh gateway, for tests/test_zenoh_events.py:
 * a Runtime (this repository's wasm_js) with the gateway to a router, and a
 * bus process of this script with a node `/events_listener` subscribing to
 * a topic. After every change of the local graph or of the gateway's remote
 * graph it prints one JSON line: the subscription's LIVELINESS_CHANGED
 * status (taken: the changes since the last line), the topic's local
 * publishers (the gateway's proxies) and the remote nodes the gateway knows.
 *
 *   node zenoh_events.mjs '{"endpoint", "module", "types": [...], "topic", "type"}'
 */

import { readFileSync } from 'node:fs';

import { BusClient, EventType, KIND_SUBSCRIPTION } from '../../packages/wasm_js/src/bus_client.mjs';
import { TypeRegistry } from '../../packages/wasm_js/src/cdr.mjs';
import { ZenohGateway } from '../../packages/wasm_js/src/bridges/zenoh/gateway.mjs';
import { Runtime } from '../../packages/wasm_js/src/runtime.mjs';

const o = JSON.parse(process.argv[2]);
const registry = new TypeRegistry(o.types.map((p) => JSON.parse(readFileSync(p, 'utf-8'))));
const runtime = await Runtime.create({});
const { pid } = await runtime.helperProcess('events');
const client = BusClient.attach(runtime.bus.handle, pid);
const node = client.createNode({ name: 'events_listener', namespace: '/', domain: 0, context: client.createContext() }).index;
const sub = client.createEndpoint({
  kind: KIND_SUBSCRIPTION, node, name: o.topic, type: o.type,
  qos: { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'volatile' },
}).index;

let gateway = null;
let last = '';
const report = () => {
  const e = client.eventStatus(sub, EventType.LIVELINESS_CHANGED, true);
  const topic = runtime.graph().topics.find((t) => t.name === o.topic);
  const line = JSON.stringify({
    alive: e.alive, aliveChange: e.aliveChange, notAlive: e.notAlive,
    publishers: topic ? topic.publishers.length : 0,
    state: gateway ? gateway.state : 'starting', remoteNodes: gateway ? gateway.remote.nodes : [],
  });
  if (line !== last) console.log(line);
  last = line;
};
gateway = await ZenohGateway.start({
  runtime, registry, endpoint: o.endpoint, module: o.module, onChange: report,
  log: (level, text) => process.stderr.write(`[${level}] ${text}\n`),
});
runtime.onGraphChange(report);
report();
// ends when the test kills it (with SIGKILL: the gateway's session then goes without a goodbye)
setInterval(() => {}, 1 << 30);
