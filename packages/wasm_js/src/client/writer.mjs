// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The writer side: publish and send_response commit a message into a slot
 * of the endpoint's ring under its writer lock (seqlock: COMMIT = ~(n+1)
 * while writing, n+1 when done), advance HEAD, and ring the matched
 * readers' processes. A RELIABLE KEEP_ALL reader that has not taken the
 * slot's old message makes the writer wait; wait_for_all_acked and
 * liveliness assertions live here too.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/writer
 */

import {
  ENDPOINT, HEADER, KIND_SERVICE, LINK, LINK_BEST_EFFORT, LINK_TARGETED, NODE, REC_ALIVE, SLOT,
} from '../layout.mjs';
import { BusError, Code, now } from '../bus.mjs';
import { lock, unlock } from '../bus/lock.mjs';
import { copyBytes } from './copy.mjs';
import { refresh, writerInfo } from './links.mjs';
import { checkEndpoint, checkNode, endpointName, KIND_NAMES } from './registry.mjs';
import { sleep } from './wait.mjs';

/** A writer blocked on a full ring looks again at least this often (ms). */
const ACK_RECHECK_MS = 1;

function describeValue(v) {
  if (v === null) return 'null';
  if (ArrayBuffer.isView(v)) return v.constructor.name;
  return typeof v === 'object' ? Object.prototype.toString.call(v) : typeof v;
}

/**
 * Publish bytes (publisher) or send a request (client).
 * @param {number} ep writer endpoint
 * @param {Uint8Array} src payload (may be a view of a wasm heap)
 * @param {number} timeoutMs how long to block on a full KEEP_ALL reader (< 0: forever)
 * @returns {number} the message's sequence number (1, 2, ...)
 */
export function publish(c, ep, src, timeoutMs = -1) {
  if (!(src instanceof Uint8Array)) badPayload(c, ep, src, 'publish');
  return write(c, ep, src, 0, src.length, timeoutMs, 0, 0, 0, 0, 'publish');
}

/**
 * Publish `len` bytes at `offset` of `heap` (e.g. a wasm heap) without
 * creating a view of them; `heap` null: of the memory given to
 * useHeapMemory(), copied with memory.copy.
 * @returns {number} the message's sequence number
 */
export function publishFrom(c, ep, heap, offset, len, timeoutMs = -1) {
  return write(c, ep, heap, offset, len, timeoutMs, 0, 0, 0, 0, 'publish');
}

export function badPayload(c, ep, src, op) {
  checkEndpoint(c, ep, 0, op);
  throw new BusError(Code.INVALID_ARGUMENT,
    `${op} on '${endpointName(c, ep)}' failed: the payload must be a Uint8Array, got ${describeValue(src)}`);
}

/**
 * Send a response (service) to the client named by `gid`.
 * @param {number} ep service endpoint
 * @param {ArrayLike<number>} gid the request id's client gid (4 words)
 * @param {number} seqLo request sequence number, low word
 * @param {number} seqHi request sequence number, high word
 * @param {Uint8Array} src payload
 * @param {number} timeoutMs
 * @returns {boolean} false when the client is gone (response dropped)
 */
export function sendResponse(c, ep, gid, seqLo, seqHi, src, timeoutMs = -1) {
  checkEndpoint(c, ep, KIND_SERVICE, 'send_response');
  const target = c.bus.endpointOfGid(gid);
  if (target < 0) return false;
  if (!(src instanceof Uint8Array)) badPayload(c, ep, src, 'send_response');
  const serial = c.bus.i32[c.bus.ep(target) + ENDPOINT.SERIAL];
  write(c, ep, src, 0, src.length, timeoutMs, target + 1, serial, seqLo, seqHi, 'send_response');
  return true;
}

