// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bag file, written by the recording worker itself (Node.js, `--record`
 * without compression): each closed chunk goes to the file in one `writev`
 * as its Chunk record (uncompressed, with the CRC-32 of its records) and its
 * MessageIndex records, at the file's shared offset. The launcher wrote the
 * magic and the Header before, writes the summary after, and hands over the
 * Schema and Channel records it builds for each topic (`writeRecords`) so
 * that they reach the file before the first chunk that uses them.
 *
 * No byte of a message is copied on its way from the chunk buffer to the
 * file, and nothing goes through the launcher's pipe but a small report per
 * write (`onWritten`), from which the launcher builds the chunk indexes.
 *
 * @module bridges/record/file_sink
 */

import { ftruncateSync, writevSync } from 'node:fs';
import zlib from 'node:zlib';

const OP_CHUNK = 0x06;
/** opcode, record length, start, end, uncompressed size, CRC, compression length, records length */
const CHUNK_HEAD = 1 + 8 + 8 + 8 + 8 + 4 + 4 + 8;
/** Node.js 20.15 and later: the C CRC-32 of zlib; else the records go without one (CRC 0, allowed). */
const crc32 = typeof zlib.crc32 === 'function' ? zlib.crc32 : null;

/** A write to the bag failed: the file was cut back to its last whole record. */
export class BagWriteError extends Error {
  /**
   * @param {Error} cause the write's error (code ENOSPC, EFBIG, EDQUOT, EIO, ...)
   * @param {number} kept the length of the file now
   */
  constructor(cause, kept) {
    super(`writing the bag failed: ${cause.message}`);
    this.name = 'BagWriteError';
    this.code = cause.code || 'EIO';
    this.errno = cause.errno;
    this.kept = kept;
  }
}

export class FileSink {
  /**
   * @param {object} options
   * @param {number} options.fd the bag, open for writing at `offset` (the launcher's descriptor)
   * @param {number} options.offset where the next record goes (after the launcher's Header)
   * @param {function(object): void} options.onWritten gets a report after each write
   */
  constructor({ fd, offset, onWritten }) {
    this.fd = fd;
    this.position = offset;
    this.onWritten = onWritten;
    this.head = new Uint8Array(CHUNK_HEAD);
    this.headView = new DataView(this.head.buffer);
    this.failed = null;
  }

  /** Write records the launcher built (Schema, Channel): whole, before any chunk using them. */
  writeRecords(bytes) {
    if (!bytes.length) return;
    const at = this.position;
    this._write([bytes]);
    this.onWritten({ kind: 'records', offset: at, end: this.position });
  }

  /**
   * Write a closed chunk (a ChunkBuilder sink: its buffer is free again on return).
   * @param {import('./chunk_builder.mjs').ClosedChunk} chunk
   * @returns {boolean} true
   */
  chunk(chunk) {
    const { records, indexes } = chunk;
    const v = this.headView;
    v.setUint8(0, OP_CHUNK);
    v.setBigUint64(1, BigInt(CHUNK_HEAD - 9 + records.length), true);
    v.setBigUint64(9, chunk.start, true);
    v.setBigUint64(17, chunk.end, true);
    v.setBigUint64(25, BigInt(records.length), true);
    const crc = crc32 ? crc32(records) : 0;
    v.setUint32(33, crc, true);
    v.setUint32(37, 0, true); // compression: none ('')
    v.setBigUint64(41, BigInt(records.length), true);
    const at = this.position;
    this._write([this.head, records, indexes]);
    this.onWritten({
      kind: 'chunk', offset: at, chunkLength: CHUNK_HEAD + records.length,
      indexLength: indexes.length, size: records.length, crc,
      start: String(chunk.start), end: String(chunk.end), messages: chunk.messages,
      channels: chunk.channels,
    });
    return true;
  }

  /** Write all of `parts` at the position; on failure cut the file back and throw BagWriteError. */
  _write(parts) {
    if (this.failed) throw this.failed;
    let total = 0;
    for (const p of parts) total += p.length;
    let written = 0;
    try {
      while (written < total) {
        const n = writevSync(this.fd, remaining(parts, written));
        if (n <= 0) throw Object.assign(new Error('the file takes no more bytes'), { code: 'EIO' });
        written += n;
      }
    } catch (e) {
      // a record cut off would end the stream readers' file there with an error:
      // the file ends after its last whole record instead
      try {
        ftruncateSync(this.fd, this.position);
      } catch (ignored) {
        // the launcher cuts the file to the last whole record it was told of
      }
      this.failed = new BagWriteError(e, this.position);
      throw this.failed;
    }
    this.position += total;
  }
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
