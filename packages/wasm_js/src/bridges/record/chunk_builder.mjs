// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * MCAP chunks built where the bytes are: the messages of a recording's
 * subscriptions are copied from the bus straight into the Message records
 * of one open chunk, with the chunk's message indexes beside them. A chunk
 * is closed when it is full or `flushMs` after its first message, and
 * handed to a sink (the recording worker posts it to the main thread, which
 * writes it into the bag or to the launcher's pipe). Chunk buffers are
 * slots of a shared pool (./chunk_pool.mjs) when there is one.
 *
 * This is the part of the MCAP layout built per message: the records of a
 * chunk's content (Message, opcode 0x05) and its MessageIndex records
 * (0x07), little endian as the MCAP specification gives them. The Chunk
 * record around them is the sink's; schemas, channels and the summary are
 * the launcher's (colcon_wasm/record/mcap_file.py).
 *
 * @module bridges/record/chunk_builder
 */

import { TakeMode } from '../../bus_client.mjs';
import { setUint64 } from '../common/little_endian.mjs';

const OP_MESSAGE = 0x05;
const OP_MESSAGE_INDEX = 0x07;
/** opcode, record length, channel id, sequence, log time, publish time */
const MESSAGE_HEAD = 1 + 8 + 2 + 4 + 8 + 8;
/**
 * A message at least this big whose place in a pool slot is not 8-aligned
 * (the bus blocks are) is copied in two steps: from the bus to the pool's
 * staging area, aligned, then in place (see ../../copier.mjs: a copy between
 * shared memories at different alignments goes byte by byte, 8 times slower).
 */
const STAGED_BYTES = 4096;

/**
 * Nanoseconds since the epoch of a bus time in milliseconds since the
 * epoch: a whole number in a double (a BigInt per message would feed the
 * garbage collector; the double holds what the bus time holds).
 */
function nanoseconds(ms) {
  return Math.round(ms * 1e6);
}

/**
 * A closed chunk, as the sinks get it.
 * @typedef {object} ClosedChunk
 * @property {Uint8Array} records its Message records (a view of the chunk buffer)
 * @property {number} slot the chunk buffer's slot in the pool, or -1 for a buffer of its own
 * @property {Uint8Array} indexes its MessageIndex records, one per channel
 * @property {number[][]} channels [channel id, message count, index record length] per channel
 * @property {bigint} start earliest log time (ns)
 * @property {bigint} end latest log time (ns)
 * @property {number} messages how many
 */

export class ChunkBuilder {
  /**
   * @param {import('../../bus_client.mjs').BusClient} client the recording process' bus client
   * @param {object} options
   * @param {number} options.chunkBytes a chunk is closed once its records reach this size
   * @param {number} options.flushMs and at the latest this long after its first message
   * @param {function(ClosedChunk): void} options.sink takes a closed chunk (its buffer is the
   *   sink's from then on: a pool slot it frees, or a buffer of its own)
   * @param {?import('./chunk_pool.mjs').ChunkPool} [options.pool] where chunk buffers come
   *   from (a chunk bigger than a slot, or with every slot taken, gets a buffer of its own)
   * @param {function(): number} [options.now] a clock in ms (for `flushDue`)
   */
  constructor(client, { chunkBytes, flushMs, sink, pool = null, now = () => performance.now() }) {
    this.client = client;
    this.chunkBytes = chunkBytes;
    this.flushMs = flushMs;
    this.sink = sink;
    this.pool = pool;
    this.now = now;
    /** subscription endpoint -> MCAP channel id */
    this.channels = new Map();
    /** when the open chunk must be closed (ms of `now`), Infinity while it is empty */
    this.deadline = Infinity;
    this._open(chunkBytes);
  }

  /** Record subscription endpoint `ep` as MCAP channel `channel`. */
  add(ep, channel) {
    this.channels.set(ep, channel);
  }

  /** Stop recording `ep` (what it has taken is in the chunk). */
  remove(ep) {
    this.channels.delete(ep);
  }

  /**
   * Copy every message waiting for the recording's subscriptions into the
   * open chunk, closing chunks as they fill up.
   * @returns {number} how many messages were copied
   */
  drain() {
    const c = this.client;
    let copied = 0;
    for (const [ep, channel] of this.channels) {
      for (;;) {
        const len = c.takeBegin(ep, TakeMode.MESSAGE);
        if (len < 0) break;
        if (this.used > 0 && this.used + MESSAGE_HEAD + len > this.buffer.length) this.flush();
        if (MESSAGE_HEAD + len > this.buffer.length) this._open(MESSAGE_HEAD + len);
        const at = this.used;
        if (!this._take(at + MESSAGE_HEAD, len)) continue;
        const info = c.info;
        const logTime = nanoseconds(info.receivedTime);
        const v = this.view;
        v.setUint8(at, OP_MESSAGE);
        setUint64(v, at + 1, MESSAGE_HEAD - 9 + len);
        v.setUint16(at + 9, channel, true);
        v.setUint32(at + 11, 0, true);
        setUint64(v, at + 15, logTime);
        setUint64(v, at + 23, nanoseconds(info.sourceTime));
        this.used = at + MESSAGE_HEAD + len;
        let index = this.index.get(channel);
        if (!index) this.index.set(channel, index = []);
        index.push(logTime, at);
        if (logTime < this.start) this.start = logTime;
        if (logTime > this.end) this.end = logTime;
        if (this.count++ === 0) this.deadline = this.now() + this.flushMs;
        copied++;
      }
    }
    if (this.used >= this.chunkBytes) this.flush();
    return copied;
  }

  /**
   * Copy the message `takeBegin` found (`len` bytes) to `dataAt` in the open
   * chunk. A pool slot is shared memory: there a big message whose place is
   * not aligned as its bus block goes in two aligned steps (`STAGED_BYTES`).
   * A buffer of its own (a message bigger than a slot, or every slot
   * waiting for the disk) takes the one-step copy: a copy from the bus into
   * memory that is not shared, staged the same way, would end in a memmove
   * that was as slow at some distances between the two buffers (3.4 GB/s
   * on the bench machine), while memory.copy within one memory was 40-50
   * GB/s at every distance tried.
   * @returns {boolean} false when it was overwritten meanwhile (as takeCopy)
   */
  _take(dataAt, len) {
    const c = this.client;
    const pool = this.pool;
    if (len < STAGED_BYTES || (dataAt & 7) === 0 || this.slot < 0 || pool.move === null) {
      return c.takeCopy(this.buffer, dataAt);
    }
    if (!c.takeCopy(pool.staging, 0)) return false;
    pool.move(this.buffer.byteOffset + dataAt, pool.staging.byteOffset, len);
    return true;
  }

  /** True when the open chunk holds messages and its time is up. */
  flushDue() {
    return this.count > 0 && this.now() >= this.deadline;
  }

  /** Hand the open chunk (when it holds a message) to the sink and open the next one. */
  flush() {
    this.deadline = Infinity;
    if (this.count === 0) return;
    const channels = [];
    let indexBytes = 0;
    for (const entries of this.index.values()) indexBytes += 1 + 8 + 2 + 4 + entries.length * 8;
    const indexes = new Uint8Array(indexBytes);
    const iv = new DataView(indexes.buffer);
    let at = 0;
    for (const [channel, entries] of this.index) {
      const bytes = entries.length * 8;
      iv.setUint8(at, OP_MESSAGE_INDEX);
      setUint64(iv, at + 1, 2 + 4 + bytes);
      iv.setUint16(at + 9, channel, true);
      iv.setUint32(at + 11, bytes, true);
      let p = at + 15;
      for (const value of entries) {
        setUint64(iv, p, value);
        p += 8;
      }
      channels.push([channel, entries.length / 2, 15 + bytes]);
      at = p;
    }
    this.sink({
      records: this.buffer.subarray(0, this.used), slot: this.slot, indexes, channels,
      start: BigInt(this.start), end: BigInt(this.end), messages: this.count,
    });
    this._open(this.chunkBytes);
  }

  /** A buffer for the next chunk: a pool slot when one is free and big enough. */
  _open(size) {
    this.slot = this.pool && size <= this.pool.slotBytes ? this.pool.acquire() : -1;
    this.buffer = this.slot >= 0 ? this.pool.bytes(this.slot) : new Uint8Array(Math.max(size, this.chunkBytes));
    this.view = new DataView(this.buffer.buffer, this.buffer.byteOffset, this.buffer.byteLength);
    this.used = 0;
    this.count = 0;
    /** earliest and latest log time of the chunk (ns, whole numbers in doubles) */
    this.start = Infinity;
    this.end = -Infinity;
    this.deadline = Infinity;
    /** channel id -> [log time (ns), offset, log time, offset, ...] */
    this.index = new Map();
  }
}