export function write(c, ep, src, srcOff, len, timeoutMs, target, targetSerial, reqLo, reqHi, op) {
  const bus = c.bus;
  const b = checkEndpoint(c, ep, 0, op);
  if (len > bus.maxMessage) {
    throw new BusError(Code.BAD_ALLOC,
      `${op} on '${endpointName(c, ep)}' failed: message of ${len} bytes exceeds the bus maximum of ${bus.maxMessage} bytes (Runtime option maxMessageBytes)`);
  }
  refresh(c);
  const w = writerInfo(c, ep);
  let i32 = bus.i32;
  const slots = i32[b + ENDPOINT.RING_SLOTS];
  const ring = i32[b + ENDPOINT.RING_OFF] >> 2;
  lock(c.bus.i32, b + ENDPOINT.WLOCK, c.pid);
  // A test's fault point (bus/faults.mjs), read once: null but in the fault tests.
  const fault = bus.faultPoint;
  let seq;
  try {
    const n = i32[b + ENDPOINT.HEAD]; // only writers (under WLOCK) store it
    const sw = ring + (n & (slots - 1)) * SLOT.WORDS;
    // Before overwriting message n - slots, every blocking reader must have taken it.
    if (w.blocking.length && i32[sw + SLOT.COMMIT] === ((n - slots + 1) | 0) &&
        !takenByAll(c, w, (n - slots) | 0, n) && blockingReader(c, w, (n - slots) | 0, sw) >= 0) {
      awaitSlot(c, ep, b, w, n, slots, sw, timeoutMs, op);
    }
    if (fault !== null) fault('publish.locked');
    i32 = bus.i32;
    Atomics.store(i32, sw + SLOT.COMMIT, ~(n + 1));
    let block = i32[sw + SLOT.BLOCK];
    if (i32[sw + SLOT.CAP] < len || block === 0) {
      block = bus.renewSlotBlock(sw, Math.max(len, 64), c.pid);
      i32 = bus.i32;
      if (!block) {
        const u = bus.memoryUsage();
        throw new BusError(Code.BAD_ALLOC,
          `${op} on '${endpointName(c, ep)}' failed: bus memory exhausted (${len} bytes needed, ${u.arenaUsed} in use, at most ${u.maxBytes}); start the Runtime with a larger maxBytes or use smaller histories`);
      }
    }
    if (block + len > bus.u8.length) bus.refreshViews();
    if (len) {
      if (src === null) c.heapCopier.toBus(block, srcOff, len);
      else copyBytes(bus.u8, block, src, srcOff, len);
    }
    const t = now();
    const hi = i32[b + ENDPOINT.HEAD_HI] + (((n + 1) | 0) === 0 ? 1 : 0);
    i32[sw + SLOT.LEN] = len;
    i32[sw + SLOT.SEQ_HI] = hi;
    i32[sw + SLOT.TARGET] = target;
    i32[sw + SLOT.TARGET_SERIAL] = targetSerial;
    i32[sw + SLOT.REQ_LO] = reqLo;
    i32[sw + SLOT.REQ_HI] = reqHi;
    bus.f64[(sw + SLOT.TIME_F64) >> 1] = t;
    if (fault !== null) fault('publish.writing');
    Atomics.store(i32, sw + SLOT.COMMIT, (n + 1) | 0);
    if (fault !== null) fault('publish.committed');
    if (((n + 1) | 0) === 0) i32[b + ENDPOINT.HEAD_HI] = hi;
    Atomics.store(i32, b + ENDPOINT.HEAD, (n + 1) | 0);
    bus.f64[(b + ENDPOINT.LAST_PUB_F64) >> 1] = t;
    bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
    seq = hi * 4294967296 + ((n + 1) >>> 0);
  } finally {
    unlock(c.bus.i32, b + ENDPOINT.WLOCK, c.pid);
  }
  if (fault !== null) fault('publish.unrung');
  const pids = w.pids;
  for (let i = 0; i < pids.length; i++) bus.ring(pids[i]);
  return seq;
}

