// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A recording inside the tools worker: the messages of its subscriptions
 * are copied from the bus straight into the MCAP Message records of one
 * open chunk, with the chunk's message indexes beside them. A chunk goes to
 * the main thread (its buffer transferred, not copied) when it is full or
 * `flushMs` after its first message, so the recorder's writer gets one
 * buffer per chunk instead of one message at a time.
 *
 * This is the part of the MCAP layout built where the bytes are: the
 * records of the chunk's content (Message, opcode 0x05) and the chunk's
 * MessageIndex records (0x07), little endian as the MCAP specification
 * gives them. The Chunk record around them, the schemas, channels and the
 * summary are written by the launcher (colcon_wasm/record/mcap_file.py).
 *
 * @module tools_process/chunk_recording
 */

import { TakeMode } from '../bus_client.mjs';

const OP_MESSAGE = 0x05;
const OP_MESSAGE_INDEX = 0x07;
/** opcode, record length, channel id, sequence, log time, publish time */
const MESSAGE_HEAD = 1 + 8 + 2 + 4 + 8 + 8;

/** Nanoseconds since the epoch (BigInt) of a bus time in milliseconds since the epoch. */
function nanoseconds(ms) {
  return BigInt(Math.round(ms * 1e6));
}

export class ChunkRecording {
  /**
   * @param {import('../bus_client.mjs').BusClient} client the tools worker's bus client
   * @param {object} options
   * @param {number} options.id the recording's id (in the chunks posted)
   * @param {number} options.chunkBytes a chunk is closed once its records reach this size
   * @param {number} options.flushMs and at the latest this long after its first message
   * @param {function(object, ArrayBuffer[]): void} options.post sends a chunk to the main thread
   */
  constructor(client, { id, chunkBytes, flushMs, post }) {
    this.client = client;
    this.id = id;
    this.chunkBytes = chunkBytes;
    this.flushMs = flushMs;
    this.post = post;
    /** subscription endpoint -> MCAP channel id */
    this.channels = new Map();
    /** buffers the main thread gave back, for the next chunks */
    this.spare = [];
    this.timer = null;
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

  /** Take a returned buffer back for later chunks. */
  recycle(buffer) {
    if (buffer.byteLength >= this.chunkBytes && this.spare.length < 4) this.spare.push(new Uint8Array(buffer));
  }

  /** Copy every message waiting for the recording's subscriptions into the open chunk. */
  drain() {
    const c = this.client;
    for (const [ep, channel] of this.channels) {
      for (;;) {
        const len = c.takeBegin(ep, TakeMode.MESSAGE);
        if (len < 0) break;
        if (this.used > 0 && this.used + MESSAGE_HEAD + len > this.buffer.length) this.flush();
        if (MESSAGE_HEAD + len > this.buffer.length) this._open(MESSAGE_HEAD + len);
        const at = this.used;
        if (!c.takeCopy(this.buffer, at + MESSAGE_HEAD)) continue;
        const info = c.info;
        const logTime = nanoseconds(info.receivedTime);
        const v = this.view;
        v.setUint8(at, OP_MESSAGE);
        v.setBigUint64(at + 1, BigInt(MESSAGE_HEAD - 9 + len), true);
        v.setUint16(at + 9, channel, true);
        v.setUint32(at + 11, 0, true);
        v.setBigUint64(at + 15, logTime, true);
        v.setBigUint64(at + 23, nanoseconds(info.sourceTime), true);
        this.used = at + MESSAGE_HEAD + len;
        let index = this.index.get(channel);
        if (!index) this.index.set(channel, index = []);
        index.push(logTime, BigInt(at));
        if (this.start === null || logTime < this.start) this.start = logTime;
        if (this.end === null || logTime > this.end) this.end = logTime;
        this.count++;
        if (this.count === 1) this.timer = setTimeout(() => this.flush(), this.flushMs);
      }
    }
    if (this.used >= this.chunkBytes) this.flush();
  }

  /** Post the open chunk (when it holds a message) and open the next one. */
  flush() {
    if (this.timer) clearTimeout(this.timer);
    this.timer = null;
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
      iv.setBigUint64(at + 1, BigInt(2 + 4 + bytes), true);
      iv.setUint16(at + 9, channel, true);
      iv.setUint32(at + 11, bytes, true);
      let p = at + 15;
      for (const value of entries) {
        iv.setBigUint64(p, value, true);
        p += 8;
      }
      channels.push([channel, entries.length / 2, 15 + bytes]);
      at = p;
    }
    const records = this.buffer.buffer;
    this.post({
      recording: this.id, records, length: this.used, indexes: indexes.buffer, channels,
      start: this.start, end: this.end, messages: this.count,
    }, [records, indexes.buffer]);
    this._open(this.chunkBytes);
  }

  _open(size) {
    const spare = size <= this.chunkBytes ? this.spare.pop() : undefined;
    this.buffer = spare || new Uint8Array(Math.max(size, this.chunkBytes));
    this.view = new DataView(this.buffer.buffer);
    this.used = 0;
    this.count = 0;
    this.start = null;
    this.end = null;
    /** channel id -> [log time, offset, log time, offset, ...] (BigInt) */
    this.index = new Map();
  }
}
