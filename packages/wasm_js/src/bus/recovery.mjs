// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Recovery after a process died holding the registry lock: whoever steals
 * the lock (Bus.tryLock, Bus.lockAsync) repairs what the dead owner's
 * critical section may have left half done, before anything else runs
 * under the lock.
 *
 * Records need no repair: each is committed by a final store of its STATE
 * word (the dead process' own records are removed by the runtime's cleanup
 * next). The arena's lists do: a free or a release of the quarantine is
 * several plain stores, and an allocation or a free cut short leaves a
 * block on no list or a list end pointing at the wrong block (the next
 * free would then link a quarantined block into a free list). So the
 * arena's free lists, quarantine and byte count are rebuilt from the
 * block headers, which the walk from ARENA_BASE to ARENA_TOP reads in
 * order:
 *   - a zombie writer with no link left (its freeing was cut short) is freed;
 *   - a ring slot whose block is no longer in use (a renewal cut short
 *     between the free and the allocation) forgets it;
 *   - a block in use that no record refers to and that the dead owner
 *     allocated (an allocation before its record was committed) is freed;
 *   - every free block goes back on its class' list, every quarantined one
 *     on the quarantine in the order it was freed.
 *
 * Nothing else allocates while the lock is held, and a block freed by the
 * dead owner's section is still in quarantine (GRACE_MS), so the walk sees
 * every block as the dead owner left it.
 *
 * @module bus/recovery
 */

import {
  BLOCK, BLOCK_FREE, BLOCK_HEADER_BYTES, BLOCK_QUARANTINE, BLOCK_USED, ENDPOINT, HEADER,
  LINK, MIN_CLASS_SHIFT, NODE, REC_ALIVE, REC_FREE, REC_ZOMBIE, SIZE_CLASSES, SLOT,
} from '../layout.mjs';
import { now } from './clock.mjs';
import { freeEndpoint } from './registry.mjs';

/**
 * Repair the arena after `deadPid` died holding the registry lock (lock held).
 * @param {import('../bus.mjs').Bus} bus
 * @param {number} deadPid the process the lock was stolen from
 * @returns {{ok: boolean, blocks: number, leaked: number, orphans: number, slots: number,
 *   why?: string}} what was repaired (ok false: the block headers do not walk, nothing done)
 */