/** Block until slot `sw` (about to hold message n) was taken by every blocking reader. */
export function awaitSlot(c, ep, b, w, n, slots, sw, timeoutMs, op) {
  const bus = c.bus;
  const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
  const old = (n - slots) | 0;
  let waiting = false;
  Atomics.add(bus.i32, c.sleepersIndex, 1);
  try {
    for (;;) {
      const i32 = bus.i32;
      const bell = Atomics.load(i32, c.bellIndex);
      if (c.service) c.service();
      // The slot holds message `old` only if it was committed (ring not yet wrapped otherwise).
      if (Atomics.load(i32, sw + SLOT.COMMIT) !== ((old + 1) | 0)) return;
      const blocker = blockingReader(c, w, old, sw);
      if (blocker < 0) return;
      if (!waiting) {
        Atomics.add(i32, b + ENDPOINT.ACK_WAITERS, 1);
        waiting = true;
        continue; // re-check after announcing ourselves (see module comment)
      }
      const t = now();
      if (t >= deadline) {
        const rb = bus.ep(i32[bus.link(blocker) + LINK.READER]);
        const rnode = bus.node(i32[rb + ENDPOINT.NODE]);
        const rname = bus.readString(i32[rnode + NODE.STR_OFF], i32[rnode + NODE.NAME_LEN]);
        throw new BusError(Code.TIMEOUT,
          `${op} on '${endpointName(c, ep)}' timed out after ${timeoutMs} ms: the ${KIND_NAMES[i32[rb + ENDPOINT.KIND]]} of node '${rname}' has not taken its oldest pending message and the writer's history of ${slots} messages is full (RELIABLE KEEP_ALL never drops); the message was not sent`);
      }
      if (bus.faultPoint !== null) bus.faultPoint('publish.blocked');
      // Readers ring only every eighth of the ring (_ringWaitingWriter): look again meanwhile.
      sleep(c, bell, Math.min(deadline - t, ACK_RECHECK_MS));
      refresh(c);
      w = writerInfo(c, ep);
    }
  } finally {
    if (waiting) Atomics.sub(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
    Atomics.sub(bus.i32, c.sleepersIndex, 1);
  }
}

/**
 * True when every blocking reader is known to have taken message `old`.
 * Readers' cursors only move forward, so the lowest cursor seen is a floor
 * that stays true; it is read again only when `old` reaches it (about once
 * per ring of messages), so the writer does not pull the readers' cursor
 * lines across cores on every publish.
 */
export function takenByAll(c, w, old, head) {
  if (w.floorValid && ((old - w.floor) | 0) < 0) return true;
  const bus = c.bus;
  const i32 = bus.i32;
  const blocking = w.blocking;
  let low = 0; // cursors relative to head: all <= 0
  for (let i = 0; i < blocking.length; i++) {
    const lb = bus.link(blocking[i]);
    const rel = (Atomics.load(i32, lb + LINK.CURSOR) - head) | 0;
    if (rel < low) low = rel;
  }
  w.floor = (head + low) | 0;
  w.floorValid = true;
  return ((old - w.floor) | 0) < 0;
}

/** The first blocking link that has not taken message `old` (in slot sw), or -1. */
export function blockingReader(c, w, old, sw) {
  const bus = c.bus;
  const i32 = bus.i32;
  const blocking = w.blocking;
  for (let i = 0; i < blocking.length; i++) {
    const lb = bus.link(blocking[i]);
    const c = Atomics.load(i32, lb + LINK.CURSOR);
    if (((old - c) | 0) < 0) continue; // taken
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
    const reader = i32[lb + LINK.READER];
    const rb = bus.ep(reader);
    if ((i32[lb + LINK.FLAGS] & LINK_TARGETED) &&
        (i32[sw + SLOT.TARGET] !== reader + 1 || i32[sw + SLOT.TARGET_SERIAL] !== i32[rb + ENDPOINT.SERIAL])) continue;
    if (!bus.processAlive(i32[rb + ENDPOINT.PID])) continue;
    return blocking[i];
  }
  return -1;
}

/**
 * Block until every matched RELIABLE reader took every message so far.
 * @returns {boolean} false on timeout
 */
export function waitForAllAcked(c, ep, timeoutMs) {
  const bus = c.bus;
  const b = checkEndpoint(c, ep, 0, 'wait_for_all_acked');
  const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
  Atomics.add(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
  Atomics.add(bus.i32, c.sleepersIndex, 1);
  try {
    for (;;) {
      const i32 = bus.i32;
      const bell = Atomics.load(i32, c.bellIndex);
      if (c.service) c.service();
      refresh(c);
      const w = writerInfo(c, ep);
      const head = Atomics.load(i32, b + ENDPOINT.HEAD);
      const slots = i32[b + ENDPOINT.RING_SLOTS];
      let pending = false;
      for (let i = 0; i < w.links.length && !pending; i++) {
        const lb = bus.link(w.links[i]);
        if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
        if (i32[lb + LINK.FLAGS] & (LINK_BEST_EFFORT | LINK_TARGETED)) continue;
        if (!bus.processAlive(i32[bus.ep(i32[lb + LINK.READER]) + ENDPOINT.PID])) continue;
        const c = Atomics.load(i32, lb + LINK.CURSOR);
        // Messages the reader can no longer take (ring lapped, or beyond its depth) count as acked.
        let floor = (head - slots) | 0;
        const depth = i32[lb + LINK.DEPTH];
        if (depth && ((head - depth - floor) | 0) > 0) floor = (head - depth) | 0;
        const from = ((c - floor) | 0) > 0 ? c : floor;
        if (((head - from) | 0) > 0) pending = true;
      }
      if (!pending) return true;
      const t = now();
      if (t >= deadline) return false;
      sleep(c, bell, Math.min(deadline - t, ACK_RECHECK_MS));
    }
  } finally {
    Atomics.sub(bus.i32, b + ENDPOINT.ACK_WAITERS, 1);
    Atomics.sub(bus.i32, c.sleepersIndex, 1);
  }
}

/** Assert the liveliness of a publisher, or of every publisher of a node (ep = -1 - node). */
export function assertLiveliness(c, ep) {
  const bus = c.bus;
  const t = now();
  if (ep >= 0) {
    const b = checkEndpoint(c, ep, 0, 'assert_liveliness');
    bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
  } else {
    const node = -1 - ep;
    checkNode(c, node);
    const i32 = bus.i32;
    const hwm = Atomics.load(i32, HEADER.EP_HWM);
    for (let e = 0; e < hwm; e++) {
      const b = bus.ep(e);
      if (Atomics.load(i32, b + ENDPOINT.STATE) === REC_ALIVE && i32[b + ENDPOINT.PID] === c.pid &&
          i32[b + ENDPOINT.NODE] === node) bus.f64[(b + ENDPOINT.LAST_ASSERT_F64) >> 1] = t;
    }
  }
  // Readers compute liveliness lazily: make them re-check.
  if (ep >= 0) {
    refresh(c);
    const pids = writerInfo(c, ep).pids;
    for (let i = 0; i < pids.length; i++) bus.ring(pids[i]);
  } else {
    bus.ringAll();
  }
}
