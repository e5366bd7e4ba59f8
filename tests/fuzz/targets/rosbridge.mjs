// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Fuzz target: the rosbridge v2 server in Node.js
 * (packages/wasm_js/src/bridges/rosbridge/): JSON ops, CBOR requests and
 * fragments, through `Session.receive()`, the entry point the server calls
 * per WebSocket message, on a real Runtime (its bus and tools worker) with
 * the cdr_test_msgs types. The client is a recording stand-in for the
 * socket; everything behind it is the server's own code.
 *
 * An input is one message: text when it is UTF-8, else binary (CBOR). The
 * rule: it is answered with a status error or dropped, never an exception
 * out of `receive()`, never an unhandled rejection, and an internal error
 * (TypeError, RangeError, ...) that reaches the client as a status is a
 * finding too. The check after it: on the same session, a rosapi call is
 * answered, and a publish reaches a second client that subscribed.
 *
 * The seed corpus (`--capture`) is the traffic of a scripted session
 * against the real server: the requests of every op (JSON, the CBOR
 * publish of colcon-wasm's rosbridge client, a CBOR subscribe written by
 * the server's CBOR writer) and what the server sent back (publish in
 * JSON, fragments, cbor and cbor-raw messages, status and responses).
 */

import { readFileSync } from 'node:fs';

import { TypeRegistry } from '../../../packages/wasm_js/src/cdr.mjs';
import { encodeCbor } from '../../../packages/wasm_js/src/bridges/rosbridge/cbor.mjs';
import { cdrPublish } from '../../../packages/wasm_js/src/bridges/rosbridge/client_topics.mjs';
import { RosbridgeServer } from '../../../packages/wasm_js/src/bridges/rosbridge/server.mjs';
import { Runtime } from '../../../packages/wasm_js/src/runtime.mjs';

export const options = { json: true };

const utf8 = new TextDecoder('utf-8', { fatal: true });
const enc = new TextEncoder();
const INTERNAL = /\b(TypeError|RangeError|ReferenceError|SyntaxError|InternalError)\b|Cannot read propert|is not a function|is not iterable|Maximum call stack|Invalid array length|Cannot mix BigInt|Do not know how to serialize|Cannot convert/;
const CHECK_TOPIC = '/fuzz_check_rosbridge';
const INNER = 'cdr_test_msgs/msg/Inner';

/** A WebSocket stand-in that keeps what the server sends. */
export class RecordingSocket {
  constructor() {
    this.sent = [];
    this.total = 0;
    this.bufferedAmount = 0;
    this.closed = null;
    this.ondrain = null;
  }

  send(data) {
    this.total++;
    this.sent.push(data);
    if (this.sent.length > 2000) this.sent.splice(0, 1000);
  }

  close(code, reason) {
    this.closed = { code, reason };
  }

  terminate() {
    this.closed = this.closed || { code: 1006 };
  }

  /** The messages sent since the last call. */
  take() {
    return this.sent.splice(0);
  }
}

/** The text or bytes of a message as the server gets it: text if UTF-8, else binary. */
export function asMessage(input) {
  try {
    return { data: utf8.decode(input), binary: false };
  } catch {
    return { data: input, binary: true };
  }
}

/** The class of what came back: the ops and status texts. */
export function outcomeOf(sent) {
  if (!sent.length) return 'silent';
  const kinds = new Set();
  for (const m of sent) {
    if (typeof m !== 'string') { kinds.add('binary'); continue; }
    try {
      const o = JSON.parse(m);
      kinds.add(o.op === 'status' ? `status ${o.level} ${String(o.msg ?? o.message).slice(0, 90)}` : `${o.op}${o.result === false ? ' failed' : ''}`);
    } catch {
      kinds.add('text');
    }
  }
  return [...kinds].sort().join(' | ');
}

const until = async (predicate, ms, what) => {
  const end = Date.now() + ms;
  while (Date.now() < end) {
    const v = predicate();
    if (v) return v;
    await new Promise((r) => setTimeout(r, 5));
  }
  throw new Error(`${what}: not within ${ms} ms`);
};

