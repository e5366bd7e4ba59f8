// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The registry: process, node and endpoint records, and what removing them
 * leaves (zombie writers whose rings are drained first), and gids. Every
 * call runs under the registry lock; a record is committed by a final
 * store of its STATE word and retracted by clearing it first.
 *
 * Each function takes the thread's Bus `bus` first (bus.mjs is the face
 * callers use).
 *
 * @module bus/registry
 */

import {
  ENDPOINT, HEADER, KIND_NODE, LINK, NODE, PROC_ALIVE, PROC_DEAD, PROC_FREE, PROCESS, QOS,
  REC_ALIVE, REC_DYING, REC_FREE, REC_ZOMBIE, SLOT,
} from '../layout.mjs';
import { alloc, allocStrings, bytesEqual, findFree, free, memoryUsage } from './arena.mjs';
import { now } from './clock.mjs';
import { BusError, Code } from './errors.mjs';
import { match } from './matching.mjs';
import { durationMs } from '../qos.mjs';

const encoder = new TextEncoder();

function fnv1a(bytes) {
  let h = 0x811c9dc5;
  for (let i = 0; i < bytes.length; i++) {
    h ^= bytes[i];
    h = Math.imul(h, 0x01000193);
  }
  return h | 0;
}

/**
 * Register a new process (lock held).
 * @param {number} kind PROC_KIND_*
 * @returns {number} pid, or 0 when the process table is full
 */
export function allocProcess(bus, kind) {
  const i32 = bus.i32;
  const idx = findFree(bus, HEADER.PROC_HINT, HEADER.PROC_HWM, bus.procCap, (i) => bus.proc(i) + PROCESS.STATE, 1);
  if (idx < 0) return 0;
  const base = bus.proc(idx);
  i32[base + PROCESS.KIND] = kind;
  i32[base + PROCESS.SLEEPERS] = 0;
  Atomics.add(i32, base + PROCESS.GEN, 1);
  Atomics.store(i32, base + PROCESS.STATE, PROC_ALIVE);
  return idx;
}


/**
 * Create a node record (lock held).
 * @returns {{index: number, serial: number, nameTaken: boolean}}
 */
export function createNode(bus, { pid, domain, context, name, namespace, enclave }) {
  const i32 = bus.i32;
  let nameTaken = false;
  const nameBytes = encoder.encode(name);
  const nsBytes = encoder.encode(namespace);
  const hwm = i32[HEADER.NODE_HWM];
  for (let i = 0; i < hwm; i++) {
    const b = bus.node(i);
    if (Atomics.load(i32, b + NODE.STATE) !== REC_ALIVE || i32[b + NODE.DOMAIN] !== domain) continue;
    if (i32[b + NODE.NAME_LEN] === nameBytes.length && i32[b + NODE.NS_LEN] === nsBytes.length &&
        bytesEqual(bus, i32[b + NODE.STR_OFF], nameBytes) &&
        bytesEqual(bus, i32[b + NODE.STR_OFF] + nameBytes.length, nsBytes)) {
      nameTaken = true;
      break;
    }
  }
  const idx = findFree(bus, HEADER.NODE_HINT, HEADER.NODE_HWM, bus.nodeCap, (i) => bus.node(i) + NODE.STATE);
  if (idx < 0) {
    throw new BusError(Code.BAD_ALLOC, `cannot create node '${name}': the bus node table is full (${bus.nodeCap} nodes); start the Runtime with a larger maxNodes`);
  }
  const strs = allocStrings(bus, [name, namespace, enclave], pid);
  if (!strs) throw fullError(bus, `node '${name}'`);
  const b = bus.node(idx);
  const serial = Atomics.add(i32, HEADER.SERIAL, 1) + 1;
  i32[b + NODE.PID] = pid;
  i32[b + NODE.DOMAIN] = domain;
  i32[b + NODE.CONTEXT] = context;
  i32[b + NODE.SERIAL] = serial;
  i32[b + NODE.STR_OFF] = strs.off;
  i32[b + NODE.NAME_LEN] = strs.lens[0];
  i32[b + NODE.NS_LEN] = strs.lens[1];
  i32[b + NODE.ENCLAVE_LEN] = strs.lens[2];
  if (bus.faultPoint !== null) bus.faultPoint('graph.node_written');
  Atomics.store(i32, b + NODE.STATE, REC_ALIVE);
  return { index: idx, serial, nameTaken };
}

