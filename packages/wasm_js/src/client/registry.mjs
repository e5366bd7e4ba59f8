// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Creating and removing this process' nodes and endpoints (checked, then
 * done under the registry lock, then every process is rung), and the
 * checks that a handle names a live entity of this process.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/registry
 */

import {
  ENDPOINT, EP_FLAG_IGNORE_LOCAL, HEADER, KIND_CLIENT, KIND_NODE, KIND_SERVICE, KIND_SUBSCRIPTION,
  NODE, QOS, REC_ALIVE,
} from '../layout.mjs';
import { BusError, Code, MAX_RING_SLOTS, nextPow2 } from '../bus.mjs';
import { encodeQos, History, resolveQos, validateQos } from '../qos.mjs';

// A ROS name ('/chatter', '/ns/topic'), or a native one without the leading
// slash ('chatter'): rmw_wasm_cpp passes those for avoid_ros_namespace_conventions,
// as DDS middlewares use the name as given; the two never match each other.
const NAME_RE = /^\/?[A-Za-z_~{}][A-Za-z0-9_~{}]*(?:\/[A-Za-z_~{}][A-Za-z0-9_~{}]*)*$/;
const NODE_NAME_RE = /^[A-Za-z_][A-Za-z0-9_]*$/;
const NAMESPACE_RE = /^\/(?:[A-Za-z_][A-Za-z0-9_]*(?:\/[A-Za-z_][A-Za-z0-9_]*)*)?$/;
const TYPE_RE = /^[A-Za-z_][A-Za-z0-9_]*(?:\/[A-Za-z_][A-Za-z0-9_]*)*$/;

/** Endpoint kind names, for messages. */
export const KIND_NAMES = { 1: 'publisher', 2: 'subscription', 3: 'service', 4: 'client' };

export function mutate(c, fn) {
  const bus = c.bus;
  bus.lock(c.pid);
  let result;
  try {
    if (bus.faultPoint !== null) bus.faultPoint('graph.locked');
    result = fn();
    if (bus.faultPoint !== null) bus.faultPoint('graph.changed');
  } finally {
    bus.bumpGraph();
    bus.unlock(c.pid);
  }
  bus.ringAll();
  return result;
}

/** A bus-wide unique context id. */
export function createContext(c) {
  return Atomics.add(c.bus.i32, HEADER.SERIAL, 1) + 1;
}

/**
 * Create a node.
 * @returns {{index: number, gid: Int32Array, nameTaken: boolean}}
 */
export function createNode(c, { domain = 0, context = 0, name, namespace = '/', enclave = '/' }) {
  if (typeof name !== 'string' || !NODE_NAME_RE.test(name) || name.length > 255) {
    throw new BusError(Code.INVALID_ARGUMENT,
      `invalid node name ${JSON.stringify(name)}: must start with a letter or '_' and contain only letters, digits and '_'`);
  }
  if (typeof namespace !== 'string' || !NAMESPACE_RE.test(namespace) || namespace.length > 255) {
    throw new BusError(Code.INVALID_ARGUMENT,
      `invalid namespace ${JSON.stringify(namespace)} for node '${name}': must be '/' or absolute like '/robot1', with tokens of letters, digits and '_'`);
  }
  if (!Number.isInteger(domain) || domain < 0 || domain > 0x7fffffff) {
    throw new BusError(Code.INVALID_ARGUMENT, `invalid domain id ${domain} for node '${name}'`);
  }
  const r = mutate(c, () => c.bus.createNode({
    pid: c.pid, domain, context, name, namespace, enclave: enclave || '/',
  }));
  return { index: r.index, gid: c.bus.gidWords(KIND_NODE, r.index), nameTaken: r.nameTaken };
}

/** Remove a node (and its endpoints). */
export function destroyNode(c, index) {
  checkNode(c, index);
  mutate(c, () => c.bus.removeNode(index));
}

export function checkNode(c, index) {
  const b = c.bus.node(index);
  if (!Number.isInteger(index) || index < 0 || index >= c.bus.nodeCap ||
      Atomics.load(c.bus.i32, b + NODE.STATE) !== REC_ALIVE || c.bus.i32[b + NODE.PID] !== c.pid) {
    throw new BusError(Code.INVALID_ARGUMENT, `node handle ${index} does not name a live node of c process`);
  }
}

