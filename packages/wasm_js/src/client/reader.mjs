// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The reader side: find the next message of a reader over its links
 * (skipping what its QoS says to skip, counting what was lost), copy it
 * straight to its destination, re-validate and advance the link's cursor
 * with a CAS, so several threads can take from one reader.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/reader
 */

import {
  ENDPOINT, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, LINK, LINK_BEST_EFFORT,
  LINK_TARGETED, REC_ALIVE, REC_DYING, REC_ZOMBIE, SLOT,
} from '../layout.mjs';
import { TakeMode } from '../abi/bus_abi.mjs';
import { now } from '../bus.mjs';
import { copyBytes } from './copy.mjs';
import { readerLinks, refresh, writerInfo } from './links.mjs';
import { checkEndpoint } from './registry.mjs';

/**
 * Find the next message for reader `ep` and remember it for takeCopy().
 * Skips what the QoS says to skip (overwritten, beyond KEEP_LAST depth,
 * expired, addressed to another client) and counts lost messages.
 * @param {number} ep reader endpoint
 * @param {number} mode TakeMode
 * @returns {number} the message length, or -1 when there is none
 */
export function takeBegin(c, ep, mode) {
  const bus = c.bus;
  refresh(c);
  const links = readerLinks(c, ep);
  const i32 = bus.i32;
  const f64 = bus.f64;
  const rb = bus.ep(ep);
  let drained = null;
  let bestLink = -1;
  let bestTime = Infinity;
  let bestCursor = 0;
  let bestSlot = 0;
  for (let i = 0; i < links.length; i++) {
    const l = links[i];
    const lb = bus.link(l);
    if (i32[lb + LINK.STATE] !== REC_ALIVE) continue;
    const writer = i32[lb + LINK.WRITER];
    const wb = bus.ep(writer);
    const wstate = i32[wb + ENDPOINT.STATE];
    if (wstate !== REC_ALIVE) {
      // DYING: another thread is removing the writer under the registry
      // lock. Its ring stays intact while this link holds untaken messages
      // (it becomes a ZOMBIE), so a reader told "ready" still takes them.
      if (wstate !== REC_ZOMBIE && wstate !== REC_DYING) continue;
      if (((Atomics.load(i32, wb + ENDPOINT.HEAD) - Atomics.load(i32, lb + LINK.CURSOR)) | 0) <= 0) {
        if (wstate === REC_ZOMBIE) (drained || (drained = [])).push(l);
        continue;
      }
    }
    const slots = i32[wb + ENDPOINT.RING_SLOTS];
    const ring = i32[wb + ENDPOINT.RING_OFF] >> 2;
    const flags = i32[lb + LINK.FLAGS];
    for (let guard = 0; guard < 1 << 22; guard++) {
      const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
      const c = Atomics.load(i32, lb + LINK.CURSOR);
      const avail = (head - c) | 0;
      if (avail <= 0) break;
      let start = c;
      if (avail > slots) start = (head - slots) | 0;
      const depth = i32[lb + LINK.DEPTH];
      if (depth && ((head - start) | 0) > depth) start = (head - depth) | 0;
      if (start !== c) {
        if (Atomics.compareExchange(i32, lb + LINK.CURSOR, c, start) === c) {
          let lost;
          if (flags & LINK_BEST_EFFORT) lost = (start - c) | 0;
          else {
            // RELIABLE KEEP_LAST: only what the writer's ring dropped before the reader's depth.
            const ringFloor = (head - slots) | 0;
            const depthFloor = depth ? (head - depth) | 0 : ringFloor;
            const from = ((c - depthFloor) | 0) > 0 ? c : depthFloor;
            lost = Math.max(0, (ringFloor - from) | 0);
          }
          if (lost > 0 && !(flags & LINK_TARGETED)) Atomics.add(i32, rb + ENDPOINT.LOST_TOTAL, lost);
        }
        continue;
      }
      const sw = ring + (c & (slots - 1)) * SLOT.WORDS;
      const commit = Atomics.load(i32, sw + SLOT.COMMIT);
      if (commit !== ((c + 1) | 0)) {
        // Lapped while we looked: the writer is overwriting it. It is lost to us.
        if (Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0) === c && !(flags & LINK_TARGETED)) {
          Atomics.add(i32, rb + ENDPOINT.LOST_TOTAL, 1);
        }
        continue;
      }
      if (flags & LINK_TARGETED) {
        const target = i32[sw + SLOT.TARGET];
        const tserial = i32[sw + SLOT.TARGET_SERIAL];
        if (Atomics.load(i32, sw + SLOT.COMMIT) !== commit) continue;
        if (target !== ep + 1 || tserial !== i32[rb + ENDPOINT.SERIAL]) {
          Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0);
          continue;
        }
      }
      const t = f64[(sw + SLOT.TIME_F64) >> 1];
      const lifespan = f64[(wb + ENDPOINT.LIFESPAN_MS_F64) >> 1];
      if (lifespan !== Infinity && now() - t > lifespan) {
        if (Atomics.load(i32, sw + SLOT.COMMIT) === commit) {
          Atomics.compareExchange(i32, lb + LINK.CURSOR, c, (c + 1) | 0);
        }
        continue;
      }
      if (t < bestTime || bestLink < 0) {
        bestTime = t;
        bestLink = l;
        bestCursor = c;
        bestSlot = sw;
      }
      break;
    }
  }
  if (drained) reapDrained(c, drained);
  if (bestLink < 0) return -1;
  const st = c._t;
  const commit = (bestCursor + 1) | 0;
  st.link = bestLink;
  st.cursor = bestCursor;
  st.slot = bestSlot;
  st.commit = commit;
  st.block = i32[bestSlot + SLOT.BLOCK];
  st.len = i32[bestSlot + SLOT.LEN];
  st.reader = ep;
  st.mode = mode;
  st.writer = i32[bus.link(bestLink) + LINK.WRITER];
  if (Atomics.load(i32, bestSlot + SLOT.COMMIT) !== commit || st.len < 0 || st.len > bus.maxMessage) {
    // Torn read of a slot being overwritten: report "something may be there" with no length.
    st.len = 0;
    st.block = -1;
  }
  return st.len;
}

