// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Waiting: the process doorbell, wait sets (checkItems, wait) and the
 * listener (listenCheck, listen). The no-lost-wake-up argument is in
 * bus_client.mjs.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/wait
 */

import { ENDPOINT, HEADER, LINK, LINK_TARGETED, REC_ALIVE, SLOT } from '../layout.mjs';
import { EventType, TakeMode, WAIT_ITEM_WORDS, WaitKind } from '../abi/bus_abi.mjs';
import { BusError, Code, now } from '../bus.mjs';
import { readerLinks, refresh } from './links.mjs';
import { eventStatus } from './events.mjs';
import { takeBegin } from './reader.mjs';

const LISTEN_KEY = 0x100000;

/** The process doorbell value (read before checking, pass to sleep()). */
export function readBell(c) {
  return Atomics.load(c.bus.i32, c.bellIndex);
}

/** Count this thread as a sleeper of the process (before bell() and checking). */
export function register(c) {
  Atomics.add(c.bus.i32, c.sleepersIndex, 1);
}

/** Stop counting this thread as a sleeper. */
export function unregister(c) {
  Atomics.sub(c.bus.i32, c.sleepersIndex, 1);
}

/**
 * Sleep on this process' doorbell while it still holds `bell` (registered callers only).
 * @param {number} bell value read after register() and before checking the entities
 * @param {number} ms at most this long (Infinity: no limit)
 */
export function sleep(c, bell, ms) {
  if (c._beforeSleep !== null) firstSleep(c);
  if (c.bus.faultPoint !== null) c.bus.faultPoint('wait.sleeping');
  Atomics.wait(c.bus.i32, c.bellIndex, bell, ms);
}

/**
 * Call `fn` once, just before this thread first sleeps on the bus (a wait,
 * a blocked publish, a wait for acknowledgements): the worker's sign that
 * main() has started and now waits for work.
 * @param {function(): void} fn
 */
export function beforeFirstSleep(c, fn) {
  c._beforeSleep = fn;
}

export function firstSleep(c) {
  const fn = c._beforeSleep;
  c._beforeSleep = null;
  fn();
}

/** Wake every wait of this process (guard condition triggers, listener changes). */
export function ringSelf(c) {
  c.bus.ring(c.pid);
}

/**
 * Check wait items once.
 * @param {Int32Array} items WAIT_ITEM_WORDS words per item: kind, handle, aux, result
 * @param {number} base first word
 * @param {number} count items
 * @param {Int32Array} heap32 the memory guard condition pointers refer to
 * @returns {number} number of ready items; c._nextExpiry is set
 */
export function checkItems(c, items, base, count, heap32) {
  let ready = 0;
  let next = Infinity;
  for (let i = 0; i < count; i++) {
    const o = base + i * WAIT_ITEM_WORDS;
    const kind = items[o];
    const handle = items[o + 1];
    let r = 0;
    switch (kind) {
      case WaitKind.SUBSCRIPTION:
      case WaitKind.SERVICE:
        r = takeBegin(c, handle, kind === WaitKind.SERVICE ? TakeMode.REQUEST : TakeMode.MESSAGE) >= 0 ? 1 : 0;
        break;
      case WaitKind.CLIENT:
        r = takeBegin(c, handle, TakeMode.RESPONSE) >= 0 ? 1 : 0;
        break;
      case WaitKind.GUARD_CONDITION: {
        const w = handle >> 2;
        if (heap32[w] === 1) {
          const v = Atomics.load(c.bus.i32, HEADER.GRAPH_VERSION);
          if (Atomics.exchange(heap32, w + 2, v) !== v) r = 1;
        }
        if (Atomics.exchange(heap32, w + 1, 0) !== 0) r = 1;
        break;
      }
      case WaitKind.EVENT: {
        const s = eventStatus(c, handle, items[o + 2], false);
        r = s.changed ? 1 : 0;
        if (s.next < next) next = s.next;
        break;
      }
      default:
        throw new BusError(Code.INVALID_ARGUMENT, `wait: unknown item kind ${kind}`);
    }
    items[o + 3] = r;
    ready += r;
  }
  c._nextExpiry = next;
  return ready;
}

/**
 * Wait until an item is ready or the timeout passes.
 * @param {Int32Array} items see checkItems()
 * @param {number} base
 * @param {number} count
 * @param {number} timeoutMs < 0: forever, 0: check once
 * @param {Int32Array} heap32
 * @param {boolean} returnAfterWake return -1 after the first sleep (the caller
 *   has work to do between sleeps, e.g. the main thread's proxied calls)
 * @returns {number} ready count (0: timed out, -1: woken, call again)
 */
