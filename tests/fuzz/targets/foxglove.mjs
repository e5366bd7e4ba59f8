// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Fuzz target: the client messages of the Foxglove WebSocket server
 * (packages/wasm_js/src/bridges/foxglove/): JSON ops and the binary
 * opcodes (message data, service call requests) through
 * `Session.receive()`, the server's per-message entry point, on a real
 * Runtime with the cdr_test_msgs types, a tools publisher on /chatter and a
 * tools server of /add in the graph. The rule: a status or a
 * serviceCallFailure, never an exception out of `receive()`, no unhandled
 * rejection, no internal error (TypeError, ...) in a status. The check:
 * the same session advertises a JSON channel and publishes on it, and a
 * bus subscription hears the message.
 *
 * Seeds (`--capture`): a scripted client's messages (every op, JSON and
 * CDR message data, JSON and CDR service calls) and the server's answers.
 */

import { readFileSync } from 'node:fs';

import { TypeRegistry } from '../../../packages/wasm_js/src/cdr.mjs';
import { FoxgloveServer } from '../../../packages/wasm_js/src/bridges/foxglove/server.mjs';
import { Runtime } from '../../../packages/wasm_js/src/runtime.mjs';
import { asMessage, outcomeOf, RecordingSocket } from './rosbridge.mjs';

export const options = { json: true };

const enc = new TextEncoder();
const INTERNAL = /\b(TypeError|RangeError|ReferenceError|SyntaxError)\b|Cannot read propert|is not a function|is not iterable|Maximum call stack|Invalid array length|Cannot mix BigInt|Do not know how to serialize|Cannot convert/;
const INNER = 'cdr_test_msgs/msg/Inner';
const ADD = 'cdr_test_msgs/srv/AddTwoInts';
const CHECK_TOPIC = '/fuzz_check_foxglove';
const CHECK_CHANNEL = 1000001;
const RELIABLE = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'volatile' };

function u32(n) {
  const b = new Uint8Array(4);
  new DataView(b.buffer).setUint32(0, n, true);
  return b;
}

const cat = (...parts) => Uint8Array.from(parts.flatMap((p) => [...p]));

async function start(types, schemas) {
  if (!types) throw new Error('the foxglove target needs --types (the types.json of cdr_test_msgs)');
  const registry = new TypeRegistry([JSON.parse(readFileSync(types, 'utf-8'))]);
  const runtime = await Runtime.create({ warmWorkers: 0 });
  const tools = await runtime.tools();
  const talker = await tools.advertise({ topic: '/chatter', type: INNER, qos: RELIABLE });
  const adder = await tools.serve({ service: '/add', type: ADD }, (requests) => {
    for (const r of requests) {
      let sum = 0n;
      try {
        const { a, b } = registry.decode(`${ADD}_Request`, r.data);
        sum = BigInt.asIntN(64, a + b);
      } catch { /* a malformed request gets 0 */ }
      adder.respond(r.id, registry.encode(`${ADD}_Response`, { sum })).catch(() => {});
    }
  });
  const server = await FoxgloveServer.start({ runtime, registry, schemas, host: '127.0.0.1', port: 0 });
  await new Promise((r) => setTimeout(r, 100));
  server._refresh();
  return { runtime, tools, talker, server, registry };
}