/**
 * Create a publisher, subscription, service or client.
 * @param {object} spec
 * @param {number} spec.kind KIND_PUBLISHER / KIND_SUBSCRIPTION / KIND_SERVICE / KIND_CLIENT
 * @param {number} spec.node node index
 * @param {string} spec.name fully qualified topic or service name
 * @param {string} spec.type type name, e.g. 'std_msgs/msg/String'
 * @param {Int32Array|object} [spec.qos] wire QoS words or a QosProfile object
 * @param {boolean} [spec.ignoreLocal] subscriptions: skip publishers of the same context
 * @param {number} [spec.keepAllDepth=1000] ring size of KEEP_ALL writers
 * @returns {{index: number, gid: Int32Array, qos: Int32Array}}
 */
export function createEndpoint(c, spec) {
  const kind = spec.kind;
  const what = KIND_NAMES[kind];
  if (!what) throw new BusError(Code.INVALID_ARGUMENT, `invalid endpoint kind ${kind}`);
  const name = spec.name;
  if (typeof name !== 'string' || name.length > 1024 || !NAME_RE.test(name) || name === '/') {
    const noun = kind === KIND_SERVICE || kind === KIND_CLIENT ? 'service' : 'topic';
    throw new BusError(Code.INVALID_ARGUMENT,
      `cannot create ${what}: invalid ${noun} name ${JSON.stringify(name)} (must be like '/chatter', or 'chatter' for a native name: tokens of letters, digits and '_' not starting with a digit)`);
  }
  if (typeof spec.type !== 'string' || !TYPE_RE.test(spec.type) || spec.type.length > 1024) {
    throw new BusError(Code.INVALID_ARGUMENT,
      `cannot create ${what} on '${name}': invalid type name ${JSON.stringify(spec.type)} (expected e.g. 'std_msgs/msg/String')`);
  }
  checkNode(c, spec.node);
  const qos = spec.qos instanceof Int32Array ? Int32Array.from(spec.qos) : encodeQos(spec.qos || {});
  const bad = validateQos(qos);
  if (bad) throw new BusError(Code.INVALID_ARGUMENT, `cannot create ${what} on '${name}': ${bad}`);
  resolveQos(qos);
  let ringSlots = 0;
  if (kind !== KIND_SUBSCRIPTION) {
    const keepAll = spec.keepAllDepth === undefined ? 1000 : spec.keepAllDepth;
    const depth = qos[QOS.HISTORY] === History.KEEP_ALL ? keepAll : qos[QOS.DEPTH];
    if (!(depth >= 1) || depth > MAX_RING_SLOTS) {
      throw new BusError(Code.INVALID_ARGUMENT,
        `cannot create ${what} on '${name}': history depth ${depth} is out of range 1..${MAX_RING_SLOTS}`);
    }
    ringSlots = nextPow2(depth);
  }
  const flags = spec.ignoreLocal ? EP_FLAG_IGNORE_LOCAL : 0;
  const r = mutate(c, () => c.bus.createEndpoint({
    kind, pid: c.pid, node: spec.node, name, type: spec.type, qos, flags, ringSlots,
  }));
  return { index: r.index, gid: c.bus.gidWords(kind, r.index), qos };
}

/** Remove an endpoint. */
export function destroyEndpoint(c, index) {
  checkEndpoint(c, index, 0, 'destroy');
  mutate(c, () => c.bus.removeEndpoint(index));
}

export function checkEndpoint(c, index, kind, op) {
  const bus = c.bus;
  if (!Number.isInteger(index) || index < 0 || index >= bus.epCap) {
    throw new BusError(Code.INVALID_ARGUMENT, `${op}: invalid endpoint handle ${index}`);
  }
  const b = bus.ep(index);
  const i32 = bus.i32;
  if (i32[b + ENDPOINT.STATE] !== REC_ALIVE || i32[b + ENDPOINT.PID] !== c.pid || (kind && i32[b + ENDPOINT.KIND] !== kind)) {
    throw new BusError(Code.INVALID_ARGUMENT,
      `${op}: endpoint handle ${index} does not name a live ${kind ? KIND_NAMES[kind] : 'endpoint'} of c process`);
  }
  return b;
}

/** The topic/service name of an endpoint (for messages). */
export function endpointName(c, index) {
  const bus = c.bus;
  const b = bus.ep(index);
  return bus.readString(bus.i32[b + ENDPOINT.STR_OFF], bus.i32[b + ENDPOINT.NAME_LEN]);
}
