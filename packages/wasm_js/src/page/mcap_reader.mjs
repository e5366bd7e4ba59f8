// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * Read an MCAP file held in memory (https://mcap.dev/spec), for the page's
 * player: its Header, Schemas, Channels and Messages, in log-time order
 * across chunks.
 *
 * The file is read from its magic, record by record, as a stream reader
 * does: the summary, the indexes and the statistics are not needed (a file
 * cut off before its summary reads up to the cut). Chunks are read when
 * they are not compressed; a browser has no zstd or lz4 decompressor
 * (DecompressionStream has gzip and deflate only), so a compressed chunk
 * refuses the whole file with {@link McapRefused}, before anything plays.
 * A record that is cut off or corrupt (a length past the end of the file or
 * of its chunk, a chunk's CRC, a message on a channel no Channel record
 * described) ends the reading there: what came before is kept and `error`
 * names the record and its byte offset.
 *
 * @module page/mcap_reader
 */

import { crc32, MAGIC, Op, OP_NAMES } from './mcap_records.mjs';

/** A file that is no MCAP file, or an MCAP file this reader does not read. */
export class McapError extends Error {
  constructor(message) {
    super(message);
    this.name = 'McapError';
  }
}

/** An MCAP file refused as a whole: compressed chunks (`compression` names it). */
export class McapRefused extends McapError {
  constructor(message, compression) {
    super(message);
    this.name = 'McapRefused';
    this.compression = compression;
  }
}

/** A record that ends the reading (cut off or corrupt); internal. */
class Broken extends Error {}

const decoder = new TextDecoder('utf-8', { fatal: true });

/** Fields of one record's content, read with bounds checks. */
class Fields {
  constructor(bytes, start, end) {
    this.bytes = bytes;
    this.view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    this.at = start;
    this.end = end;
  }

  _need(n, what) {
    if (this.at + n > this.end) throw new Broken(`its ${what} goes past the end of the record`);
  }

  u8(what) { this._need(1, what); return this.view.getUint8(this.at++); }

  u16(what) { this._need(2, what); const x = this.view.getUint16(this.at, true); this.at += 2; return x; }

  u32(what) { this._need(4, what); const x = this.view.getUint32(this.at, true); this.at += 4; return x; }

  u64(what) { this._need(8, what); const x = this.view.getBigUint64(this.at, true); this.at += 8; return x; }

  /** `n` bytes, a view (no copy). */
  take(n, what) {
    if (typeof n === 'bigint') {
      if (n > BigInt(this.end - this.at)) throw new Broken(`its ${what} goes past the end of the record`);
      n = Number(n);
    }
    this._need(n, what);
    const out = this.bytes.subarray(this.at, this.at + n);
    this.at += n;
    return out;
  }

  string(what) {
    try {
      return decoder.decode(this.take(this.u32(what), what));
    } catch (e) {
      if (e instanceof Broken) throw e;
      throw new Broken(`its ${what} is not UTF-8`);
    }
  }

  map(what, readValue) {
    const length = this.u32(what);
    if (this.at + length > this.end) throw new Broken(`its ${what} goes past the end of the record`);
    const inner = new Fields(this.bytes, this.at, this.at + length);
    const out = {};
    while (inner.at < inner.end) {
      const key = inner.string(`${what} key`);
      out[key] = readValue(inner);
    }
    this.at += length;
    return out;
  }
}

/**
 * A channel of the file.
 * @typedef {object} McapChannel
 * @property {number} id
 * @property {number} schemaId 0: none
 * @property {string} topic
 * @property {string} messageEncoding
 * @property {Object<string, string>} metadata
 */

/**
 * A message of the file.
 * @typedef {object} McapMessage
 * @property {number} channelId
 * @property {number} sequence
 * @property {bigint} logTime nanoseconds
 * @property {bigint} publishTime nanoseconds
 * @property {Uint8Array} data a view into the file's bytes
 */

/**
 * What a file holds.
 * @typedef {object} McapContent
 * @property {string} profile the Header's profile (`ros2` for rosbag2)
 * @property {string} library the Header's library
 * @property {Map<number, {id: number, name: string, encoding: string, data: Uint8Array}>} schemas
 * @property {Map<number, McapChannel>} channels
 * @property {McapMessage[]} messages in log-time order (file order among equal times)
 * @property {?string} error where the file stops being readable (the messages
 *   before it were read), or null
 */

/**
 * Read an MCAP file.
 * @param {Uint8Array} bytes the whole file
 * @param {object} [options]
 * @param {string} [options.name] the file's name, for messages
 * @returns {McapContent}
 * @throws {McapError} when it is no MCAP file; {@link McapRefused} for a compressed chunk
 */