/** Start a server on a Runtime; `finding(kind, text)` hears internal errors logged by it. */
async function start(types, schemas, finding) {
  if (!types) throw new Error('the rosbridge target needs --types (the types.json of cdr_test_msgs)');
  const registry = new TypeRegistry([JSON.parse(readFileSync(types, 'utf-8'))]);
  const runtime = await Runtime.create({ warmWorkers: 0 });
  const server = await RosbridgeServer.start({
    runtime, registry, schemas, host: '127.0.0.1', port: 0,
    limits: { maxMessageBytes: 1 << 20, callTimeoutMs: 300 },
    log: (level, text) => {
      if (level === 'debug' && / failed: /.test(text) && INTERNAL.test(text) && finding) finding('internal', text);
    },
  });
  return { runtime, server, registry };
}

/** The seed corpus: a scripted session's requests and the server's answers. */
export async function capture({ types, schemas }) {
  const { runtime, server, registry } = await start(types, schemas, null);
  const a = new RecordingSocket();
  const b = new RecordingSocket();
  const sa = server.attach(a, 'capture-a');
  const sb = server.attach(b, 'capture-b');
  const seeds = [];
  const keep = (name, data) => seeds.push({ name, bytes: typeof data === 'string' ? enc.encode(data) : Uint8Array.from(data) });
  const send = async (session, name, msg) => {
    const data = typeof msg === 'string' || msg instanceof Uint8Array ? msg : JSON.stringify(msg);
    keep(`request-${name}`, data);
    session.receive(data, typeof data !== 'string');
    await new Promise((r) => setTimeout(r, 60));
  };
  const inner = { tag: 7, x: 2.5, label: 'hello' };
  await send(sb, 'set-level', { op: 'set_level', level: 'info', id: 'l1' });
  await send(sb, 'subscribe', { op: 'subscribe', id: 's1', topic: '/chatter', type: INNER, throttle_rate: 0, queue_length: 2 });
  await send(sb, 'subscribe-fragments', { op: 'subscribe', id: 's2', topic: '/chatter', type: INNER, fragment_size: 24 });
  await send(sb, 'subscribe-cbor', encodeCbor({ op: 'subscribe', id: 's3', topic: '/nested', type: 'cdr_test_msgs/msg/Nested', compression: 'cbor' }));
  await send(sb, 'subscribe-cbor-raw', { op: 'subscribe', id: 's4', topic: '/seq', type: 'cdr_test_msgs/msg/Sequences', compression: 'cbor-raw' });
  await send(sb, 'subscribe-png', { op: 'subscribe', id: 's5', topic: '/prims', type: 'cdr_test_msgs/msg/Primitives', compression: 'png' });
  await send(sa, 'advertise', { op: 'advertise', id: 'a1', topic: '/chatter', type: INNER, latch: false, queue_size: 10 });
  await send(sa, 'publish', { op: 'publish', id: 'p1', topic: '/chatter', msg: inner });
  await send(sa, 'publish-nested', { op: 'publish', topic: '/nested', type: 'cdr_test_msgs/msg/Nested', msg: { lead: 1, inner, more: [inner], tail: -3 } });
  await send(sa, 'publish-sequences', { op: 'publish', topic: '/seq', type: 'cdr_test_msgs/msg/Sequences', msg: { u8s: 'AQID', f64s: [0.5, -1], u64s: ['18446744073709551615'], strings: ['a', 'b'] } });
  await send(sa, 'publish-primitives', { op: 'publish', topic: '/prims', type: 'cdr_test_msgs/msg/Primitives', msg: { b: true, u8: 200, i64: '-9007199254740993', f32: 1.5 } });
  await send(sa, 'publish-cdr', cdrPublish('/seq', registry.encode('cdr_test_msgs/msg/Sequences', { u8s: [9, 8], lead: 2 }), 1700000000123, 1000));
  await send(sa, 'call-rosapi-topics', { op: 'call_service', id: 'c1', service: '/rosapi/topics', args: {} });
  await send(sa, 'call-rosapi-nodes', { op: 'call_service', id: 'c2', service: '/rosapi/nodes' });
  await send(sa, 'call-rosapi-type', { op: 'call_service', id: 'c3', service: '/rosapi/topic_type', args: { topic: '/chatter' } });
  await send(sa, 'call-rosapi-details', { op: 'call_service', id: 'c4', service: '/rosapi/message_details', args: { type: 'cdr_test_msgs/msg/Nested' } });
  await send(sb, 'advertise-service', { op: 'advertise_service', service: '/add', type: 'cdr_test_msgs/srv/AddTwoInts' });
  await send(sa, 'call-service', { op: 'call_service', id: 'c5', service: '/add', type: 'cdr_test_msgs/srv/AddTwoInts', args: { a: 2, b: '40' }, timeout: 2 });
  await new Promise((r) => setTimeout(r, 200));
  const call = b.sent.map((m) => (typeof m === 'string' ? JSON.parse(m) : null)).find((m) => m && m.op === 'call_service');
  if (call) await send(sb, 'service-response', { op: 'service_response', id: call.id, service: '/add', values: { sum: 42 }, result: true });
  await send(sb, 'unadvertise-service', { op: 'unadvertise_service', service: '/add' });
  await send(sa, 'send-action-goal', { op: 'send_action_goal', id: 'g1', action: '/fib', action_type: 'cdr_test_msgs/action/Fibonacci', args: { order: 3 }, feedback: true });
  await send(sa, 'fragment-0', { op: 'fragment', id: 'f1', num: 0, total: 2, data: '{"op":"call_service","service":' });
  await send(sa, 'fragment-1', { op: 'fragment', id: 'f1', num: 1, total: 2, data: '"/rosapi/services","id":"f1"}' });
  await send(sa, 'unsubscribe', { op: 'unsubscribe', id: 's1', topic: '/chatter' });
  await send(sa, 'unadvertise', { op: 'unadvertise', topic: '/chatter' });
  await send(sa, 'status', { op: 'status', level: 'info', msg: 'a client report' });
  await send(sa, 'malformed', '{"op": "publish", "id": "m1", ');
  await new Promise((r) => setTimeout(r, 300));
  // what the server sent: one of each kind of message
  const seen = new Set();
  for (const [who, sock] of [['a', a], ['b', b]]) {
    for (const m of sock.sent) {
      const kind = typeof m === 'string' ? JSON.parse(m).op : 'cbor';
      if (seen.has(`${who}${kind}`) || seen.size > 24) continue;
      seen.add(`${who}${kind}`);
      keep(`sent-${who}-${kind}`, m);
    }
  }
  await server.close(100);
  await runtime.close();
  return seeds;
}