/** Remove a node record and its endpoints (lock held). Idempotent. */
export function removeNode(bus, index) {
  const i32 = bus.i32;
  const b = bus.node(index);
  const st = Atomics.load(i32, b + NODE.STATE);
  if (st === REC_FREE) return;
  Atomics.store(i32, b + NODE.STATE, REC_DYING);
  const hwm = i32[HEADER.EP_HWM];
  for (let e = 0; e < hwm; e++) {
    const eb = bus.ep(e);
    if (Atomics.load(i32, eb + ENDPOINT.STATE) !== REC_FREE && i32[eb + ENDPOINT.NODE] === index &&
        i32[eb + ENDPOINT.PID] === i32[b + NODE.PID]) {
      removeEndpoint(bus, e);
    }
  }
  free(bus, i32[b + NODE.STR_OFF]);
  Atomics.store(i32, b + NODE.STATE, REC_FREE);
}

export function fullError(bus, what) {
  const u = memoryUsage(bus);
  return new BusError(Code.BAD_ALLOC,
    `cannot create ${what}: bus memory exhausted (${u.arenaUsed} bytes in use, buffer ${u.bufferBytes} of at most ${u.maxBytes} bytes); start the Runtime with a larger maxBytes`);
}

/**
 * Create an endpoint and match it with its peers (lock held).
 * @param {object} spec
 * @param {number} spec.kind KIND_*
 * @param {number} spec.pid
 * @param {number} spec.node node index
 * @param {string} spec.name topic or service name
 * @param {string} spec.type type name
 * @param {Int32Array|number[]} spec.qos resolved wire QoS
 * @param {number} spec.flags EP_FLAG_*
 * @param {number} spec.ringSlots ring size for writers (power of two), 0 for plain readers
 * @returns {{index: number, serial: number, touched: Set<number>}} touched: pids to ring
 */
export function createEndpoint(bus, spec) {
  const i32 = bus.i32;
  const nb = bus.node(spec.node);
  if (Atomics.load(i32, nb + NODE.STATE) !== REC_ALIVE || i32[nb + NODE.PID] !== spec.pid) {
    throw new BusError(Code.INVALID_ARGUMENT, `cannot create endpoint '${spec.name}': its node (index ${spec.node}) does not exist on the bus`);
  }
  const idx = findFree(bus, HEADER.EP_HINT, HEADER.EP_HWM, bus.epCap, (i) => bus.ep(i) + ENDPOINT.STATE);
  if (idx < 0) {
    throw new BusError(Code.BAD_ALLOC, `cannot create endpoint '${spec.name}': the bus endpoint table is full (${bus.epCap} endpoints); start the Runtime with a larger maxEndpoints`);
  }
  const strs = allocStrings(bus, [spec.name, spec.type], spec.pid);
  if (!strs) throw fullError(bus, `endpoint '${spec.name}'`);
  let ring = 0;
  if (spec.ringSlots) {
    ring = alloc(bus, spec.ringSlots * SLOT.WORDS * 4, spec.pid);
    if (!ring) {
      free(bus, strs.off);
      throw fullError(bus, `endpoint '${spec.name}' (ring of ${spec.ringSlots} slots)`);
    }
    bus.i32.fill(0, ring >> 2, (ring >> 2) + spec.ringSlots * SLOT.WORDS);
  }
  const r32 = bus.i32;
  const f64 = bus.f64;
  const b = bus.ep(idx);
  r32.fill(0, b + 1, b + ENDPOINT.WORDS);
  const serial = Atomics.add(r32, HEADER.SERIAL, 1) + 1;
  const t = now();
  r32[b + ENDPOINT.KIND] = spec.kind;
  r32[b + ENDPOINT.PID] = spec.pid;
  r32[b + ENDPOINT.NODE] = spec.node;
  r32[b + ENDPOINT.DOMAIN] = r32[nb + NODE.DOMAIN];
  r32[b + ENDPOINT.CONTEXT] = r32[nb + NODE.CONTEXT];
  r32[b + ENDPOINT.SERIAL] = serial;
  r32[b + ENDPOINT.FLAGS] = spec.flags | 0;
  r32[b + ENDPOINT.STR_OFF] = strs.off;
  r32[b + ENDPOINT.NAME_LEN] = strs.lens[0];
  r32[b + ENDPOINT.TYPE_LEN] = strs.lens[1];
  r32[b + ENDPOINT.NAME_HASH] = fnv1a(encoder.encode(spec.name));
  for (let q = 0; q < QOS.WORDS; q++) r32[b + ENDPOINT.QOS + q] = spec.qos[q];
  const qw = (k) => r32[b + ENDPOINT.QOS + k];
  f64[(b + ENDPOINT.DEADLINE_MS_F64) >> 1] = durationMs(qw(QOS.DEADLINE_LO), qw(QOS.DEADLINE_HI));
  f64[(b + ENDPOINT.LIFESPAN_MS_F64) >> 1] = durationMs(qw(QOS.LIFESPAN_LO), qw(QOS.LIFESPAN_HI));
  f64[(b + ENDPOINT.LEASE_MS_F64) >> 1] = durationMs(qw(QOS.LEASE_LO), qw(QOS.LEASE_HI));
  r32[b + ENDPOINT.RING_OFF] = ring;
  r32[b + ENDPOINT.RING_SLOTS] = spec.ringSlots | 0;
  f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] = t;
  f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
  f64[(b + ENDPOINT.CREATED_F64) >> 1] = t;
  f64[(b + ENDPOINT.DEADLINE_ACCT_BASE_F64) >> 1] = t;
  f64[(b + ENDPOINT.LIVE_LOST_BASE_F64) >> 1] = t;
  const touched = new Set([spec.pid]);
  if (bus.faultPoint !== null) bus.faultPoint('graph.endpoint_written');
  Atomics.store(r32, b + ENDPOINT.STATE, REC_ALIVE);
  try {
    match(bus, idx, touched);
  } catch (e) {
    removeEndpoint(bus, idx);
    throw e;
  }
  return { index: idx, serial, touched };
}