export function recoverArena(bus, deadPid) {
  bus.refreshViews();
  const report = { ok: true, blocks: 0, leaked: 0, orphans: 0, slots: 0 };
  const walk = walkBlocks(bus);
  if (walk.why) return { ...report, ok: false, why: walk.why };
  const i32 = bus.i32;
  // Zombie writers whose last link went: the dead owner was freeing them.
  const ehwm = i32[HEADER.EP_HWM];
  const lhwm = i32[HEADER.LINK_HWM];
  const read = new Set();
  for (let l = 0; l < lhwm; l++) {
    const lb = bus.link(l);
    if (Atomics.load(i32, lb + LINK.STATE) === REC_ALIVE) read.add(i32[lb + LINK.WRITER]);
  }
  for (let e = 0; e < ehwm; e++) {
    if (Atomics.load(i32, bus.ep(e) + ENDPOINT.STATE) === REC_ZOMBIE && !read.has(e)) {
      freeEndpoint(bus, e); // frees only blocks still in use: the others are already
      report.orphans++;
    }
  }
  const state = (off) => {
    const k = walk.index.get(off);
    return k === undefined ? 0 : i32[((off - BLOCK_HEADER_BYTES) >> 2) + BLOCK.STATE];
  };
  const referenced = new Set();
  const nhwm = i32[HEADER.NODE_HWM];
  for (let n = 0; n < nhwm; n++) {
    const nb = bus.node(n);
    if (Atomics.load(i32, nb + NODE.STATE) !== REC_FREE) referenced.add(i32[nb + NODE.STR_OFF]);
  }
  for (let e = 0; e < ehwm; e++) {
    const eb = bus.ep(e);
    if (Atomics.load(i32, eb + ENDPOINT.STATE) === REC_FREE) continue;
    referenced.add(i32[eb + ENDPOINT.STR_OFF]);
    const ring = i32[eb + ENDPOINT.RING_OFF];
    if (!ring || state(ring) !== BLOCK_USED) continue;
    referenced.add(ring);
    const slots = i32[eb + ENDPOINT.RING_SLOTS];
    for (let s = 0; s < slots; s++) {
      const sw = (ring >> 2) + s * SLOT.WORDS;
      const block = i32[sw + SLOT.BLOCK];
      if (!block) continue;
      if (state(block) === BLOCK_USED) {
        referenced.add(block);
      } else {
        // A renewal cut short: the slot (marked as being written) keeps no freed block.
        i32[sw + SLOT.BLOCK] = 0;
        i32[sw + SLOT.CAP] = 0;
        report.slots++;
      }
    }
  }
  const t = now();
  const free = [];
  const quarantine = [];
  let used = 0;
  for (const off of walk.blocks) {
    const hw = (off - BLOCK_HEADER_BYTES) >> 2;
    let st = i32[hw + BLOCK.STATE];
    if (st === BLOCK_USED && !referenced.has(off) && i32[hw + BLOCK.OWNER] === deadPid) {
      // Allocated by the dead owner for a record it never committed.
      i32[hw + BLOCK.STATE] = st = BLOCK_QUARANTINE;
      bus.f64[(hw + BLOCK.FREED_F64) >> 1] = t;
      report.leaked++;
    }
    if (st === BLOCK_USED) used += 2 ** (i32[hw + BLOCK.CLASS] + MIN_CLASS_SHIFT);
    else if (st === BLOCK_FREE) free.push(off);
    else quarantine.push(off);
  }
  // The free lists, class by class.
  for (let cls = 0; cls < SIZE_CLASSES; cls++) i32[HEADER.FREE_BASE + cls] = 0;
  for (let k = free.length - 1; k >= 0; k--) {
    const off = free[k];
    const hw = (off - BLOCK_HEADER_BYTES) >> 2;
    const cls = i32[hw + BLOCK.CLASS];
    i32[hw + BLOCK.NEXT] = i32[HEADER.FREE_BASE + cls];
    i32[HEADER.FREE_BASE + cls] = off;
  }
  // The quarantine, oldest first (a block is reused GRACE_MS after its free).
  const freedAt = (off) => bus.f64[(((off - BLOCK_HEADER_BYTES) >> 2) + BLOCK.FREED_F64) >> 1];
  quarantine.sort((a, b) => freedAt(a) - freedAt(b) || a - b);
  for (let k = 0; k < quarantine.length; k++) {
    const hw = (quarantine[k] - BLOCK_HEADER_BYTES) >> 2;
    i32[hw + BLOCK.STATE] = BLOCK_QUARANTINE;
    i32[hw + BLOCK.NEXT] = k + 1 < quarantine.length ? quarantine[k + 1] : 0;
  }
  i32[HEADER.QUAR_HEAD] = quarantine.length ? quarantine[0] : 0;
  i32[HEADER.QUAR_TAIL] = quarantine.length ? quarantine[quarantine.length - 1] : 0;
  Atomics.store(i32, HEADER.ARENA_USED, used);
  report.blocks = walk.blocks.length;
  return report;
}

/**
 * The arena's blocks in address order (payload offsets), walked by their
 * headers' size classes from ARENA_BASE to ARENA_TOP.
 * @returns {{blocks: number[], index: Map<number, number>, why?: string}}
 */
export function walkBlocks(bus) {
  const i32 = bus.i32;
  const top = i32[HEADER.ARENA_TOP];
  const blocks = [];
  const index = new Map();
  for (let at = i32[HEADER.ARENA_BASE]; at < top;) {
    const hw = at >> 2;
    const cls = i32[hw + BLOCK.CLASS];
    const st = i32[hw + BLOCK.STATE];
    const end = at + BLOCK_HEADER_BYTES + 2 ** (cls + MIN_CLASS_SHIFT);
    if (cls < 0 || cls >= SIZE_CLASSES || end > top ||
        (st !== BLOCK_USED && st !== BLOCK_FREE && st !== BLOCK_QUARANTINE)) {
      return { blocks, index, why: `the block header at byte ${at} does not walk (class ${cls}, state ${st}, arena top ${top})` };
    }
    index.set(at + BLOCK_HEADER_BYTES, blocks.length);
    blocks.push(at + BLOCK_HEADER_BYTES);
    at = end;
  }
  return { blocks, index };
}