export async function setup({ types, schemas, finding }) {
  const { runtime, server } = await start(types, schemas, finding);
  const fuzzed = new RecordingSocket();
  const watcher = new RecordingSocket();
  const session = server.attach(fuzzed, 'fuzz');
  const observer = server.attach(watcher, 'observer');
  observer.receive(JSON.stringify({ op: 'subscribe', id: 'w', topic: CHECK_TOPIC, type: INNER }), false);
  let round = 0;
  return {
    coverageFiles: ['/bridges/rosbridge/'],
    async one(input) {
      const { data, binary } = asMessage(input);
      session.receive(data, binary);
      await new Promise((r) => setImmediate(r));
      const sent = fuzzed.take();
      for (const m of sent) {
        if (typeof m === 'string' && m.includes('"op":"status"') && INTERNAL.test(m)) finding('internal', `an internal error reached the client: ${m.slice(0, 400)}`);
      }
      return outcomeOf(sent);
    },
    async check() {
      round++;
      const id = `check-${round}`;
      fuzzed.take();
      session.receive(JSON.stringify({ op: 'call_service', id, service: '/rosapi/topics', fragment_size: 0 }), false);
      await until(() => fuzzed.sent.some((m) => typeof m === 'string' && m.includes(`"id":"${id}"`) && m.includes('"op":"service_response"') && m.includes('"result":true')),
        3000, `the rosapi call ${id} was not answered`);
      watcher.take();
      session.receive(JSON.stringify({ op: 'publish', topic: CHECK_TOPIC, type: INNER, msg: { tag: round % 256, x: 0.5, label: id } }), false);
      await until(() => watcher.sent.some((m) => typeof m === 'string' && m.includes(`"label":"${id}"`)), 3000,
        `a publish of ${id} did not reach the other client`);
      fuzzed.take();
    },
    async close() {
      await server.close(100);
      await runtime.close();
    },
  };
}