/** The seed corpus: a scripted client's messages and what the server sent. */
export async function capture({ types, schemas }) {
  const { runtime, talker, server, registry } = await start(types, schemas);
  const sock = new RecordingSocket();
  sock.protocol = 'foxglove.websocket.v1';
  const session = server.attach(sock, 'capture');
  const seeds = [];
  const keep = (name, data) => seeds.push({ name, bytes: typeof data === 'string' ? enc.encode(data) : Uint8Array.from(data) });
  const sent = () => sock.sent.map((m) => (typeof m === 'string' ? JSON.parse(m) : null)).filter(Boolean);
  const send = async (name, msg) => {
    const data = typeof msg === 'string' || msg instanceof Uint8Array ? msg : JSON.stringify(msg);
    keep(`client-${name}`, data);
    session.receive(data, typeof data !== 'string');
    await new Promise((r) => setTimeout(r, 80));
  };
  const channel = sent().flatMap((m) => (m.op === 'advertise' ? m.channels : [])).find((c) => c.topic === '/chatter');
  const service = sent().flatMap((m) => (m.op === 'advertiseServices' ? m.services : [])).find((s) => s.name === '/add');
  if (!channel || !service) throw new Error('the server did not advertise /chatter and /add');
  await send('subscribe', { op: 'subscribe', subscriptions: [{ id: 1, channelId: channel.id }] });
  await talker.publish(registry.encode(INNER, { tag: 1, x: 0.25, label: 'from the bus' }));
  await send('advertise', { op: 'advertise', channels: [{ id: 7, topic: '/from_client', encoding: 'json', schemaName: INNER },
    { id: 8, topic: '/from_client_cdr', encoding: 'cdr', schemaName: 'cdr_test_msgs/msg/Nested' }] });
  await send('message-json', cat([1], u32(7), enc.encode(JSON.stringify({ tag: 3, x: 1.5, label: 'json' }))));
  await send('message-cdr', cat([1], u32(8), registry.encode('cdr_test_msgs/msg/Nested', { lead: 2, more: [{ tag: 1, x: 2, label: 'n' }] })));
  const request = registry.encode(`${ADD}_Request`, { a: 2n, b: 40n });
  await send('call-cdr', cat([2], u32(service.id), u32(11), u32(3), enc.encode('cdr'), request));
  await send('call-json', cat([2], u32(service.id), u32(12), u32(4), enc.encode('json'), enc.encode('{"a": 5, "b": 6}')));
  await send('get-parameters', { op: 'getParameters', parameterNames: ['/talker.rate'], id: 'g1' });
  await send('set-parameters', { op: 'setParameters', parameters: [{ name: '/talker.rate', value: 5 }], id: 's1' });
  await send('subscribe-parameter-updates', { op: 'subscribeParameterUpdates', parameterNames: ['/talker.rate'] });
  await send('unsubscribe-parameter-updates', { op: 'unsubscribeParameterUpdates', parameterNames: ['/talker.rate'] });
  await send('subscribe-graph', { op: 'subscribeConnectionGraph' });
  await send('unsubscribe-graph', { op: 'unsubscribeConnectionGraph' });
  await send('fetch-asset', { op: 'fetchAsset', uri: 'package://cdr_test_msgs/package.xml', requestId: 3 });
  await send('unadvertise', { op: 'unadvertise', channelIds: [7, 8] });
  await send('unsubscribe', { op: 'unsubscribe', subscriptionIds: [1] });
  await new Promise((r) => setTimeout(r, 200));
  const kinds = new Set();
  for (const m of sock.sent) {
    const kind = typeof m === 'string' ? JSON.parse(m).op : `binary-${m[0]}`;
    if (kinds.has(kind)) continue;
    kinds.add(kind);
    keep(`server-${kind}`, m);
  }
  await server.close(100);
  await runtime.close();
  return seeds;
}

export async function setup({ types, schemas, finding }) {
  const { runtime, tools, server } = await start(types, schemas);
  const sock = new RecordingSocket();
  sock.protocol = 'foxglove.websocket.v1';
  const session = server.attach(sock, 'fuzz');
  const heard = [];
  await tools.subscribe({ topic: CHECK_TOPIC, type: INNER, qos: RELIABLE }, (batch) => heard.push(...batch));
  let round = 0;
  const until = async (predicate, ms, what) => {
    const end = Date.now() + ms;
    while (Date.now() < end) {
      if (predicate()) return;
      await new Promise((r) => setTimeout(r, 5));
    }
    throw new Error(`${what}: not within ${ms} ms`);
  };
  return {
    coverageFiles: ['/bridges/foxglove/'],
    async one(input) {
      const { data, binary } = asMessage(input);
      session.receive(binary ? data : data, binary);
      await new Promise((r) => setImmediate(r));
      const sent = sock.take();
      for (const m of sent) {
        if (typeof m === 'string' && INTERNAL.test(m)) finding('internal', `an internal error reached the client: ${m.slice(0, 400)}`);
      }
      return outcomeOf(sent);
    },
    async check() {
      round++;
      const label = `check ${round}`;
      session.receive(JSON.stringify({ op: 'advertise', channels: [{ id: CHECK_CHANNEL, topic: CHECK_TOPIC, encoding: 'json', schemaName: INNER }] }), false);
      await new Promise((r) => setTimeout(r, 20));
      session.receive(cat([1], u32(CHECK_CHANNEL), enc.encode(JSON.stringify({ tag: 1, x: 0.5, label }))), true);
      const registry = server.registry;
      await until(() => heard.some((m) => { try { return registry.decode(INNER, m.data).label === label; } catch { return false; } }),
        3000, `a message the session published as '${label}' did not reach the bus`);
      heard.length = 0;
      sock.take();
    },
    async close() {
      await server.close(100);
      await runtime.close();
    },
  };
}
