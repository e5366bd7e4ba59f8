// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the page's MCAP reader and writer share (https://mcap.dev/spec): the
 * magic, the opcodes, CRC-32 (the IEEE polynomial, as zlib's) and an
 * encoder of records. Every field is little endian; a string is a uint32
 * byte length and UTF-8, a map a uint32 byte length and its entries.
 *
 * @module page/mcap_records
 */

/** The 8 bytes an MCAP file starts and ends with: 0x89 "MCAP" "0" "\r\n". */
export const MAGIC = Uint8Array.of(0x89, 0x4d, 0x43, 0x41, 0x50, 0x30, 0x0d, 0x0a);

/** Record opcodes. */
export const Op = Object.freeze({
  HEADER: 0x01,
  FOOTER: 0x02,
  SCHEMA: 0x03,
  CHANNEL: 0x04,
  MESSAGE: 0x05,
  CHUNK: 0x06,
  MESSAGE_INDEX: 0x07,
  CHUNK_INDEX: 0x08,
  ATTACHMENT: 0x09,
  ATTACHMENT_INDEX: 0x0a,
  STATISTICS: 0x0b,
  METADATA: 0x0c,
  METADATA_INDEX: 0x0d,
  SUMMARY_OFFSET: 0x0e,
  DATA_END: 0x0f,
});

/** Record names by opcode, for messages ("the Chunk record at byte offset 8"). */
export const OP_NAMES = Object.freeze(Object.fromEntries(Object.entries(Op).map(
  ([key, value]) => [value, key.toLowerCase().split('_').map((w) => w[0].toUpperCase() + w.slice(1)).join('')])));

const CRC_TABLE = (() => {
  const table = new Uint32Array(256 * 4);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  // slicing by 4: table[k * 256 + n] is the CRC of n followed by k zero bytes
  for (let n = 0; n < 256; n++) {
    for (let k = 1; k < 4; k++) {
      const prev = table[(k - 1) * 256 + n];
      table[k * 256 + n] = (table[prev & 0xff] ^ (prev >>> 8)) >>> 0;
    }
  }
  return table;
})();

/**
 * CRC-32 of `bytes`, continuing from `crc` (the CRC of what came before).
 * @param {Uint8Array} bytes
 * @param {number} [crc=0]
 * @returns {number} an unsigned 32-bit value
 */
export function crc32(bytes, crc = 0) {
  const t = CRC_TABLE;
  let c = ~crc >>> 0;
  let i = 0;
  const n = bytes.length;
  for (; i + 4 <= n; i += 4) {
    c ^= bytes[i] | (bytes[i + 1] << 8) | (bytes[i + 2] << 16) | (bytes[i + 3] << 24);
    c = t[768 + (c & 0xff)] ^ t[512 + ((c >>> 8) & 0xff)] ^ t[256 + ((c >>> 16) & 0xff)] ^ t[c >>> 24];
  }
  for (; i < n; i++) c = t[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return ~c >>> 0;
}

const encoder = new TextEncoder();

/**
 * One record (or the content of one) being encoded: `u8`, `u16`, ... append
 * fields, `end()` returns the bytes. A record begins with `record(opcode)`,
 * whose length `end()` fills in.
 */
export class RecordBuilder {
  constructor() {
    this.buffer = new Uint8Array(256);
    this.view = new DataView(this.buffer.buffer);
    this.length = 0;
    this._record = -1;
  }

  _room(n) {
    if (this.length + n <= this.buffer.length) return;
    let size = this.buffer.length * 2;
    while (size < this.length + n) size *= 2;
    const bigger = new Uint8Array(size);
    bigger.set(this.buffer.subarray(0, this.length));
    this.buffer = bigger;
    this.view = new DataView(bigger.buffer);
  }

  /** Start a record of `opcode` (its uint64 length is written by `end`). */
  record(opcode) {
    this.u8(opcode);
    this._record = this.length;
    return this.u64(0);
  }

  /** Append a uint8. */
  u8(x) { this._room(1); this.view.setUint8(this.length, x); this.length += 1; return this; }

  /** Append a uint16. */
  u16(x) { this._room(2); this.view.setUint16(this.length, x, true); this.length += 2; return this; }

  /** Append a uint32. */
  u32(x) { this._room(4); this.view.setUint32(this.length, x >>> 0, true); this.length += 4; return this; }

  /** Append a uint64 (a BigInt, or a whole number in a double). */
  u64(x) {
    this._room(8);
    this.view.setBigUint64(this.length, typeof x === 'bigint' ? x : BigInt(Math.round(x)), true);
    this.length += 8;
    return this;
  }

  /** Append raw bytes. */
  raw(bytes) {
    this._room(bytes.length);
    this.buffer.set(bytes, this.length);
    this.length += bytes.length;
    return this;
  }

  /** Append a string: uint32 byte length, UTF-8. */
  string(text) {
    const bytes = encoder.encode(text);
    return this.u32(bytes.length).raw(bytes);
  }

  /** Append bytes with a uint32 length. */
  bytes32(bytes) { return this.u32(bytes.length).raw(bytes); }

  /**
   * Append a map: uint32 byte length, then each entry with `writeKey` and `writeValue`.
   * @param {Iterable<Array>} entries [key, value] pairs
   */
  map(entries, writeKey, writeValue) {
    const at = this.length;
    this.u32(0);
    for (const [key, value] of entries) {
      writeKey.call(this, key);
      writeValue.call(this, value);
    }
    this.view.setUint32(at, this.length - at - 4, true);
    return this;
  }

  /** The bytes so far (the open record's length filled in); the builder is empty again. */
  end() {
    if (this._record >= 0) this.view.setBigUint64(this._record, BigInt(this.length - this._record - 8), true);
    const out = this.buffer.slice(0, this.length);
    this.length = 0;
    this._record = -1;
    return out;
  }
}
