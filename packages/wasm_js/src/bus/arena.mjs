// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * The arena: the bus memory past the record tables, in blocks of
 * power-of-two size classes with a 32-byte header (rings, message blocks,
 * strings), and the free records of the tables. Every call here runs
 * under the registry lock, except renewSlotBlock(), which takes it.
 *
 * A freed block waits GRACE_MS in a quarantine before reuse, since a reader
 * may still be copying from it (readers re-validate what they copied).
 *
 * Each function takes the thread's Bus `bus` first (bus.mjs is the face
 * callers use).
 *
 * @module bus/arena
 */

import {
  BLOCK, BLOCK_FREE, BLOCK_HEADER_BYTES, BLOCK_QUARANTINE, BLOCK_USED, GRACE_MS, HEADER,
  MIN_CLASS_SHIFT, REC_FREE, SIZE_CLASSES, SLOT,
} from '../layout.mjs';
import { now } from './clock.mjs';

const encoder = new TextEncoder();
const decoder = new TextDecoder();
/** WebAssembly page size: a bus that is a WebAssembly.Memory grows by whole pages. */
export const PAGE = 65536;

/**
 * Make this thread's views cover the whole arena (registry lock held): another
 * thread may have grown the bus, and blocks, free ones included, may lie
 * beyond the views this thread last saw. Typed-array writes past a view are
 * silently dropped, so every arena walk starts here.
 */
function coverArena(bus) {
  if (bus.i32[HEADER.ARENA_TOP] > bus.u8.length) bus.refreshViews();
}

/**
 * Allocate an arena block of at least `bytes` bytes (registry lock held).
 * @param {number} bytes
 * @param {number} owner pid, recorded in the block header
 * @returns {number} payload byte offset, or 0 when the bus is full
 */
export function alloc(bus, bytes, owner) {
  coverArena(bus);
  releaseQuarantine(bus);
  let shift = MIN_CLASS_SHIFT;
  while ((1 << shift) < bytes && shift < 31) shift++;
  if ((2 ** shift) < bytes) return 0;
  const cls = shift - MIN_CLASS_SHIFT;
  if (cls >= SIZE_CLASSES) return 0;
  const i32 = bus.i32;
  const head = i32[HEADER.FREE_BASE + cls];
  if (head !== 0) {
    const hw = (head - BLOCK_HEADER_BYTES) >> 2;
    i32[HEADER.FREE_BASE + cls] = i32[hw + BLOCK.NEXT];
    i32[hw + BLOCK.STATE] = BLOCK_USED;
    i32[hw + BLOCK.OWNER] = owner;
    i32[hw + BLOCK.NEXT] = 0;
    i32[HEADER.ARENA_USED] += 2 ** shift;
    return head;
  }
  const top = i32[HEADER.ARENA_TOP];
  const end = top + BLOCK_HEADER_BYTES + 2 ** shift;
  if (end > bus.byteLength() && !grow(bus, end)) return 0;
  const ri32 = bus.i32;
  const hw = top >> 2;
  ri32[hw + BLOCK.CLASS] = cls;
  ri32[hw + BLOCK.STATE] = BLOCK_USED;
  ri32[hw + BLOCK.OWNER] = owner;
  ri32[hw + BLOCK.NEXT] = 0;
  ri32[HEADER.ARENA_TOP] = end; // commit
  ri32[HEADER.ARENA_USED] += 2 ** shift;
  return top + BLOCK_HEADER_BYTES;
}

/** Payload capacity of the block at `off`. */
export function blockCapacity(bus, off) {
  return 2 ** (bus.i32[((off - BLOCK_HEADER_BYTES) >> 2) + BLOCK.CLASS] + MIN_CLASS_SHIFT);
}

/**
 * Free a block (registry lock held). It is reused only after GRACE_MS,
 * since a reader may still be copying from it (readers re-validate).
 * @param {number} off payload byte offset
 */
export function free(bus, off) {
  if (!off) return;
  coverArena(bus);
  const i32 = bus.i32;
  const hw = (off - BLOCK_HEADER_BYTES) >> 2;
  if (i32[hw + BLOCK.STATE] !== BLOCK_USED) return;
  i32[hw + BLOCK.STATE] = BLOCK_QUARANTINE;
  i32[hw + BLOCK.NEXT] = 0;
  bus.f64[(hw + BLOCK.FREED_F64) >> 1] = now();
  i32[HEADER.ARENA_USED] -= 2 ** (i32[hw + BLOCK.CLASS] + MIN_CLASS_SHIFT);
  const tail = i32[HEADER.QUAR_TAIL];
  if (tail) {
    i32[((tail - BLOCK_HEADER_BYTES) >> 2) + BLOCK.NEXT] = off;
    if (bus.faultPoint !== null) bus.faultPoint('arena.freeing');
  } else i32[HEADER.QUAR_HEAD] = off;
  i32[HEADER.QUAR_TAIL] = off;
}