/** Remove links from writers that left and whose messages we took (rare). */
export function reapDrained(c, links) {
  const bus = c.bus;
  bus.lock(c.pid);
  try {
    if (bus.faultPoint !== null) bus.faultPoint('take.reaping');
    bus.reapDrainedLinks(links);
    bus.bumpGraph();
  } finally {
    bus.unlock(c.pid);
  }
}

/**
 * Copy the message found by takeBegin() to `dst` at `dstOff`, validate it
 * and consume it. On false, call takeBegin() again (it was overwritten or
 * another thread took it).
 * @param {?Uint8Array} dst destination (e.g. the wasm heap); null: the
 *   memory given to useHeapMemory(), copied with memory.copy
 * @param {number} dstOff
 * @returns {boolean}
 */
export function takeCopy(c, dst, dstOff) {
  const bus = c.bus;
  const st = c._t;
  const i32 = bus.i32;
  const sw = st.slot;
  if (st.block < 0) return false;
  // A test's fault point (bus/faults.mjs), read once: null but in the fault tests.
  const fault = bus.faultPoint;
  if (fault !== null) fault('take.found');
  const info = c.info;
  info.sourceTime = bus.f64[(sw + SLOT.TIME_F64) >> 1];
  info.pubSeqHi = i32[sw + SLOT.SEQ_HI];
  info.reqLo = i32[sw + SLOT.REQ_LO];
  info.reqHi = i32[sw + SLOT.REQ_HI];
  const len = st.len;
  if (len) {
    if (st.block + len > bus.u8.length && (!bus.refreshViews() || st.block + len > bus.u8.length)) {
      return false;
    }
    if (dst === null) c.heapCopier.fromBus(dstOff, st.block, len);
    else copyBytes(dst, dstOff, bus.u8, st.block, len);
  }
  if (Atomics.load(i32, sw + SLOT.COMMIT) !== st.commit) return false;
  if (fault !== null) fault('take.copied');
  const lb = bus.link(st.link);
  if (Atomics.compareExchange(i32, lb + LINK.CURSOR, st.cursor, (st.cursor + 1) | 0) !== st.cursor) return false;
  if (fault !== null) fault('take.consumed');
  const rb = bus.ep(st.reader);
  const wb = bus.ep(st.writer);
  info.len = len;
  info.pubSeqLo = st.commit;
  // On the bus a message enters every matched reader's history when its
  // writer commits it (the slot's time), as a DDS sample's reception
  // timestamp is taken on arrival, not on take. This also spares a clock
  // read per take (a clock read costs 90-340 ns in a Chromium worker, see bus.mjs).
  info.receivedTime = info.sourceTime;
  const lo = Atomics.add(i32, rb + ENDPOINT.RECV_SEQ_LO, 1) + 1;
  if (lo === 0) Atomics.add(i32, rb + ENDPOINT.RECV_SEQ_HI, 1);
  info.recvSeqLo = lo;
  info.recvSeqHi = i32[rb + ENDPOINT.RECV_SEQ_HI];
  info.sameProcess = i32[wb + ENDPOINT.PID] === c.pid;
  const g = info.gid;
  if (st.mode === TakeMode.RESPONSE) {
    // The request id of a response is (this client's gid, the request's number).
    g[0] = bus.id; g[1] = c.pid; g[2] = (KIND_CLIENT << 24) | st.reader; g[3] = i32[rb + ENDPOINT.SERIAL];
  } else {
    g[0] = bus.id; g[1] = i32[wb + ENDPOINT.PID]; g[2] = (i32[wb + ENDPOINT.KIND] << 24) | st.writer; g[3] = i32[wb + ENDPOINT.SERIAL];
    info.reqLo = st.commit;
    info.reqHi = info.pubSeqHi;
  }
  if (Atomics.load(i32, wb + ENDPOINT.ACK_WAITERS) > 0) ringWaitingWriter(c, wb, (st.cursor + 1) | 0);
  return true;
}

