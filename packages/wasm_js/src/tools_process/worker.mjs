// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The tools worker: a JS-only bus process. It never blocks in a wait (it
 * must keep receiving calls): it sleeps with Atomics.waitAsync on its
 * doorbell and, on each wake-up, drains its subscriptions into one batch per
 * subscription and completes pending service calls.
 *
 * @module tools_process/worker
 */

import { BusClient, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, TakeMode } from '../bus_client.mjs';
import { armFaultPoint } from '../bus/faults.mjs';
import { FromTools, ToTools } from '../protocol.mjs';

let client = null;
const subscriptions = new Set();
/** service server endpoints (rosbridge's advertise_service) */
const servers = new Set();
const publishers = new Map();
/** service name key -> client endpoint */
const clientByKey = new Map();
/** client endpoint -> Map(sequence number -> pending call) */
const clients = new Map();
let armed = false;
let drainQueued = false;
/**
 * Work that must follow the reply of the current call: a new subscription's
 * first drain (a TRANSIENT_LOCAL writer's history is there at once) goes
 * after the reply that gives the main thread its id, else the main thread
 * gets a batch for a subscription it does not know yet, and drops it.
 */
let afterReply = [];

/**
 * Drain once the current call is done: a subscription of this process to a
 * topic it publishes on gets the message now, not at the next wake-up (a
 * burst of publishes would otherwise overrun a KEEP_LAST reader's history).
 */
function drainSoon() {
  if (drainQueued) return;
  drainQueued = true;
  queueMicrotask(() => {
    drainQueued = false;
    drain();
  });
}

const post = (m, transfer) => (typeof self !== 'undefined' && self.postMessage
  ? self.postMessage(m, transfer || [])
  : port.postMessage(m, transfer || []));

let port = null;
if (typeof self === 'undefined' || typeof self.postMessage !== 'function') {
  port = (await import('node:worker_threads')).parentPort;
}

function infoOf(c) {
  const i = c.info;
  return {
    sourceTime: i.sourceTime,
    receivedTime: i.receivedTime,
    publicationSequence: i.pubSeqHi * 4294967296 + (i.pubSeqLo >>> 0),
    publisherGid: Array.from(i.gid),
  };
}

function drain() {
  for (const ep of subscriptions) {
    const messages = [];
    const transfer = [];
    let data;
    while ((data = client.take(ep, TakeMode.MESSAGE))) {
      messages.push({ data, info: infoOf(client) });
      transfer.push(data.buffer);
    }
    if (messages.length) post({ type: FromTools.BATCH, subscription: ep, messages }, transfer);
  }
  for (const ep of servers) {
    const requests = [];
    const transfer = [];
    let data;
    while ((data = client.take(ep, TakeMode.REQUEST))) {
      const i = client.info;
      requests.push({ data, id: { gid: Array.from(i.gid), seqLo: i.reqLo, seqHi: i.reqHi }, info: infoOf(client) });
      transfer.push(data.buffer);
    }
    if (requests.length) post({ type: FromTools.REQUESTS, service: ep, requests }, transfer);
  }
  for (const [ep, pending] of clients) {
    let data;
    while (pending.size && (data = client.take(ep, TakeMode.RESPONSE))) {
      const seq = client.info.reqHi * 4294967296 + (client.info.reqLo >>> 0);
      const p = pending.get(seq);
      if (p) {
        pending.delete(seq);
        clearTimeout(p.timer);
        p.resolve({ data, info: infoOf(client) });
      }
    }
    if (pending.size && !client.serverAvailable(ep)) serversGone(ep, pending);
  }
}

/**
 * The servers a client's calls went to left the bus (stopped, or killed
 * before they answered): an answer they committed was taken above, none
 * can come now, so those calls fail at once rather than at their timeout.
 */
function serversGone(ep, pending) {
  for (const [seq, p] of pending) {
    if (!p.hadServer) continue; // sent before any server was there: its timeout tells
    pending.delete(seq);
    clearTimeout(p.timer);
    p.reject(Object.assign(new Error(`service call to '${p.name}' failed: its server went away before it answered (no server of it is left on the bus)`), { code: 1 }));
  }
}

/**
 * Sleep on the doorbell without blocking: registered as a sleeper (so that
 * writers ring), then read the doorbell, drain, and waitAsync while the
 * doorbell keeps the value read (the protocol of BusClient.wait).
 */
