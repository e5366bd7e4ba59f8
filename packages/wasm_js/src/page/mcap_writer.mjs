// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Write an MCAP file in memory (https://mcap.dev/spec), for the page's
 * recorder: the magic, a Header, the Schema and Channel records as topics
 * appear, the messages in uncompressed chunks of 1 MiB (each with the CRC
 * of its records) and their MessageIndex records, a DataEnd, and a summary
 * (the schemas and channels again, Statistics, a ChunkIndex per chunk,
 * SummaryOffset records, its CRC in the Footer), so that readers that
 * seek (`mcap`'s indexed reader, @mcap/core's McapIndexedReader) and
 * readers that stream both read it.
 *
 * The Message and MessageIndex records of a chunk are built by the Node
 * recorder's chunk builder (../bridges/record/chunk_builder.mjs), fed from
 * the page's subscriptions instead of the bus (`BatchFeed`); the Chunk
 * record around them is built here. What it holds is bounded: past
 * `maxBytes` a message is dropped and counted (`dropped`), as serve's
 * recorder drops what it cannot keep up with.
 *
 * @module page/mcap_writer
 */

import { ChunkBuilder } from '../bridges/record/chunk_builder.mjs';
import { crc32, MAGIC, Op, RecordBuilder } from './mcap_records.mjs';

/** A chunk is closed once its records reach this size. */
export const CHUNK_BYTES = 1 << 20;
/** The most a recording holds in memory by default (the file it makes is this size at most). */
export const MAX_BYTES = 256 * 1024 * 1024;
/** Message head (31) and MessageIndex entry (16): what a message adds besides its bytes. */
const PER_MESSAGE = 31 + 16;
/** Room kept for the summary and footer, so the file stays under `maxBytes`. */
const SUMMARY_ROOM = 64 * 1024;

/**
 * The chunk builder's bus client, fed from message batches: `takeBegin` and
 * `takeCopy` hand over the messages of `feed(endpoint, batch)` one by one.
 */
class BatchFeed {
  constructor() {
    this.pending = new Map();
    this.info = null;
    this._message = null;
  }

  /** Queue `batch` ({data: Uint8Array, info: {receivedTime, sourceTime}} each) for `endpoint`. */
  feed(endpoint, batch) {
    this.pending.set(endpoint, { batch, at: 0 });
  }

  /** The next message's length (-1: none), as BusClient.takeBegin. */
  takeBegin(endpoint) {
    const p = this.pending.get(endpoint);
    if (!p || p.at >= p.batch.length) {
      this.pending.delete(endpoint);
      return -1;
    }
    this._message = p.batch[p.at++];
    this.info = this._message.info;
    return this._message.data.length;
  }

  /** Copy the message `takeBegin` found into `buffer` at `at`, as BusClient.takeCopy. */
  takeCopy(buffer, at) {
    buffer.set(this._message.data, at);
    return true;
  }
}

/** One MCAP file being written in memory. */
export class McapWriter {
  /**
   * @param {object} [options]
   * @param {string} [options.profile='ros2'] the Header's profile
   * @param {string} [options.library] the Header's library
   * @param {number} [options.chunkBytes=CHUNK_BYTES]
   * @param {number} [options.maxBytes=MAX_BYTES] messages past this size of file are dropped
   */
  constructor({ profile = 'ros2', library = 'colcon-wasm page', chunkBytes = CHUNK_BYTES, maxBytes = MAX_BYTES } = {}) {
    this.maxBytes = maxBytes;
    this.parts = [];
    this.size = 0;
    this.schemas = [];
    this.channels = [];
    this.chunkIndexes = [];
    this.counts = new Map();
    this.messages = 0;
    this.dropped = 0;
    this.start = null;
    this.end = null;
    this.finished = false;
    this._records = new RecordBuilder();
    this._feed = new BatchFeed();
    this._chunks = new ChunkBuilder(this._feed, {
      chunkBytes, flushMs: Infinity, sink: (chunk) => this._writeChunk(chunk),
    });
    this._append(MAGIC);
    this._append(this._records.record(Op.HEADER).string(profile).string(library).end());
  }

  _append(bytes) {
    this.parts.push(bytes);
    this.size += bytes.length;
  }

  /**
   * Add a Schema record.
   * @param {string} name e.g. `std_msgs/msg/String`
   * @param {string} encoding e.g. `ros2msg`
   * @param {Uint8Array} data its text, encoded
   * @returns {number} its id
   */
  addSchema(name, encoding, data) {
    const id = this.schemas.length + 1;
    const record = this._records.record(Op.SCHEMA).u16(id).string(name).string(encoding).bytes32(data).end();
    this.schemas.push(record);
    this._append(record);
    return id;
  }