export function wait(c, items, base, count, timeoutMs, heap32, returnAfterWake = false) {
  // The clock is read only when we are about to sleep (a clock read costs
  // 90-340 ns in a Chromium worker, see bus.mjs).
  let deadline = timeoutMs < 0 ? Infinity : -1;
  for (;;) {
    if (c.service) c.service();
    let ready = checkItems(c, items, base, count, heap32);
    if (ready > 0 || timeoutMs === 0) return ready;
    const t = now();
    if (deadline < 0) deadline = t + timeoutMs;
    if (t >= deadline) return 0;
    // Register, then look again before sleeping (see the module comment):
    // writers only ring while we are registered, so keep that window short.
    register(c);
    const bell = readBell(c);
    if (c.service) c.service();
    ready = checkItems(c, items, base, count, heap32);
    if (ready === 0) {
      const until = Math.min(deadline, c._nextExpiry);
      sleep(c, bell, until === Infinity ? Infinity : Math.max(0, until - t));
    }
    unregister(c);
    if (ready > 0) return ready;
    if (returnAfterWake) return -1;
  }
}

/**
 * Count what arrived since the listener last looked (no message is taken).
 * Items use the wait layout and must live in `items` = the wasm heap (a
 * guard condition item points at a wake-up word there); result = number
 * of new events.
 * @returns {number} total new events; c._nextExpiry is set
 */
export function listenCheck(c, items, base, count) {
  const bus = c.bus;
  const i32 = bus.i32;
  refresh(c);
  let total = 0;
  let next = Infinity;
  for (let i = 0; i < count; i++) {
    const o = base + i * WAIT_ITEM_WORDS;
    const kind = items[o];
    const ep = items[o + 1];
    let n = 0;
    if (kind === WaitKind.GUARD_CONDITION) {
      // The listener's own wake-up word (registration changes): items is the wasm heap.
      n = Atomics.exchange(items, (ep >> 2) + 1, 0) !== 0 ? 1 : 0;
    } else if (kind === WaitKind.EVENT) {
      const key = -1 - (ep * 8 + items[o + 2]);
      const s = eventStatus(c, ep, items[o + 2], false);
      const level = items[o + 2] === EventType.LIVELINESS_CHANGED
        ? s.alive * 65536 + s.notAlive : s.total;
      const seen = c._listenMarks.get(key);
      if (seen === undefined) {
        n = s.changed ? 1 : 0;
      } else if (seen !== level) n = items[o + 2] === EventType.LIVELINESS_CHANGED ? 1 : level - seen;
      c._listenMarks.set(key, level);
      if (s.next < next) next = s.next;
    } else {
      const links = readerLinks(c, ep);
      for (let k = 0; k < links.length; k++) {
        const lb = bus.link(links[k]);
        if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE) continue;
        const wb = bus.ep(i32[lb + LINK.WRITER]);
        const head = Atomics.load(i32, wb + ENDPOINT.HEAD);
        const key = links[k] * LISTEN_KEY + ep;
        let mark = c._listenMarks.get(key);
        if (mark === undefined) mark = Atomics.load(i32, lb + LINK.CURSOR);
        const slots = i32[wb + ENDPOINT.RING_SLOTS];
        let from = mark;
        if (((head - from) | 0) > slots) from = (head - slots) | 0;
        if (i32[lb + LINK.FLAGS] & LINK_TARGETED) {
          const ring = i32[wb + ENDPOINT.RING_OFF] >> 2;
          const serial = i32[bus.ep(ep) + ENDPOINT.SERIAL];
          for (let m = from; ((head - m) | 0) > 0; m = (m + 1) | 0) {
            const sw = ring + (m & (slots - 1)) * SLOT.WORDS;
            if (i32[sw + SLOT.TARGET] === ep + 1 && i32[sw + SLOT.TARGET_SERIAL] === serial) n++;
          }
        } else {
          let d = (head - from) | 0;
          const depth = i32[lb + LINK.DEPTH];
          if (depth && d > depth && mark === Atomics.load(i32, lb + LINK.CURSOR)) d = depth;
          n += Math.max(0, d);
        }
        c._listenMarks.set(key, head);
      }
    }
    items[o + 3] = n;
    total += n;
  }
  c._nextExpiry = next;
  return total;
}

/**
 * Wait until something new arrives for the listener's items (nothing is taken).
 * @returns {number} new events (0: timed out, -1: woken, call again)
 */
export function listen(c, items, base, count, timeoutMs, returnAfterWake = false) {
  const deadline = timeoutMs < 0 ? Infinity : now() + timeoutMs;
  register(c);
  try {
    for (;;) {
      const bell = readBell(c);
      if (c.service) c.service();
      const n = listenCheck(c, items, base, count);
      if (n > 0) return n;
      const t = now();
      if (t >= deadline) return 0;
      const until = Math.min(deadline, c._nextExpiry);
      sleep(c, bell, until === Infinity ? Infinity : Math.max(0, until - t));
      if (returnAfterWake) return -1;
    }
  } finally {
    unregister(c);
  }
}

/** Forget the listener marks of endpoint ep (its callback was cleared). */
export function listenForget(c, ep) {
  for (const key of [...c._listenMarks.keys()]) {
    if ((key >= 0 && key % LISTEN_KEY === ep) || (key < 0 && Math.floor((-1 - key) / 8) === ep)) {
      c._listenMarks.delete(key);
    }
  }
}
