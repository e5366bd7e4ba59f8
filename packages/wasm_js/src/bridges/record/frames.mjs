// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The frames between the Node.js launcher and the launcher, one pipe each way:
 * `u32 length` (of what follows), `u8 kind`, the body; little endian.
 * colcon_wasm/record/frames.py is the other side and describes the bodies.
 *
 * @module bridges/record/frames
 */

export const Kind = Object.freeze({ CHANNEL: 1, MESSAGE: 2, NOTE: 3, END: 4 });

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
 * The head of a recorded message's frame (channel, log and publish times in ms
 * since the epoch); the CDR bytes follow it.
 */
export function messageHead(channel, logMs, publishMs, length) {
  const out = new Uint8Array(25);
  const view = new DataView(out.buffer);
  view.setUint32(0, 1 + 20 + length, true);
  out[4] = Kind.MESSAGE;
  view.setUint32(5, channel, true);
  view.setFloat64(9, logMs, true);
  view.setFloat64(17, publishMs, true);
  return out;
}

/** A recorded message's whole frame. */
export function messageFrame(channel, logMs, publishMs, data) {
  const out = new Uint8Array(5 + 20 + data.length);
  const view = new DataView(out.buffer);
  view.setUint32(0, 1 + 20 + data.length, true);
  out[4] = Kind.MESSAGE;
  view.setUint32(5, channel, true);
  view.setFloat64(9, logMs, true);
  view.setFloat64(17, publishMs, true);
  out.set(data, 25);
  return out;
}

/**
 * Cuts a byte stream into frames: `push(chunk)` returns the whole frames
 * received so far as {kind, json} or, for messages to play,
 * {kind, channel, sec, nanosec, offsetNs, data}.
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