/**
 * Wake the writer's threads that wait for room or for acknowledgements,
 * once this reader's cursor is `next`. Woken per message, a writer that is
 * faster than its reader would sleep and wake once per message (a futex
 * call on both sides each time); so the reader rings when it has taken
 * everything, or each time it has freed an eighth of the ring. A writer
 * also looks again every ACK_RECHECK_MS, for a reader that stops between.
 */
export function ringWaitingWriter(c, wb, next) {
  const i32 = c.bus.i32;
  const slots = i32[wb + ENDPOINT.RING_SLOTS];
  const step = slots >= 8 ? slots >> 3 : 1;
  if ((next & (step - 1)) === 0 || ((Atomics.load(i32, wb + ENDPOINT.HEAD) - next) | 0) <= 0) {
    c.bus.ring(i32[wb + ENDPOINT.PID]);
  }
}

/**
 * Take the next message as a new Uint8Array (JS callers).
 * @param {number} ep reader endpoint
 * @param {number} [mode] TakeMode
 * @returns {Uint8Array|null} null when there is none; the client's info describes it
 */
export function take(c, ep, mode = TakeMode.MESSAGE) {
  const kinds = [KIND_SUBSCRIPTION, KIND_SERVICE, KIND_CLIENT];
  checkEndpoint(c, ep, kinds[mode], 'take');
  for (;;) {
    const len = takeBegin(c, ep, mode);
    if (len < 0) return null;
    const out = new Uint8Array(len);
    if (takeCopy(c, out, 0)) return out;
  }
}

/** True when reader `ep` has a message to take now. */
export function hasData(c, ep) {
  return takeBegin(c, ep, 0) >= 0;
}

/** Number of live matched peers (publisher: readers; subscription: writers). */
export function matchedCount(c, ep) {
  const bus = c.bus;
  const i32 = bus.i32;
  const b = checkEndpoint(c, ep, 0, 'matched_count');
  refresh(c);
  const kind = i32[b + ENDPOINT.KIND];
  const links = kind === KIND_PUBLISHER || kind === KIND_CLIENT ? writerInfo(c, ep).links : readerLinks(c, ep);
  let n = 0;
  for (let i = 0; i < links.length; i++) {
    const lb = bus.link(links[i]);
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
    const other = i32[lb + LINK.WRITER] === ep ? i32[lb + LINK.READER] : i32[lb + LINK.WRITER];
    const ob = bus.ep(other);
    if (Atomics.load(i32, ob + ENDPOINT.STATE) === REC_ALIVE && bus.processAlive(i32[ob + ENDPOINT.PID])) n++;
  }
  return n;
}

/** True when a client has at least one live matched server. */
export function serverAvailable(c, ep) {
  checkEndpoint(c, ep, KIND_CLIENT, 'service_server_is_available');
  return matchedCount(c, ep) > 0;
}