function arm() {
  if (armed) return;
  armed = true;
  client.register();
  const i32 = client.bus.i32;
  const bell = client.bell();
  drain();
  const r = Atomics.waitAsync(i32, client.bellIndex, bell);
  const wake = () => {
    client.unregister();
    armed = false;
    arm();
  };
  if (r.async) r.value.then(wake);
  else Promise.resolve().then(wake);
}

function endpoint(spec, kind) {
  return client.createEndpoint({
    kind, node: spec.node, name: spec.name, type: spec.type, qos: spec.qos || {}, ignoreLocal: !!spec.ignoreLocal,
  }).index;
}

const methods = {
  init(sab, pid) {
    client = BusClient.attach(sab, pid);
    arm();
    return pid;
  },
  createNode(spec) {
    return client.createNode({ name: spec.name, namespace: spec.namespace, domain: spec.domain, context: client.createContext() }).index;
  },
  subscribe(spec) {
    const ep = endpoint(spec, KIND_SUBSCRIPTION);
    subscriptions.add(ep);
    afterReply.push(drain);
    return ep;
  },
  advertise(spec) {
    return endpoint(spec, KIND_PUBLISHER);
  },
  publish(ep, data) {
    const seq = client.publish(ep, data, 10000);
    if (subscriptions.size) drainSoon();
    return seq;
  },
  publishMany(ep, list) {
    let seq = 0;
    for (const data of list) seq = client.publish(ep, data, 10000);
    if (subscriptions.size) drainSoon();
    return seq;
  },
  /** Wait (blocking this worker, `timeoutMs` at most) until every reliable reader took all. */
  waitForAllAcked(ep, timeoutMs) {
    return client.waitForAllAcked(ep, timeoutMs);
  },
  publishOnce(spec, data) {
    const key = JSON.stringify([spec.node, spec.name, spec.type, spec.qos || {}]);
    let ep = publishers.get(key);
    if (ep === undefined) {
      ep = endpoint(spec, KIND_PUBLISHER);
      publishers.set(key, ep);
    }
    const seq = client.publish(ep, data, 10000);
    if (subscriptions.size) drainSoon();
    return seq;
  },
  call(spec, request, timeoutMs) {
    const key = JSON.stringify([spec.node, spec.name, spec.type, spec.qos || {}]);
    let ep = clientByKey.get(key);
    if (ep === undefined) {
      ep = endpoint(spec, KIND_CLIENT);
      clientByKey.set(key, ep);
      clients.set(ep, new Map());
    }
    const pending = clients.get(ep);
    return new Promise((resolve, reject) => {
      // Before the request goes out: a server that dies right after it was sent was there.
      const hadServer = client.serverAvailable(ep);
      const seq = client.publish(ep, request, timeoutMs);
      const timer = setTimeout(() => {
        pending.delete(seq);
        reject(Object.assign(new Error(`service call to '${spec.name}' timed out after ${timeoutMs} ms (server available: ${client.serverAvailable(ep)})`), { code: 2 }));
      }, timeoutMs);
      pending.set(seq, { resolve, reject, timer, name: spec.name, hadServer });
      drain();
    });
  },
  serve(spec) {
    const ep = endpoint(spec, KIND_SERVICE);
    servers.add(ep);
    afterReply.push(drain);
    return ep;
  },
  respond(ep, id, data, timeoutMs) {
    return client.sendResponse(ep, id.gid, id.seqLo, id.seqHi, data, timeoutMs);
  },
  /** Tests only: stop this worker at a fault point (bus/faults.mjs). */
  armFaultPoint(spec) {
    armFaultPoint(client.bus, spec);
  },
  destroy(ep) {
    subscriptions.delete(ep);
    servers.delete(ep);
    client.destroyEndpoint(ep);
  },
};

async function onMessage(m) {
  if (!m || (m.type !== ToTools.CALL && m.type !== ToTools.INIT)) return;
  try {
    const value = await methods[m.method](...m.args);
    post({ type: FromTools.RETURN, id: m.id, ok: true, value });
  } catch (e) {
    post({ type: FromTools.RETURN, id: m.id, ok: false, error: { name: e.name, message: e.message, code: e.code || 1, stack: e.stack } });
  }
  const after = afterReply;
  afterReply = [];
  for (const fn of after) fn();
}

if (port) port.on('message', onMessage);
else self.onmessage = (e) => onMessage(e.data);
