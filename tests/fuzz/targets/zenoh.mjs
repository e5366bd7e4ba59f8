// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Fuzz target: what the Zenoh gateway (packages/wasm_js/src/bridges/zenoh/)
 * takes from peers: liveliness tokens (RemoteGraph.sample, parseToken,
 * the QoS text), samples with their attachment on a bridged topic
 * (TopicIn), and queries with their attachment on a served service
 * (ServiceServed). The gateway core runs on a real GatewayBus of a real
 * Runtime, as in its worker; in place of the zenoh-pico session (a C build,
 * not fuzzed here) a stand-in hands the gateway's callbacks what
 * zenoh-pico would: `{kind, key}` tokens, `{kind, key, payload,
 * attachment}` samples, queries with `reply()` and `drop()`.
 *
 * An input's first byte picks the kind (0: token, 1: sample, 2: query,
 * others: token); a token is `put KEY` or `delete KEY`; a sample or query is
 * one byte of attachment length, the attachment, then the payload. The
 * rule: a malformed one is dropped and counted (counters.malformed,
 * malformedTokens), never an exception out of the callback. The check: the
 * remote publisher's token put again, a well-formed sample reaches a local
 * subscription, a well-formed query is answered by the local server.
 *
 * Seeds (`--capture`): the tokens, attachments and samples the gateway
 * itself writes (tokenKey, encodeAttachment) for the entities of a run.
 */

import { readFileSync } from 'node:fs';

import { TypeRegistry } from '../../../packages/wasm_js/src/cdr.mjs';
import { GATEWAY_NODE, GatewayCore, knownTypes } from '../../../packages/wasm_js/src/bridges/zenoh/core.mjs';
import { GatewayBus } from '../../../packages/wasm_js/src/bridges/zenoh/gateway_bus.mjs';
import { decodeAttachment, encodeAttachment, Kind, tokenKey } from '../../../packages/wasm_js/src/bridges/zenoh/keys.mjs';
import { Runtime } from '../../../packages/wasm_js/src/runtime.mjs';

export const options = { json: false };

const enc = new TextEncoder();
const dec = new TextDecoder();
const INNER = 'cdr_test_msgs/msg/Inner';
const ADD = 'cdr_test_msgs/srv/AddTwoInts';
const TOPIC = '/fuzz_in';
const SERVICE = '/fuzz_add';
const REMOTE_ZID = '1f2e3d4c5b6a79880716253443526170';
const RELIABLE = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'volatile' };
const GID = Uint8Array.from({ length: 16 }, (_, i) => i + 1);

const remotePublisher = tokenKey({
  domain: 0, zid: REMOTE_ZID, nodeId: 3, id: 4, kind: Kind.PUBLISHER, enclave: '/', namespace: '/', node: 'talker',
  name: TOPIC, type: INNER, qos: RELIABLE,
});

function registryOf(types) {
  if (!types) throw new Error('the zenoh target needs --types (the types.json of cdr_test_msgs)');
  return new TypeRegistry([JSON.parse(readFileSync(types, 'utf-8'))]);
}

const framed = (kind, attachment, payload) => Uint8Array.of(kind, attachment.length, ...attachment, ...payload);

