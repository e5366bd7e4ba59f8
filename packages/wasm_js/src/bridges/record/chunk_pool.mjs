// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Chunk buffers shared by the recording worker and the main thread: one
 * shared WebAssembly.Memory cut into slots, each free or taken (a word per
 * slot), and a staging area. The worker takes a slot, builds a chunk in it
 * and posts its number; the main thread writes the slot's bytes (into the
 * bag, or to the launcher's pipe) and frees it. No buffer is transferred,
 * allocated or collected per chunk, so neither thread meets a garbage
 * collection on this path.
 *
 * The memory is a WebAssembly.Memory (its buffer a SharedArrayBuffer) so
 * that a message can be copied from the bus to a place of any alignment in
 * a slot at memmove speed: into the staging area (at the bus block's
 * alignment), then moved in place with memory.copy (`move`, ../../copier.mjs).
 *
 * @module bridges/record/chunk_pool
 */

import { memoryMover } from '../../copier.mjs';

const FREE = 0;
const TAKEN = 1;
/** Where slots and the staging area start: a multiple of the bus blocks' alignment. */
const ALIGN = 64;
const PAGE = 65536;

const aligned = (n) => Math.ceil(n / ALIGN) * ALIGN;

export class ChunkPool {
  /**
   * A new pool of `slots` buffers of `slotBytes` bytes, and a staging area as big as a slot.
   * @returns {ChunkPool}
   */
  static create(slots, slotBytes) {
    const bytes = aligned(4 * slots) + (slots + 1) * aligned(slotBytes);
    const pages = Math.ceil(bytes / PAGE);
    return new ChunkPool(new WebAssembly.Memory({ initial: pages, maximum: pages, shared: true }), slots, slotBytes);
  }

  /**
   * Attach to a pool (the other thread's side gets `memory`, `slots`, `slotBytes`).
   * @param {WebAssembly.Memory} memory
   * @param {number} slots
   * @param {number} slotBytes
   */
  constructor(memory, slots, slotBytes) {
    this.memory = memory;
    this.slots = slots;
    this.slotBytes = slotBytes;
    const sab = memory.buffer;
    this.state = new Int32Array(sab, 0, slots);
    const stride = aligned(slotBytes);
    const base = aligned(4 * slots);
    this.views = [];
    for (let i = 0; i < slots; i++) this.views.push(new Uint8Array(sab, base + i * stride, slotBytes));
    /** where a message is copied before `move` puts it in a slot (aligned as the bus blocks) */
    this.staging = new Uint8Array(sab, base + slots * stride, slotBytes);
    this._move = undefined;
  }

  /**
   * move(dstOffset, srcOffset, len): memory.copy within the pool's memory
   * (offsets from its start, as `byteOffset`s), or null where the engine has
   * none. Made on first use: only the recording worker's side moves.
   */
  get move() {
    if (this._move === undefined) this._move = memoryMover(this.memory);
    return this._move;
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