/**
 * Remove an endpoint from the graph (lock held). Idempotent.
 *
 * A writer whose ring still holds messages some live reader has not taken
 * becomes a ZOMBIE: gone from the graph and from matching, but its ring
 * stays readable through the remaining links until they are drained (a
 * message published before the writer went away is delivered, as with
 * DDS reader caches). Otherwise the ring and its blocks are freed.
 * @param {number} index
 * @returns {Set<number>} pids of the peers that lost a match (to ring)
 */
export function removeEndpoint(bus, index) {
  const i32 = bus.i32;
  const b = bus.ep(index);
  const peers = new Set();
  const st = Atomics.load(i32, b + ENDPOINT.STATE);
  if (st === REC_FREE || st === REC_ZOMBIE) return peers;
  Atomics.store(i32, b + ENDPOINT.STATE, REC_DYING);
  const head = Atomics.load(i32, b + ENDPOINT.HEAD);
  const zombies = new Set();
  let kept = 0;
  const hwm = i32[HEADER.LINK_HWM];
  for (let l = 0; l < hwm; l++) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
    const w = i32[lb + LINK.WRITER];
    const r = i32[lb + LINK.READER];
    if (w !== index && r !== index) continue;
    const other = w === index ? r : w;
    const ob = bus.ep(other);
    peers.add(i32[ob + ENDPOINT.PID]);
    if (w === index && Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ALIVE &&
        ((head - Atomics.load(i32, lb + LINK.CURSOR)) | 0) > 0) {
      kept++;
      continue;
    }
    Atomics.store(i32, lb + LINK.STATE, REC_FREE);
    if (bus.faultPoint !== null) bus.faultPoint('graph.removing');
    if (Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ZOMBIE) zombies.add(other);
  }
  for (const z of zombies) freeZombieIfDrained(bus, z);
  if (kept) {
    Atomics.store(i32, b + ENDPOINT.STATE, REC_ZOMBIE);
    return peers;
  }
  freeEndpoint(bus, index);
  return peers;
}

export function freeEndpoint(bus, index) {
  const i32 = bus.i32;
  const b = bus.ep(index);
  const ring = i32[b + ENDPOINT.RING_OFF];
  if (ring) {
    const slots = i32[b + ENDPOINT.RING_SLOTS];
    for (let s = 0; s < slots; s++) {
      const sw = (ring >> 2) + s * SLOT.WORDS;
      Atomics.store(i32, sw + SLOT.COMMIT, 0);
      free(bus, i32[sw + SLOT.BLOCK]);
    }
    free(bus, ring);
  }
  free(bus, i32[b + ENDPOINT.STR_OFF]);
  Atomics.store(i32, b + ENDPOINT.STATE, REC_FREE);
}

