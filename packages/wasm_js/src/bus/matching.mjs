// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Matching: which endpoints of a new one's domain it pairs with (same name
 * and type, compatible QoS), and the link record of each pair, with the
 * reader's starting cursor (a TRANSIENT_LOCAL late joiner starts in the
 * writer's retained history). Under the registry lock.
 *
 * Each function takes the thread's Bus `bus` first (bus.mjs is the face
 * callers use).
 *
 * @module bus/matching
 */

import {
  ENDPOINT, EP_FLAG_IGNORE_LOCAL, HEADER, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE,
  KIND_SUBSCRIPTION, LINK, LINK_BEST_EFFORT, LINK_BLOCKING, LINK_TARGETED, QOS, REC_ALIVE,
} from '../layout.mjs';
import { findFree } from './arena.mjs';
import { BusError, Code } from './errors.mjs';
import { checkCompatible, Durability, History, Reliability } from '../qos.mjs';

/** True when endpoint `a` and `b` use the same name (byte compare). */
export function sameName(bus, a, b) {
  const i32 = bus.i32;
  const ab = bus.ep(a);
  const bb = bus.ep(b);
  if (i32[ab + ENDPOINT.NAME_HASH] !== i32[bb + ENDPOINT.NAME_HASH] || i32[ab + ENDPOINT.NAME_LEN] !== i32[bb + ENDPOINT.NAME_LEN]) return false;
  const ao = i32[ab + ENDPOINT.STR_OFF];
  const bo = i32[bb + ENDPOINT.STR_OFF];
  const u8 = bus.u8;
  for (let i = 0, n = i32[ab + ENDPOINT.NAME_LEN]; i < n; i++) if (u8[ao + i] !== u8[bo + i]) return false;
  return true;
}

export function sameType(bus, a, b) {
  const i32 = bus.i32;
  const ab = bus.ep(a);
  const bb = bus.ep(b);
  const n = i32[ab + ENDPOINT.TYPE_LEN];
  if (n !== i32[bb + ENDPOINT.TYPE_LEN]) return false;
  const ao = i32[ab + ENDPOINT.STR_OFF] + i32[ab + ENDPOINT.NAME_LEN];
  const bo = i32[bb + ENDPOINT.STR_OFF] + i32[bb + ENDPOINT.NAME_LEN];
  const u8 = bus.u8;
  for (let i = 0; i < n; i++) if (u8[ao + i] !== u8[bo + i]) return false;
  return true;
}

export function qosWords(bus, idx) {
  const b = bus.ep(idx) + ENDPOINT.QOS;
  return bus.i32.subarray(b, b + QOS.WORDS);
}

