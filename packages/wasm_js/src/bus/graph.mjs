// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The graph: a consistent snapshot of the nodes and endpoints of the
 * registry, read without the lock (retried while the graph version moves).
 *
 * Each function takes the thread's Bus `bus` first (bus.mjs is the face
 * callers use).
 *
 * @module bus/graph
 */

import { ENDPOINT, HEADER, KIND_NODE, NODE, REC_ALIVE } from '../layout.mjs';
import { readString } from './arena.mjs';
import { gidWords } from './registry.mjs';
import { qosWords } from './matching.mjs';
import { decodeQos } from '../qos.mjs';

/**
 * A consistent snapshot of the graph.
 * @param {object} [filter]
 * @param {number} [filter.domain] only this domain
 * @returns {{version: number, nodes: object[], endpoints: object[]}}
 */
export function snapshot(bus, filter = {}) {
  for (let attempt = 0; ; attempt++) {
    const v1 = bus.graphVersion();
    const snap = readGraph(bus, filter);
    const v2 = bus.graphVersion();
    if (v1 === v2 || attempt > 100) {
      snap.version = v2;
      return snap;
    }
  }
}

export function readGraph(bus, filter) {
  bus.refreshViews();
  const i32 = bus.i32;
  const nodes = [];
  const byIndex = new Map();
  const nhwm = Atomics.load(i32, HEADER.NODE_HWM);
  for (let n = 0; n < nhwm; n++) {
    const b = bus.node(n);
    if (Atomics.load(i32, b + NODE.STATE) !== REC_ALIVE) continue;
    const domain = i32[b + NODE.DOMAIN];
    if (filter.domain !== undefined && domain !== filter.domain) continue;
    const off = i32[b + NODE.STR_OFF];
    const nl = i32[b + NODE.NAME_LEN];
    const sl = i32[b + NODE.NS_LEN];
    const node = {
      index: n,
      name: readString(bus, off, nl),
      namespace: readString(bus, off + nl, sl),
      enclave: readString(bus, off + nl + sl, i32[b + NODE.ENCLAVE_LEN]),
      domain,
      pid: i32[b + NODE.PID],
      gid: gidWords(bus, KIND_NODE, n),
    };
    nodes.push(node);
    byIndex.set(n, node);
  }
  const endpoints = [];
  const ehwm = Atomics.load(i32, HEADER.EP_HWM);
  const kinds = { 1: 'publisher', 2: 'subscription', 3: 'service', 4: 'client' };
  for (let e = 0; e < ehwm; e++) {
    const b = bus.ep(e);
    if (Atomics.load(i32, b + ENDPOINT.STATE) !== REC_ALIVE) continue;
    const domain = i32[b + ENDPOINT.DOMAIN];
    if (filter.domain !== undefined && domain !== filter.domain) continue;
    const node = byIndex.get(i32[b + ENDPOINT.NODE]);
    if (!node) continue;
    const off = i32[b + ENDPOINT.STR_OFF];
    const nl = i32[b + ENDPOINT.NAME_LEN];
    const qos = Int32Array.from(qosWords(bus, e));
    endpoints.push({
      index: e,
      kind: i32[b + ENDPOINT.KIND],
      kindName: kinds[i32[b + ENDPOINT.KIND]],
      name: readString(bus, off, nl),
      type: readString(bus, off + nl, i32[b + ENDPOINT.TYPE_LEN]),
      node: node.name,
      namespace: node.namespace,
      domain,
      pid: i32[b + ENDPOINT.PID],
      gid: gidWords(bus, i32[b + ENDPOINT.KIND], e),
      qosWords: qos,
      qos: decodeQos(qos),
    });
  }
  return { nodes, endpoints };
}

/** A gid (4 words) in hex, byte by byte (as Runtime.graph() spells it). */
function hex(words) {
  return Array.from(new Uint8Array(Int32Array.from(words).buffer), (b) => b.toString(16).padStart(2, '0')).join('');
}

/**
 * The graph of a snapshot as Runtime.graph() gives it: nodes, and topics and
 * services (per domain, by name) with their types and endpoints.
 * @param {{version: number, nodes: object[], endpoints: object[]}} snap snapshot()'s result
 * @param {function(number): string} [processName] a process' name by its id
 * @returns {{version: number, nodes: object[], topics: object[], services: object[]}}
 */
export function graphOf(snap, processName = () => '') {
  const nodes = snap.nodes.map((n) => ({
    name: n.name, namespace: n.namespace, enclave: n.enclave, domain: n.domain, pid: n.pid,
    process: processName(n.pid), gid: hex(n.gid),
  }));
  const topics = new Map();
  const services = new Map();
  for (const e of snap.endpoints) {
    const isTopic = e.kind === 1 || e.kind === 2;
    const map = isTopic ? topics : services;
    const key = `${e.domain}\u0000${e.name}`;
    let entry = map.get(key);
    if (!entry) {
      entry = isTopic
        ? { name: e.name, domain: e.domain, types: [], publishers: [], subscriptions: [] }
        : { name: e.name, domain: e.domain, types: [], servers: [], clients: [] };
      map.set(key, entry);
    }
    if (!entry.types.includes(e.type)) entry.types.push(e.type);
    const ep = { node: e.node, namespace: e.namespace, type: e.type, gid: hex(e.gid), qos: e.qos, pid: e.pid };
    ({ 1: entry.publishers, 2: entry.subscriptions, 3: entry.servers, 4: entry.clients })[e.kind].push(ep);
  }
  const byName = (a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : a.domain - b.domain);
  return {
    version: snap.version,
    nodes: nodes.sort((a, b) => (a.namespace + a.name < b.namespace + b.name ? -1 : 1)),
    topics: [...topics.values()].sort(byName),
    services: [...services.values()].sort(byName),
  };
}