/** Free a zombie writer once no link reads from it (lock held). */
export function freeZombieIfDrained(bus, index) {
  const i32 = bus.i32;
  if (Atomics.load(i32, bus.ep(index) + ENDPOINT.STATE) !== REC_ZOMBIE) return;
  const hwm = i32[HEADER.LINK_HWM];
  for (let l = 0; l < hwm; l++) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) === REC_ALIVE && i32[lb + LINK.WRITER] === index) return;
  }
  freeEndpoint(bus, index);
}

/**
 * Drop links from zombie writers that their readers have drained (lock held).
 * @param {number[]} links
 */
export function reapDrainedLinks(bus, links) {
  const i32 = bus.i32;
  const writers = new Set();
  for (const l of links) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
    const w = i32[lb + LINK.WRITER];
    const wb = bus.ep(w);
    if (Atomics.load(i32, wb + ENDPOINT.STATE) !== REC_ZOMBIE) continue;
    if (((Atomics.load(i32, wb + ENDPOINT.HEAD) - Atomics.load(i32, lb + LINK.CURSOR)) | 0) > 0) continue;
    Atomics.store(i32, lb + LINK.STATE, REC_FREE);
    writers.add(w);
  }
  for (const w of writers) freeZombieIfDrained(bus, w);
}

/**
 * Remove everything a dead process owned (lock held). Idempotent.
 * @param {number} pid
 */
export function cleanupProcess(bus, pid) {
  const i32 = bus.i32;
  const pb = bus.proc(pid);
  Atomics.store(i32, pb + PROCESS.STATE, PROC_DEAD);
  const hwm = i32[HEADER.EP_HWM];
  for (let e = 0; e < hwm; e++) {
    const eb = bus.ep(e);
    if (Atomics.load(i32, eb + ENDPOINT.STATE) !== REC_FREE && i32[eb + ENDPOINT.PID] === pid) removeEndpoint(bus, e);
  }
  const nhwm = i32[HEADER.NODE_HWM];
  for (let n = 0; n < nhwm; n++) {
    const nb = bus.node(n);
    if (Atomics.load(i32, nb + NODE.STATE) !== REC_FREE && i32[nb + NODE.PID] === pid) removeNode(bus, n);
  }
  // The record stays DEAD until nobody can be sleeping on its doorbell.
  Atomics.add(i32, pb + PROCESS.BELL, 1);
  Atomics.notify(i32, pb + PROCESS.BELL);
}

/**
 * Return a dead process' record to the free pool (lock held).
 * @param {number} pid
 */
export function releaseProcess(bus, pid) {
  const pb = bus.proc(pid);
  if (Atomics.load(bus.i32, pb + PROCESS.STATE) === PROC_DEAD) Atomics.store(bus.i32, pb + PROCESS.STATE, PROC_FREE);
}

/**
 * The 16-byte gid of an entity: bus id, pid, (kind << 24 | index), serial.
 * @returns {Int32Array}
 */
export function gidWords(bus, kind, index) {
  const i32 = bus.i32;
  const b = kind === KIND_NODE ? bus.node(index) : bus.ep(index);
  const serial = kind === KIND_NODE ? i32[b + NODE.SERIAL] : i32[b + ENDPOINT.SERIAL];
  const pid = kind === KIND_NODE ? i32[b + NODE.PID] : i32[b + ENDPOINT.PID];
  return Int32Array.of(bus.id, pid, (kind << 24) | index, serial);
}

/**
 * Find the endpoint a gid names, or -1 if it is gone.
 * @param {ArrayLike<number>} w four gid words
 */
export function endpointOfGid(bus, w) {
  if (w[0] !== bus.id) return -1;
  const index = w[2] & 0xffffff;
  const kind = w[2] >>> 24;
  if (kind === KIND_NODE || index >= bus.epCap) return -1;
  const b = bus.ep(index);
  if (Atomics.load(bus.i32, b + ENDPOINT.STATE) !== REC_ALIVE || bus.i32[b + ENDPOINT.SERIAL] !== w[3]) return -1;
  return index;
}