/** The seed corpus: tokens, samples and queries as the gateway writes them. */
export function capture({ types }) {
  const registry = registryOf(types);
  const seeds = [];
  const token = (name, text) => seeds.push({ name: `token-${name}`, bytes: Uint8Array.of(0, ...enc.encode(text)) });
  const base = { domain: 0, zid: REMOTE_ZID, nodeId: 3, enclave: '/', namespace: '/robot', node: 'talker' };
  token('node', `put ${tokenKey({ ...base, id: 3, kind: Kind.NODE })}`);
  token('publisher', `put ${remotePublisher}`);
  token('subscription-latched', `put ${tokenKey({ ...base, id: 5, kind: Kind.SUBSCRIPTION, name: '/tf_static', type: 'cdr_test_msgs/msg/Nested',
    qos: { history: 'keep_last', depth: 1, reliability: 'reliable', durability: 'transient_local', deadlineMs: 100, lifespanMs: 2000, liveliness: 'manual_by_topic', leaseMs: 500 } })}`);
  token('server', `put ${tokenKey({ ...base, id: 6, kind: Kind.SERVER, name: SERVICE, type: ADD, qos: RELIABLE })}`);
  token('client', `put ${tokenKey({ ...base, id: 7, kind: Kind.CLIENT, name: '/other', type: 'cdr_test_msgs/srv/Trigger', qos: { reliability: 'best_effort', history: 'keep_all' } })}`);
  token('delete', `delete ${tokenKey({ ...base, id: 3, kind: Kind.NODE })}`);
  const attachment = encodeAttachment(41n, 1700000000123456789n, GID);
  seeds.push({ name: 'sample', bytes: framed(1, attachment, registry.encode(INNER, { tag: 2, x: 0.5, label: 'over zenoh' })) });
  seeds.push({ name: 'sample-empty-payload', bytes: framed(1, encodeAttachment(0n, 0n, GID), []) });
  seeds.push({ name: 'query', bytes: framed(2, encodeAttachment(7n, 1700000000000000000n, GID), registry.encode(`${ADD}_Request`, { a: 20n, b: 22n })) });
  return seeds;
}