export function match(bus, idx, touched) {
  const i32 = bus.i32;
  const b = bus.ep(idx);
  const kind = i32[b + ENDPOINT.KIND];
  const domain = i32[b + ENDPOINT.DOMAIN];
  const hwm = i32[HEADER.EP_HWM];
  for (let o = 0; o < hwm; o++) {
    if (o === idx) continue;
    const ob = bus.ep(o);
    if (Atomics.load(i32, ob + ENDPOINT.STATE) !== REC_ALIVE || i32[ob + ENDPOINT.DOMAIN] !== domain) continue;
    const okind = i32[ob + ENDPOINT.KIND];
    let writer;
    let reader;
    if (kind === KIND_PUBLISHER && okind === KIND_SUBSCRIPTION) [writer, reader] = [idx, o];
    else if (kind === KIND_SUBSCRIPTION && okind === KIND_PUBLISHER) [writer, reader] = [o, idx];
    else if ((kind === KIND_CLIENT && okind === KIND_SERVICE) ||
             (kind === KIND_SERVICE && okind === KIND_CLIENT)) {
      if (!sameName(bus, idx, o) || !sameType(bus, idx, o)) continue;
      const client = kind === KIND_CLIENT ? idx : o;
      const service = kind === KIND_CLIENT ? o : idx;
      if (!checkCompatible(qosWords(bus, client), qosWords(bus, service)).ok ||
          !checkCompatible(qosWords(bus, service), qosWords(bus, client)).ok) continue;
      addLink(bus, client, service, LINK_BLOCKING);
      if (bus.faultPoint !== null) bus.faultPoint('graph.matching');
      addLink(bus, service, client, LINK_BLOCKING | LINK_TARGETED);
      touched.add(i32[ob + ENDPOINT.PID]);
      continue;
    } else continue;
    if (!sameName(bus, idx, o) || !sameType(bus, idx, o)) continue;
    const wb = bus.ep(writer);
    const rb = bus.ep(reader);
    if ((i32[rb + ENDPOINT.FLAGS] & EP_FLAG_IGNORE_LOCAL) && i32[rb + ENDPOINT.CONTEXT] === i32[wb + ENDPOINT.CONTEXT]) continue;
    const c = checkCompatible(qosWords(bus, writer), qosWords(bus, reader));
    touched.add(i32[ob + ENDPOINT.PID]);
    if (!c.ok) {
      for (const e of [wb, rb]) {
        // The policy first: a waiter woken by the total reads the policy it names.
        Atomics.store(i32, e + ENDPOINT.INCOMPAT_POLICY, c.policy);
        Atomics.add(i32, e + ENDPOINT.INCOMPAT_TOTAL, 1);
      }
      continue;
    }
    const rq = qosWords(bus, reader);
    let flags = 0;
    if (rq[QOS.RELIABILITY] === Reliability.RELIABLE && rq[QOS.HISTORY] === History.KEEP_ALL) flags |= LINK_BLOCKING;
    if (rq[QOS.RELIABILITY] === Reliability.BEST_EFFORT) flags |= LINK_BEST_EFFORT;
    addLink(bus, writer, reader, flags);
    if (bus.faultPoint !== null) bus.faultPoint('graph.matching');
  }
}

export function addLink(bus, writer, reader, flags) {
  const i32 = bus.i32;
  const idx = findFree(bus, HEADER.LINK_HINT, HEADER.LINK_HWM, bus.linkCap, (i) => bus.link(i) + LINK.STATE);
  if (idx < 0) {
    throw new BusError(Code.BAD_ALLOC, `cannot match endpoints: the bus link table is full (${bus.linkCap} matched pairs); start the Runtime with a larger maxLinks`);
  }
  const wb = bus.ep(writer);
  const rb = bus.ep(reader);
  const wq = qosWords(bus, writer);
  const rq = qosWords(bus, reader);
  const readerDepth = rq[QOS.HISTORY] === History.KEEP_LAST ? rq[QOS.DEPTH] : 0;
  const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
  let cursor = head;
  if (wq[QOS.DURABILITY] === Durability.TRANSIENT_LOCAL && rq[QOS.DURABILITY] === Durability.TRANSIENT_LOCAL) {
    // A late joiner gets the writer's retained history, as much as its own depth holds.
    const published = i32[wb + ENDPOINT.HEAD_HI] > 0 ? 0x7fffffff : (head >>> 0);
    let retained = wq[QOS.HISTORY] === History.KEEP_LAST ? wq[QOS.DEPTH] : i32[wb + ENDPOINT.RING_SLOTS];
    retained = Math.min(retained, i32[wb + ENDPOINT.RING_SLOTS], published);
    if (readerDepth) retained = Math.min(retained, readerDepth);
    cursor = (head - retained) | 0;
  }
  const lb = bus.link(idx);
  i32[lb + LINK.WRITER] = writer;
  i32[lb + LINK.READER] = reader;
  i32[lb + LINK.CURSOR] = cursor;
  i32[lb + LINK.FLAGS] = flags;
  i32[lb + LINK.DEPTH] = (flags & LINK_TARGETED) ? 0 : readerDepth;
  i32[lb + LINK.WRITER_SERIAL] = i32[wb + ENDPOINT.SERIAL];
  i32[lb + LINK.READER_SERIAL] = i32[rb + ENDPOINT.SERIAL];
  Atomics.store(i32, lb + LINK.STATE, REC_ALIVE);
}
