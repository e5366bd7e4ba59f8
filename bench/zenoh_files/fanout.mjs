// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The fan-out simulation of bench/zenoh: G runtimes (each a bus with its own
 * tools process, as a page has) in one Node.js process, each with N nodes
 * subscribing to /fanout and its own Zenoh gateway to one router; node 0 of
 * runtime 0 publishes M messages at R Hz. Every message should reach G x N
 * subscriptions: N on the publisher's bus, N on each other bus through the
 * router (one Zenoh sample per gateway, fanned out locally).
 *
 *   node fanout.mjs '{"endpoint", "module", "types": [...], "gateways", "nodes", "messages", "rateHz"}'
 *
 * Prints one JSON line: deliveries, deliveries/s, one-way latency p50/p99.
 */

import { readFileSync } from 'node:fs';

import { TypeRegistry } from '../../packages/wasm_js/src/cdr.mjs';
import { Runtime } from '../../packages/wasm_js/src/runtime.mjs';
import { ZenohGateway } from '../../packages/wasm_js/src/bridges/zenoh/gateway.mjs';

const o = JSON.parse(process.argv[2]);
const TYPE = 'demo_interfaces/msg/Chatter';
const QOS = { history: 'keep_last', depth: 100, reliability: 'reliable', durability: 'volatile' };
const registry = new TypeRegistry(o.types.map((p) => JSON.parse(readFileSync(p, 'utf-8'))));
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

function chatter(text) {
  const bytes = new TextEncoder().encode(text);
  const len = bytes.length + 1;
  const pad = (4 - ((8 + len) % 4)) % 4;
  const out = new Uint8Array(8 + len + pad + 4);
  new DataView(out.buffer).setUint32(4, len, true);
  out.set([0, 1, 0, 0]);
  out.set(bytes, 8);
  return out;
}

const latencies = [];
let delivered = 0;
const runtimes = [];
const gateways = [];
let publisher = null;
for (let g = 0; g < o.gateways; g++) {
  const runtime = await Runtime.create({});
  runtimes.push(runtime);
  const tools = await runtime.tools();
  for (let n = 0; n < o.nodes; n++) {
    const node = await tools.createNode(`fan_${g}_${n}`);
    await tools.subscribe({ topic: '/fanout', type: TYPE, qos: QOS, node }, (batch) => {
      const now = performance.timeOrigin + performance.now();
      for (const m of batch) {
        delivered += 1;
        const text = new TextDecoder().decode(m.data.subarray(8, 30)).split('|')[0];
        latencies.push(now - Number(text));
      }
    });
    if (g === 0 && n === 0) publisher = await tools.advertise({ topic: '/fanout', type: TYPE, qos: QOS, node });
  }
  gateways.push(await ZenohGateway.start({ runtime, registry, endpoint: o.endpoint, module: o.module }));
}
// every gateway connected and bridging /fanout (in: one remote publisher; out: the publisher's)
const deadline = Date.now() + 60000;
while (Date.now() < deadline) {
  const ready = gateways.every((gw, i) => gw.connected && gw.status()[i === 0 ? 'out' : 'in'].includes('/fanout'));
  if (ready) break;
  await sleep(100);
}
await sleep(1500);
delivered = 0;
latencies.length = 0;
const t0 = performance.now();
for (let i = 0; i < o.messages; i++) {
  await publisher.publish(chatter(`${(performance.timeOrigin + performance.now()).toFixed(3)}|${i}`));
  const wait = t0 + ((i + 1) * 1000) / o.rateHz - performance.now();
  if (wait > 0) await sleep(wait);
}
const expected = o.messages * o.gateways * o.nodes;
const end = Date.now() + 20000;
while (delivered < expected && Date.now() < end) await sleep(50);
const seconds = (performance.now() - t0) / 1000;
const sorted = [...latencies].sort((a, b) => a - b);
const pick = (p) => (sorted.length ? sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))] : NaN);
console.log(JSON.stringify({
  gateways: o.gateways, nodes: o.nodes, rateHz: o.rateHz, messages: o.messages, expected, delivered,
  deliveriesPerSecond: delivered / seconds, p50: pick(0.5), p99: pick(0.99),
  lost: gateways.reduce((s, gw) => s + gw.status().counters.lost, 0),
}));
for (const gw of gateways) await gw.close();
for (const r of runtimes) await r.close();
process.exit(0);
