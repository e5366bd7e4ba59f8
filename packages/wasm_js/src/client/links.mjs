// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The links of this thread's endpoints, cached per graph version: a
 * writer's links (all, blocking ones) and its readers' processes, a
 * reader's links.
 *
 * Each function takes the thread's BusClient `c` first (bus_client.mjs is
 * the face callers use).
 *
 * @module client/links
 */

import { ENDPOINT, HEADER, LINK, LINK_BLOCKING, REC_ALIVE } from '../layout.mjs';

const EMPTY = new Int32Array(0);

export function refresh(c) {
  // A plain read: a stale version only delays the cache refresh.
  const v = c.bus.i32[HEADER.GRAPH_VERSION];
  if (v !== c._cacheVersion) {
    c._cacheVersion = v;
    c._writers.clear();
    c._readers.clear();
    // New endpoints (rings) may lie beyond this thread's views.
    c.bus.refreshViews();
  }
}

export function writerInfo(c, ep) {
  let w = c._writers.get(ep);
  if (w) return w;
  const bus = c.bus;
  const i32 = bus.i32;
  const links = [];
  const blocking = [];
  const pids = new Set();
  const hwm = Atomics.load(i32, HEADER.LINK_HWM);
  for (let l = 0; l < hwm; l++) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) !== REC_ALIVE || i32[lb + LINK.WRITER] !== ep) continue;
    links.push(l);
    if (i32[lb + LINK.FLAGS] & LINK_BLOCKING) blocking.push(l);
    pids.add(i32[bus.ep(i32[lb + LINK.READER]) + ENDPOINT.PID]);
  }
  w = { links: Int32Array.from(links), blocking: Int32Array.from(blocking), pids: Int32Array.from(pids), floor: 0, floorValid: false };
  c._writers.set(ep, w);
  return w;
}

export function readerLinks(c, ep) {
  let r = c._readers.get(ep);
  if (r) return r;
  const bus = c.bus;
  const i32 = bus.i32;
  const links = [];
  const hwm = Atomics.load(i32, HEADER.LINK_HWM);
  for (let l = 0; l < hwm; l++) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) === REC_ALIVE && i32[lb + LINK.READER] === ep) links.push(l);
  }
  r = links.length ? Int32Array.from(links) : EMPTY;
  c._readers.set(ep, r);
  return r;
}
