// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// One JS-only bus process of the fault tests (bus_faults_scenarios.mjs), in
// a Node.js worker thread or a browser's module worker: it runs the bus
// operations the scenario's main thread asks for, one call at a time
// ({id, method, args} -> {id, ok, value | error}). A call that reaches the
// armed fault point never answers: the thread sleeps there until the
// scenario terminates the worker.

let client = null;
let api = null;

const isBrowser = typeof WorkerGlobalScope !== 'undefined';
const port = isBrowser ? null : (await import('node:worker_threads')).parentPort;
const post = (m) => (isBrowser ? self.postMessage(m) : port.postMessage(m));

/**
 * A message starts with a tag and a counter (little endian), so that each is
 * known; the rest of its `size` bytes repeat the counter's low byte.
 */
function message(tag, n, size = 8) {
  const b = new Uint8Array(size).fill(n & 0xff);
  const v = new DataView(b.buffer);
  v.setInt32(0, tag, true);
  v.setInt32(4, n, true);
  return b;
}

function decode(data) {
  if (!data || data.length < 8) return { tag: -1, n: -1, len: data ? data.length : -1, intact: false };
  const v = new DataView(data.buffer, data.byteOffset, 8);
  const n = v.getInt32(4, true);
  let intact = true;
  for (let i = 8; i < data.length; i++) if (data[i] !== (n & 0xff)) intact = false;
  return { tag: v.getInt32(0, true), n, len: data.length, intact };
}

const KINDS = { publisher: 1, subscription: 2, service: 3, client: 4 };
const MODES = { subscription: 0, service: 1, client: 2 };

const methods = {
  async init(src, handle, pid) {
    const [busClient, faults] = await Promise.all([
      import(`${src}bus_client.mjs`), import(`${src}bus/faults.mjs`)]);
    api = { ...busClient, ...faults };
    client = busClient.BusClient.attach(handle, pid);
    return pid;
  },
  node(name) {
    return client.createNode({ name, context: client.createContext() }).index;
  },
  destroyNode(node) {
    client.destroyNode(node);
  },
  endpoint(kind, node, name, qos = {}, extra = {}) {
    return client.createEndpoint({
      kind: KINDS[kind], node, name, type: 'test_msgs/msg/Bytes', qos, ...extra,
    }).index;
  },
  destroy(ep) {
    client.destroyEndpoint(ep);
  },
  /** Publish messages (tag, from .. from + count - 1) of `size` bytes; returns the last sequence number. */
  publish(ep, tag, from, count = 1, timeoutMs = 5000, size = 8) {
    let seq = 0;
    for (let i = 0; i < count; i++) seq = client.publish(ep, message(tag, from + i, size), timeoutMs);
    return seq;
  },
  /** Take what is there now (at most `max`; raw: with the bytes). */
  take(ep, kind = 'subscription', max = 100000, raw = false) {
    const got = [];
    let data;
    while (got.length < max && (data = client.take(ep, MODES[kind]))) got.push(taken(data, raw));
    return got;
  },
  /**
   * Wait (a wait set, as an executor) until `count` messages were taken or
   * `timeoutMs` passed; returns what was taken.
   */
  waitTake(ep, kind, count, timeoutMs, raw = false) {
    const items = new Int32Array(api.WAIT_ITEM_WORDS);
    items[0] = { subscription: api.WaitKind.SUBSCRIPTION, service: api.WaitKind.SERVICE, client: api.WaitKind.CLIENT }[kind];
    items[1] = ep;
    const got = [];
    const deadline = performance.now() + timeoutMs;
    while (got.length < count) {
      const left = deadline - performance.now();
      if (left <= 0) break;
      if (client.wait(items, 0, 1, left, items) <= 0) continue;
      let data;
      while (got.length < count && (data = client.take(ep, MODES[kind]))) got.push(taken(data, raw));
    }
    return got;
  },
  /** Answer the requests taken by take()/waitTake() (their ids), as a service. */
  respond(ep, requests, tag, timeoutMs = 5000) {
    return requests.map((r, i) => client.sendResponse(ep, r.gid, r.reqLo, r.reqHi, message(tag, r.n * 1000 + i), timeoutMs));
  },
  matched(ep) {
    return client.matchedCount(ep);
  },
  serverAvailable(ep) {
    return client.serverAvailable(ep);
  },
  event(ep, type, take = true) {
    const s = client.eventStatus(ep, api.EventType[type], take);
    return { ...s, next: s.next === Infinity ? null : s.next };
  },
  waitForAllAcked(ep, timeoutMs) {
    return client.waitForAllAcked(ep, timeoutMs);
  },
  arm(spec) {
    api.armFaultPoint(client.bus, spec);
  },
  sleepMs(ms) {
    Atomics.wait(new Int32Array(new SharedArrayBuffer(4)), 0, 0, ms);
  },
};

function taken(data, raw = false) {
  const i = client.info;
  const m = { ...decode(data), gid: Array.from(i.gid), reqLo: i.reqLo, reqHi: i.reqHi };
  if (raw) m.bytes = Array.from(data);
  return m;
}

async function onMessage(m) {
  try {
    post({ id: m.id, ok: true, value: await methods[m.method](...m.args) });
  } catch (e) {
    post({ id: m.id, ok: false, error: { message: e.message, code: e.code || 0, stack: e.stack } });
  }
}

if (isBrowser) self.onmessage = (e) => onMessage(e.data);
else port.on('message', onMessage);
post({ ready: true });
