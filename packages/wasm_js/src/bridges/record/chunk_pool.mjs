// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Chunk buffers shared by the recording worker and the main thread: one
 * SharedArrayBuffer cut into slots, each free or taken (a word per slot).
 * The worker takes a slot, builds a chunk in it and posts its number; the
 * main thread writes the slot's bytes (into the bag, or to the launcher's
 * pipe) and frees it. No buffer is transferred, allocated or collected per
 * chunk, so neither thread meets a garbage collection on this path.
 *
 * @module bridges/record/chunk_pool
 */

const FREE = 0;
const TAKEN = 1;

export class ChunkPool {
  /**
   * A new pool of `slots` buffers of `slotBytes` bytes.
   * @returns {ChunkPool}
   */
  static create(slots, slotBytes) {
    return new ChunkPool(new SharedArrayBuffer(4 * slots + slots * slotBytes), slots, slotBytes);
  }

  /**
   * Attach to a pool (the other thread's side gets `sab`, `slots`, `slotBytes`).
   * @param {SharedArrayBuffer} sab
   * @param {number} slots
   * @param {number} slotBytes
   */
  constructor(sab, slots, slotBytes) {
    this.sab = sab;
    this.slots = slots;
    this.slotBytes = slotBytes;
    this.state = new Int32Array(sab, 0, slots);
    this.views = [];
    for (let i = 0; i < slots; i++) this.views.push(new Uint8Array(sab, 4 * slots + i * slotBytes, slotBytes));
  }

  /** Take a free slot: its number, or -1 when every slot is taken. */
  acquire() {
    for (let i = 0; i < this.slots; i++) {
      if (Atomics.compareExchange(this.state, i, FREE, TAKEN) === FREE) return i;
    }
    return -1;
  }

  /** The bytes of slot `slot`. */
  bytes(slot) {
    return this.views[slot];
  }

  /** Give slot `slot` back. */
  release(slot) {
    Atomics.store(this.state, slot, FREE);
  }
}