export async function setup({ types, finding }) {
  const registry = registryOf(types);
  const runtime = await Runtime.create({ warmWorkers: 0 });
  const helper = await runtime.helperProcess('zenoh');
  const bus = GatewayBus.attach(runtime.bus.handle, helper.pid, { name: GATEWAY_NODE, domain: 0 });
  const logs = [];
  const core = new GatewayCore(bus, {
    registry: knownTypes({ messages: [...registry.messages.keys()], services: [...registry.services.keys()] }),
    endpoint: 'tcp/127.0.0.1:7447', createModule: null, domain: 0,
    log: (level, text) => { if (logs.length < 100) logs.push(`${level} ${text}`); },
  });
  // the stand-in of zenoh-pico's session: it records the gateway's declarations
  const subscribers = new Map();
  const queryables = new Map();
  const entity = () => ({ close() {} });
  const session = {
    zid: 'aa00000000000000000000000000000b',
    up: true,
    subscribe: (key, cb) => { subscribers.set(key, cb); return entity(); },
    advancedSubscribe: (key, cb) => { subscribers.set(key, cb); return entity(); },
    subscribeLiveliness: () => entity(),
    queryable: (key, cb) => { queryables.set(key, cb); return entity(); },
    token: () => entity(),
    publisher: () => ({ ...entity(), put() {} }),
    advancedPublisher: () => ({ ...entity(), put() {} }),
    batch: (fn) => fn(),
    get: async () => [],
    close() {},
  };
  core.session = session;
  core.state = 'connected';
  core.tokens.attach(session);
  bus.onGraphChange(() => core._scheduleSync());

  const tools = await runtime.tools();
  const heard = [];
  await tools.subscribe({ topic: TOPIC, type: INNER, qos: RELIABLE }, (batch) => heard.push(...batch));
  const server = await tools.serve({ service: SERVICE, type: ADD }, (requests) => {
    for (const r of requests) {
      let sum = 0n;
      try {
        const { a, b } = registry.decode(`${ADD}_Request`, r.data);
        sum = BigInt.asIntN(64, a + b);
      } catch { /* a request that is not AddTwoInts gets 0 */ }
      server.respond(r.id, registry.encode(`${ADD}_Response`, { sum })).catch(() => {});
    }
  });
  const until = async (predicate, ms, what) => {
    const end = Date.now() + ms;
    while (Date.now() < end) {
      const v = predicate();
      if (v) return v;
      await new Promise((r) => setTimeout(r, 5));
    }
    throw new Error(`${what}: not within ${ms} ms`);
  };
  const sampleCallback = () => [...subscribers].find(([k]) => k.includes('fuzz_in'))?.[1];
  const queryCallback = () => [...queryables].find(([k]) => k.includes('fuzz_add'))?.[1];

  const feed = async (input) => {
    const kind = input[0];
    if (kind === 1 || kind === 2) {
      const n = input.length > 1 ? input[1] : 0;
      const attachment = input.subarray(2, 2 + n);
      const payload = input.subarray(2 + n);
      if (kind === 1) {
        const cb = sampleCallback();
        if (!cb) return 'no bridge';
        cb({ kind: payload.length % 7 === 6 ? 'delete' : 'put', key: `0/${TOPIC.slice(1)}`, payload, attachment });
        return 'sample';
      }
      const cb = queryCallback();
      if (!cb) return 'no service';
      let answer = 'pending';
      const done = cb({
        key: 'q', payload, attachment,
        reply: (key, response, att) => { answer = `reply ${response ? response.length : 0} ${att ? att.length : 0}`; },
        drop: () => { answer = 'dropped'; },
      });
      await done;
      return `query ${answer}`;
    }
    const text = dec.decode(kind === 0 ? input.subarray(1) : input);
    const space = text.indexOf(' ');
    const verb = space < 0 ? 'put' : text.slice(0, space);
    core.remoteGraph.sample({ kind: verb === 'delete' ? 'delete' : 'put', key: space < 0 ? text : text.slice(space + 1) });
    return `token ${verb === 'delete' ? 'delete' : 'put'}`;
  };
  let round = 0;
  const check = async () => {
    round++;
    core.remoteGraph.sample({ kind: 'put', key: remotePublisher });
    const cb = await until(sampleCallback, 3000, `the gateway did not bridge ${TOPIC} for the remote publisher`);
    const label = `check ${round}`;
    heard.length = 0;
    cb({ kind: 'put', key: `0/${TOPIC.slice(1)}`, payload: registry.encode(INNER, { tag: 1, x: 1, label }), attachment: encodeAttachment(BigInt(round), 1n, GID) });
    await until(() => heard.some((m) => { try { return registry.decode(INNER, m.data).label === label; } catch { return false; } }), 3000,
      `a sample '${label}' did not reach the local subscription`);
    const qcb = await until(queryCallback, 3000, `the gateway does not serve ${SERVICE}`);
    let reply = null;
    await qcb({
      key: 'q', payload: registry.encode(`${ADD}_Request`, { a: BigInt(round), b: 1n }), attachment: encodeAttachment(BigInt(round), 2n, GID),
      reply: (key, response, att) => { reply = { response, att }; },
      drop: () => { reply = { dropped: true }; },
    });
    if (!reply || reply.dropped) throw new Error(`a query of ${SERVICE} was ${reply ? 'dropped' : 'not answered'}`);
    const { sum } = registry.decode(`${ADD}_Response`, reply.response);
    if (sum !== BigInt(round) + 1n) throw new Error(`the query got ${sum}, not ${round + 1}`);
    if (decodeAttachment(reply.att).sequence !== BigInt(round)) throw new Error('the reply does not carry the query\'s sequence number');
  };
  return {
    coverageFiles: ['/bridges/zenoh/keys.mjs', '/bridges/zenoh/remote_graph.mjs', '/bridges/zenoh/bridges.mjs', '/bridges/zenoh/core.mjs'],
    async one(input) {
      if (!input.length) return 'empty';
      const before = { ...core.counters, tokens: core.remoteGraph.malformed };
      const outcome = await feed(input);
      await new Promise((r) => setImmediate(r));
      const after = core.counters;
      const counted = after.malformed > before.malformed ? ' counted malformed'
        : core.remoteGraph.malformed > before.tokens ? ' counted malformed token' : '';
      if (core.remoteGraph._named.size > 200) finding('memory', `the gateway keeps ${core.remoteGraph._named.size} malformed-token messages (unbounded)`);
      return `${outcome}${counted}`;
    },
    check,
    async close() {
      await core.close();
      await helper.release();
      await runtime.close();
    },
  };
}
