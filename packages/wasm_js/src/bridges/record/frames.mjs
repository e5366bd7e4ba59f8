// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The frames between the Node.js launcher and the launcher, one pipe each way:
 * `u32 length` (of what follows), `u8 kind`, the body; little endian.
 * colcon_wasm/record/frames.py is the other side and describes the bodies.
 *
 * @module bridges/record/frames
 */

export const Kind = Object.freeze({
  CHANNEL: 1, MESSAGE: 2, NOTE: 3, END: 4, CHUNK: 5, READY: 6, REFUSED: 7, WRITTEN: 8, FAILED: 9,
});

const encoder = new TextEncoder();
const decoder = new TextDecoder();

/** A frame with a JSON body. */
export function jsonFrame(kind, value) {
  const body = encoder.encode(JSON.stringify(value));
  const out = new Uint8Array(5 + body.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, body.length + 1, true);
  out[4] = kind;
  out.set(body, 5);
  return out;
}

/**
 * The head of a recorded chunk's frame: the JSON of its times, message count
 * and per-channel message indexes, then (`bodyBytes` of them) the chunk's
 * records and its MessageIndex records follow.
 * @param {{length: number, start: bigint, end: bigint, messages: number, channels: number[][]}} chunk
 * @param {number} bodyBytes records and indexes, in bytes
 */
export function chunkHead(chunk, bodyBytes) {
  const meta = encoder.encode(JSON.stringify({
    records: chunk.length, start: String(chunk.start), end: String(chunk.end),
    messages: chunk.messages, channels: chunk.channels,
  }));
  const out = new Uint8Array(9 + meta.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, 1 + 4 + meta.length + bodyBytes, true);
  out[4] = Kind.CHUNK;
  view.setUint32(5, meta.length, true);
  out.set(meta, 9);
  return out;
}

/**
 * Cuts a byte stream into frames: `push(chunk)` returns the whole frames
 * received so far as {kind, json} or, for messages to play,
 * {kind, channel, sec, nanosec, offsetNs, data}, or for a recorded
 * channel's answer {kind: READY, channel, records}.
 */
export class FrameReader {
  constructor() {
    this._parts = [];
    this._size = 0;
  }

  push(chunk) {
    this._parts.push(chunk);
    this._size += chunk.length;
    const frames = [];
    let buffer = this._parts.length === 1 ? this._parts[0] : Buffer.concat(this._parts, this._size);
    let at = 0;
    while (buffer.length - at >= 5) {
      const length = buffer.readUInt32LE(at);
      if (buffer.length - at < 4 + length) break;
      const kind = buffer[at + 4];
      const body = buffer.subarray(at + 5, at + 4 + length);
      if (kind === Kind.MESSAGE) {
        frames.push({
          kind,
          channel: body.readUInt32LE(0),
          sec: body.readUInt32LE(4),
          nanosec: body.readUInt32LE(8),
          offsetNs: body.readDoubleLE(12),
          data: new Uint8Array(body.subarray(20)), // a copy: the buffer is reused
        });
      } else if (kind === Kind.READY) {
        // a copy: the buffer is reused
        frames.push({ kind, channel: body.readUInt32LE(0), records: new Uint8Array(body.subarray(4)) });
      } else {
        frames.push({ kind, json: JSON.parse(decoder.decode(body)) });
      }
      at += 4 + length;
    }
    buffer = buffer.subarray(at);
    this._parts = buffer.length ? [buffer] : [];
    this._size = buffer.length;
    return frames;
  }
}
