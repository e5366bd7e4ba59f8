// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bag file, written by the Node host itself (`--record` without
 * compression): each batch of chunks the recording worker closes goes to
 * the file in one `writev`, each chunk as its Chunk record (uncompressed, with the CRC-32 of its
 * records, which the worker computed) and its MessageIndex records, at the
 * file's shared offset. The launcher wrote the magic and the Header before,
 * writes the summary after, and hands over the Schema and Channel records it
 * builds for each topic (`writeRecords`), which reach the file before the
 * first chunk that uses them.
 *
 * Writes are asynchronous (libuv's thread pool) and one at a time, in the
 * order they were asked for: the recording worker never waits for the
 * disk, so a slow write does not make it miss messages; what waits is
 * bounded (`maxQueuedBytes`), beyond it chunks are dropped and counted.
 * No byte of a message is copied on its way from the chunk buffer to the
 * file, and nothing goes through the launcher's pipe but a small report per
 * write (`onWritten`, a line per chunk), from which the launcher builds the
 * chunk indexes.
 *
 * @module bridges/record/file_sink
 */

import { ftruncate, writev } from 'node:fs';

const OP_CHUNK = 0x06;
/** opcode, record length, start, end, uncompressed size, CRC, compression length, records length */
const CHUNK_HEAD = 1 + 8 + 8 + 8 + 8 + 4 + 4 + 8;

export class FileSink {
  /**
   * @param {object} options
   * @param {number} options.fd the bag, open for writing at `offset` (the launcher's descriptor)
   * @param {number} options.offset where the next record goes (after the launcher's Header)
   * @param {number} options.maxQueuedBytes chunks beyond this many bytes waiting are dropped
   * @param {function(object[]): void} options.onWritten gets the reports of each write (one per
   *   record or chunk written)
   * @param {function({code: string, message: string, kept: number}): void} options.onFailed
   *   a write failed: the file was cut back to `kept` bytes, nothing more is written
   */
  constructor({ fd, offset, maxQueuedBytes, onWritten, onFailed }) {
    this.fd = fd;
    /** the end of the last whole write */
    this.position = offset;
    this.maxQueuedBytes = maxQueuedBytes;
    this.onWritten = onWritten;
    this.onFailed = onFailed;
    this.queue = [];
    this.queuedBytes = 0;
    this.writing = false;
    this.failed = null;
    /** resolves when nothing waits (see `drained`) */
    this._idle = [];
  }

  /** Write records the launcher built (Schema, Channel): whole, before any chunk asked for later. */
  writeRecords(bytes) {
    if (!bytes.length || this.failed) return;
    this._enqueue([bytes], (at) => [{ kind: 'records', offset: at, end: at + bytes.length }]);
  }

  /**
   * Write closed chunks of the recording worker, in this order, in one go.
   * Each gets its `release()` called once its buffers are no longer needed.
   * @param {{records: Uint8Array, indexes: Uint8Array, crc: number, start: bigint, end: bigint,
   *   messages: number, channels: number[][], release: function(): void}[]} chunks
   * @returns {boolean} false when they were dropped (a failed file, or too much waiting)
   */
  writeChunks(chunks) {
    const done = () => { for (const c of chunks) c.release(); };
    let size = 0;
    for (const c of chunks) size += c.records.length;
    if (this.failed || this.queuedBytes + size > this.maxQueuedBytes) {
      done();
      return false;
    }
    const parts = [];
    const layout = [];
    for (const chunk of chunks) {
      const { records, indexes } = chunk;
      parts.push(chunkHead(chunk), records, indexes);
      layout.push({
        chunkLength: CHUNK_HEAD + records.length, indexLength: indexes.length, size: records.length,
        crc: chunk.crc, start: String(chunk.start), end: String(chunk.end), messages: chunk.messages,
        channels: chunk.channels,
      });
    }
    this._enqueue(parts, (at) => layout.map((l) => {
      const report = { kind: 'chunk', offset: at, ...l };
      at += l.chunkLength + l.indexLength;
      return report;
    }), done);
    return true;
  }

  /** Resolves once every write asked for is done (or failed). */
  drained() {
    if (!this.writing) return Promise.resolve();
    return new Promise((resolve) => this._idle.push(resolve));
  }

  _enqueue(parts, report, done = () => {}) {
    let bytes = 0;
    for (const p of parts) bytes += p.length;
    this.queue.push({ parts, bytes, report, done });
    this.queuedBytes += bytes;
    if (!this.writing) this._next();
  }

  _next() {
    const job = this.queue.shift();
    if (!job) {
      this.writing = false;
      for (const resolve of this._idle.splice(0)) resolve();
      return;
    }
    this.writing = true;
    const at = this.position;
    this._writeAll(job.parts, 0, job.bytes, (error) => {
      this.queuedBytes -= job.bytes;
      // the report before done(): done gives the buffers away (they detach)
      const report = error ? null : job.report(at);
      job.done();
      if (error) {
        this._fail(error);
        return;
      }
      this.position = at + job.bytes;
      this.onWritten(report);
      this._next();
    });
  }

  /** writev until all of `parts` is written (a writev may write part of them). */
  _writeAll(parts, written, total, callback) {
    writev(this.fd, remaining(parts, written), (error, n) => {
      if (error) callback(error);
      else if (n <= 0) callback(Object.assign(new Error('the file takes no more bytes'), { code: 'EIO' }));
      else if (written + n < total) this._writeAll(parts, written + n, total, callback);
      else callback(null);
    });
  }

  /**
   * A record cut off would end the stream readers' file there with an
   * error: the file ends after its last whole record instead, and nothing
   * more is written.
   */
  _fail(error) {
    const kept = this.position;
    this.failed = error;
    for (const job of this.queue.splice(0)) job.done();
    this.queuedBytes = 0;
    ftruncate(this.fd, kept, () => {
      // on an error here the launcher cuts the file to the end it was told of
      this.writing = false;
      this.onFailed({ code: error.code || 'EIO', message: `writing the bag failed: ${error.message}`, kept });
      for (const resolve of this._idle.splice(0)) resolve();
    });
  }
}

/** The head of an uncompressed Chunk record (its records and indexes follow). */
function chunkHead(chunk) {
  const length = chunk.records.length;
  const head = new Uint8Array(CHUNK_HEAD);
  const v = new DataView(head.buffer);
  v.setUint8(0, OP_CHUNK);
  v.setBigUint64(1, BigInt(CHUNK_HEAD - 9 + length), true);
  v.setBigUint64(9, chunk.start, true);
  v.setBigUint64(17, chunk.end, true);
  v.setBigUint64(25, BigInt(length), true);
  v.setUint32(33, chunk.crc, true);
  v.setUint32(37, 0, true); // compression: none ('')
  v.setBigUint64(41, BigInt(length), true);
  return head;
}

/** The parts after the first `skip` bytes (a writev that wrote part of them). */
function remaining(parts, skip) {
  if (skip === 0) return parts;
  const out = [];
  for (const p of parts) {
    if (skip >= p.length) {
      skip -= p.length;
      continue;
    }
    out.push(skip ? p.subarray(skip) : p);
    skip = 0;
  }
  return out;
}