  /**
   * Add a Channel record (before its first message).
   * @param {string} topic
   * @param {string} messageEncoding e.g. `cdr`
   * @param {number} schemaId
   * @param {Object<string, string>} [metadata]
   * @returns {number} its id
   */
  addChannel(topic, messageEncoding, schemaId, metadata = {}) {
    const id = this.channels.length + 1;
    const record = this._records.record(Op.CHANNEL).u16(id).u16(schemaId).string(topic).string(messageEncoding)
      .map(Object.entries(metadata), RecordBuilder.prototype.string, RecordBuilder.prototype.string).end();
    this.channels.push(record);
    this.counts.set(id, 0);
    this._append(record);
    this._chunks.add(id, id);
    return id;
  }

  /**
   * Add messages of one channel, as a subscription hands them over.
   * @param {number} channel its id
   * @param {{data: Uint8Array, info: {receivedTime: number, sourceTime: number}}[]} batch
   *   times in milliseconds since the epoch (log time: received, publish time: source)
   * @returns {number} how many were kept (the others were dropped: `maxBytes`)
   */
  write(channel, batch) {
    if (this.finished) throw new Error('the MCAP file is finished');
    let room = this.maxBytes - SUMMARY_ROOM - this.size - this._chunks.used - 16 * this._chunks.count;
    const kept = [];
    for (const m of batch) {
      const cost = m.data.length + PER_MESSAGE;
      if (cost > room) {
        this.dropped++;
        continue;
      }
      room -= cost;
      kept.push(m);
    }
    if (!kept.length) return 0;
    this._feed.feed(channel, kept);
    this._chunks.drain();
    this.counts.set(channel, this.counts.get(channel) + kept.length);
    this.messages += kept.length;
    return kept.length;
  }

  _writeChunk({ records, indexes, channels, start, end }) {
    const offset = this.size;
    const crc = crc32(records);
    const head = this._records.record(Op.CHUNK).u64(start).u64(end).u64(records.length).u32(crc)
      .string('').u64(records.length).end();
    // the head's length counts the records that follow it
    new DataView(head.buffer).setBigUint64(1, BigInt(head.length - 9 + records.length), true);
    this._append(head);
    this._append(records.slice());
    const chunkLength = this.size - offset;
    const indexOffsets = [];
    let at = this.size;
    for (const [channel, , length] of channels) {
      indexOffsets.push([channel, at]);
      at += length;
    }
    this._append(indexes);
    this.chunkIndexes.push({ start, end, offset, chunkLength, indexOffsets, indexLength: indexes.length, size: records.length });
    this.start = this.start === null || start < this.start ? start : this.start;
    this.end = this.end === null || end > this.end ? end : this.end;
  }

  /**
   * Close the open chunk and write DataEnd, the summary and the Footer.
   * @returns {Uint8Array[]} the file's parts, in order (`new Blob(parts)` is the file)
   */
  finish() {
    if (this.finished) return this.parts;
    this._chunks.flush();
    this.finished = true;
    const r = this._records;
    // no CRC of the whole data section (0: not computed), as the mcap C++ and
    // Python writers by default: each chunk has its own, one pass over the bytes
    this._append(r.record(Op.DATA_END).u32(0).end());
    const summaryStart = this.size;
    const summary = [];
    const groups = [];
    const group = (opcode, records) => {
      if (!records.length) return;
      const at = summaryStart + summary.reduce((n, b) => n + b.length, 0);
      summary.push(...records);
      groups.push([opcode, at, records.reduce((n, b) => n + b.length, 0)]);
    };
    group(Op.SCHEMA, this.schemas);
    group(Op.CHANNEL, this.channels);
    group(Op.STATISTICS, [r.record(Op.STATISTICS).u64(this.messages).u16(this.schemas.length)
      .u32(this.channels.length).u32(0).u32(0).u32(this.chunkIndexes.length)
      .u64(this.start ?? 0n).u64(this.end ?? 0n)
      .map(this.counts, RecordBuilder.prototype.u16, RecordBuilder.prototype.u64).end()]);
    group(Op.CHUNK_INDEX, this.chunkIndexes.map((c) => r.record(Op.CHUNK_INDEX).u64(c.start).u64(c.end)
      .u64(c.offset).u64(c.chunkLength)
      .map(c.indexOffsets, RecordBuilder.prototype.u16, RecordBuilder.prototype.u64)
      .u64(c.indexLength).string('').u64(c.size).u64(c.size).end()));
    const summaryOffsetStart = summaryStart + summary.reduce((n, b) => n + b.length, 0);
    for (const [opcode, at, length] of groups) {
      summary.push(r.record(Op.SUMMARY_OFFSET).u8(opcode).u64(at).u64(length).end());
    }
    let crc = 0;
    for (const b of summary) crc = crc32(b, crc);
    // the Footer's CRC covers the summary and the Footer up to the CRC itself
    const footer = r.record(Op.FOOTER).u64(summaryStart).u64(summaryOffsetStart).u32(0).end();
    crc = crc32(footer.subarray(0, footer.length - 4), crc);
    new DataView(footer.buffer).setUint32(footer.length - 4, crc, true);
    const tail = new Uint8Array(footer.length + MAGIC.length);
    tail.set(footer);
    tail.set(MAGIC, footer.length);
    for (const b of summary) this._append(b);
    this._append(tail);
    return this.parts;
  }
}