export function releaseQuarantine(bus) {
  coverArena(bus);
  const i32 = bus.i32;
  let head = i32[HEADER.QUAR_HEAD];
  if (!head) return;
  const t = now();
  while (head) {
    const hw = (head - BLOCK_HEADER_BYTES) >> 2;
    if (t - bus.f64[(hw + BLOCK.FREED_F64) >> 1] < GRACE_MS) break;
    const next = i32[hw + BLOCK.NEXT];
    i32[HEADER.QUAR_HEAD] = next;
    if (bus.faultPoint !== null) bus.faultPoint('arena.releasing');
    if (!next) i32[HEADER.QUAR_TAIL] = 0;
    const cls = i32[hw + BLOCK.CLASS];
    i32[hw + BLOCK.STATE] = BLOCK_FREE;
    i32[hw + BLOCK.NEXT] = i32[HEADER.FREE_BASE + cls];
    i32[HEADER.FREE_BASE + cls] = head;
    head = next;
  }
}

export function grow(bus, end) {
  if (!bus.growable || end > bus.maxBytes) return false;
  const len = bus.byteLength();
  let target = Math.max(end, Math.min(bus.maxBytes, len + Math.max(len >> 1, 8 * 1024 * 1024)));
  // Whole pages (maxBytes is whole MiB), as a WebAssembly.Memory grows.
  target = Math.min(bus.maxBytes, Math.ceil(target / PAGE) * PAGE);
  if (target < end) return false;
  try {
    if (bus.memory !== null) {
      bus.memory.grow((target - len) / PAGE);
      bus.sab = bus.memory.buffer;
    } else {
      bus.sab.grow(target);
    }
  } catch (e) {
    return false;
  }
  bus.refreshViews();
  return true;
}

/** Bytes of arena in use and the current / maximum buffer size (diagnostics). */
export function memoryUsage(bus) {
  return {
    arenaUsed: Atomics.load(bus.i32, HEADER.ARENA_USED),
    bufferBytes: bus.byteLength(),
    maxBytes: bus.maxBytes,
  };
}

/**
 * Allocate one block holding several UTF-8 strings back to back (lock held).
 * @param {string[]} strings
 * @param {number} owner
 * @returns {{off: number, lens: number[]}|null}
 */
export function allocStrings(bus, strings, owner) {
  const encoded = strings.map((s) => encoder.encode(s));
  const total = encoded.reduce((a, b) => a + b.length, 0);
  const off = alloc(bus, Math.max(total, 1), owner);
  if (!off) return null;
  let p = off;
  for (const b of encoded) {
    bus.u8.set(b, p);
    p += b.length;
  }
  return { off, lens: encoded.map((b) => b.length) };
}

/** Decode `len` UTF-8 bytes at byte offset `off`. */
export function readString(bus, off, len) {
  if (len === 0) return '';
  return decoder.decode(bus.u8.slice(off, off + len));
}

export function bytesEqual(bus, off, bytes) {
  const u8 = bus.u8;
  for (let i = 0; i < bytes.length; i++) if (u8[off + i] !== bytes[i]) return false;
  return true;
}

/**
 * A free record of a table (lock held): searched from the table's hint word,
 * which then points past it; raises the high-water mark.
 * @returns {number} the record index, or -1 when the table is full
 */
export function findFree(bus, hintWord, hwmWord, cap, stateWordOf, first = 0) {
  const i32 = bus.i32;
  const hint = i32[hintWord] || first;
  for (let n = 0; n < cap; n++) {
    let i = hint + n;
    if (i >= cap) i = first + ((i - first) % (cap - first));
    if (Atomics.load(i32, stateWordOf(i)) === REC_FREE) {
      i32[hintWord] = i + 1 < cap ? i + 1 : first;
      if (i + 1 > i32[hwmWord]) i32[hwmWord] = i + 1;
      return i;
    }
  }
  return -1;
}

/**
 * Give the ring slot at word `slot` a block of at least `bytes` bytes in
 * place of its current one, which is freed; takes the registry lock for it
 * (workers only). The slot's BLOCK and CAP words are set under the lock.
 * @param {import('../bus.mjs').Bus} bus
 * @param {number} slot word index of the ring slot
 * @param {number} bytes
 * @param {number} owner the caller's process id
 * @returns {number} the new block's payload offset, or 0 when the bus is full
 */
export function renewSlotBlock(bus, slot, bytes, owner) {
  bus.lock(owner);
  try {
    free(bus, bus.i32[slot + SLOT.BLOCK]);
    if (bus.faultPoint !== null) bus.faultPoint('publish.renewing');
    const block = alloc(bus, bytes, owner);
    const i32 = bus.i32; // alloc() may have grown the bus
    i32[slot + SLOT.BLOCK] = block;
    i32[slot + SLOT.CAP] = block ? blockCapacity(bus, block) : 0;
    return block;
  } finally {
    bus.unlock(owner);
  }
}