export function readMcap(bytes, { name = 'the file' } = {}) {
  const label = `'${name}'`;
  if (bytes.length < MAGIC.length || !MAGIC.every((b, i) => bytes[i] === b)) {
    throw new McapError(`${label} is not an MCAP file: it does not start with the MCAP magic`);
  }
  const content = {
    profile: '', library: '', schemas: new Map(), channels: new Map(), messages: [], error: null,
  };
  let offset = MAGIC.length;
  let ended = false;
  let what = 'record';
  try {
    let first = true;
    while (offset < bytes.length) {
      what = 'record';
      if (bytes.length - offset < 9) throw new Broken('is cut off');
      const opcode = bytes[offset];
      what = `${OP_NAMES[opcode] || `unknown (opcode 0x${opcode.toString(16).padStart(2, '0')})`} record`;
      const length = new DataView(bytes.buffer, bytes.byteOffset + offset + 1, 8).getBigUint64(0, true);
      const left = BigInt(bytes.length - offset - 9);
      if (length > left) {
        throw new Broken(`is cut off: it is ${length} bytes long, the file ends ${left} bytes into it`);
      }
      const start = offset + 9;
      const end = start + Number(length);
      if (first && opcode !== Op.HEADER) throw new Broken('comes first, where the Header record must be');
      first = false;
      if (opcode === Op.FOOTER) {
        ended = true;
        break;
      }
      readRecord(content, opcode, new Fields(bytes, start, end), label, offset);
      offset = end;
    }
  } catch (e) {
    if (!(e instanceof Broken)) throw e;
    const how = e.message.startsWith('its ') ? `is broken: ${e.message}` : e.message;
    content.error = `${label}: the ${what} at byte offset ${offset} ${how}; the messages before it were read`;
  }
  if (!ended && content.error === null) {
    content.error = `${label} ends at byte ${offset} without a Footer record: it was cut off `
      + '(the recording did not finish); the messages before it were read';
  }
  // log-time order across chunks; Array.prototype.sort is stable (file order among equals)
  content.messages.sort((a, b) => (a.logTime < b.logTime ? -1 : a.logTime > b.logTime ? 1 : 0));
  return content;
}

function readRecord(content, opcode, f, label, offset) {
  switch (opcode) {
    case Op.HEADER:
      content.profile = f.string('profile');
      content.library = f.string('library');
      break;
    case Op.SCHEMA: {
      const id = f.u16('id');
      const name = f.string('name');
      const encoding = f.string('encoding');
      const data = f.take(f.u32('data length'), 'data');
      // id 0 is "no schema"; a schema seen again (the summary repeats them) is the same one
      if (id !== 0 && !content.schemas.has(id)) content.schemas.set(id, { id, name, encoding, data });
      break;
    }
    case Op.CHANNEL: {
      const id = f.u16('id');
      const schemaId = f.u16('schema id');
      const topic = f.string('topic');
      const messageEncoding = f.string('message encoding');
      const metadata = f.map('metadata', (inner) => inner.string('metadata value'));
      if (!content.channels.has(id)) content.channels.set(id, { id, schemaId, topic, messageEncoding, metadata });
      break;
    }
    case Op.MESSAGE:
      content.messages.push(readMessage(content, f));
      break;
    case Op.CHUNK:
      readChunk(content, f, label, offset);
      break;
    default:
      // indexes, statistics, attachments, metadata, summary offsets, DataEnd
      // and records of later versions: not needed to play, skipped
      break;
  }
}

function readMessage(content, f) {
  const channelId = f.u16('channel id');
  const sequence = f.u32('sequence');
  const logTime = f.u64('log time');
  const publishTime = f.u64('publish time');
  if (!content.channels.has(channelId)) {
    throw new Broken(`its channel ${channelId} is described by no Channel record before it`);
  }
  return { channelId, sequence, logTime, publishTime, data: f.take(f.end - f.at, 'data') };
}

function readChunk(content, f, label, offset) {
  f.u64('message start time');
  f.u64('message end time');
  const size = f.u64('uncompressed size');
  const crc = f.u32('uncompressed CRC');
  const compression = f.string('compression');
  const records = f.take(f.u64('records length'), 'records');
  if (compression !== '') {
    throw new McapRefused(
      `${label}: its chunks are compressed with ${compression} (the Chunk record at byte offset ${offset}), `
      + `and a page cannot decompress ${compression} (browsers have gzip and deflate only): play it under `
      + "'colcon-wasm serve', or write an uncompressed copy to play here ('mcap decompress IN.mcap -o OUT.mcap', "
      + "or 'ros2 bag convert' to a bag with no compression)", compression);
  }
  if (size !== BigInt(records.length)) {
    throw new Broken(`is corrupt: it says ${size} bytes of records and holds ${records.length}`);
  }
  if (crc !== 0 && crc32(records) !== crc) {
    throw new Broken(`is corrupt: the CRC of its records is 0x${crc32(records).toString(16)}, not the 0x${crc.toString(16)} it says`);
  }
  let at = 0;
  while (at < records.length) {
    if (records.length - at < 9) throw new Broken(`is corrupt: a record at byte ${at} of its records is cut off`);
    const opcode = records[at];
    const length = new DataView(records.buffer, records.byteOffset + at + 1, 8).getBigUint64(0, true);
    if (length > BigInt(records.length - at - 9)) {
      throw new Broken(`is corrupt: the record at byte ${at} of its records goes past the chunk's end`);
    }
    const start = at + 9;
    const end = start + Number(length);
    const inner = new Fields(records, start, end);
    try {
      if (opcode === Op.SCHEMA || opcode === Op.CHANNEL || opcode === Op.MESSAGE) readRecord(content, opcode, inner, label, offset);
    } catch (e) {
      if (!(e instanceof Broken)) throw e;
      throw new Broken(`is corrupt: the ${OP_NAMES[opcode]} record at byte ${at} of its records is broken (${e.message})`);
    }
    at = end;
  }
}
