// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * WebSocket frames (RFC 6455 section 5), both directions, no I/O: a parser
 * that takes bytes as they come off a socket and yields whole messages
 * (fragmented messages reassembled, control frames answered through
 * callbacks), and the encoder of frames. Text and binary data frames,
 * continuation, close, ping and pong; masking (client to server); no
 * extensions (permessage-deflate is not negotiated, so RSV bits are errors).
 *
 * @module bridges/rosbridge/ws_frames
 */

export const Opcode = Object.freeze({
  CONTINUATION: 0x0, TEXT: 0x1, BINARY: 0x2, CLOSE: 0x8, PING: 0x9, PONG: 0xa,
});

/** Close codes (RFC 6455 section 7.4.1). */
export const CloseCode = Object.freeze({
  NORMAL: 1000, GOING_AWAY: 1001, PROTOCOL_ERROR: 1002, UNSUPPORTED: 1003,
  INVALID_DATA: 1007, POLICY: 1008, TOO_BIG: 1009, INTERNAL: 1011,
});

/** A violation of the protocol by the peer; `code` is the close code to send. */
export class FrameError extends Error {
  constructor(code, message) {
    super(message);
    this.name = 'FrameError';
    this.code = code;
  }
}

const utf8 = new TextDecoder('utf-8', { fatal: true });

/**
 * Encode one frame.
 * @param {number} opcode
 * @param {Uint8Array} payload
 * @param {object} [options]
 * @param {boolean} [options.mask=false] mask the payload (a client must)
 * @param {boolean} [options.fin=true]
 * @returns {Uint8Array[]} header and payload (the payload is not copied unless masked)
 */
export function encodeFrame(opcode, payload, { mask = false, fin = true } = {}) {
  const len = payload.length;
  const ext = len < 126 ? 0 : len < 65536 ? 2 : 8;
  const header = new Uint8Array(2 + ext + (mask ? 4 : 0));
  header[0] = (fin ? 0x80 : 0) | opcode;
  header[1] = (mask ? 0x80 : 0) | (ext === 0 ? len : ext === 2 ? 126 : 127);
  const view = new DataView(header.buffer);
  if (ext === 2) view.setUint16(2, len);
  else if (ext === 8) view.setBigUint64(2, BigInt(len));
  if (!mask) return [header, payload];
  const key = header.subarray(2 + ext);
  crypto.getRandomValues(key);
  const masked = new Uint8Array(len);
  for (let i = 0; i < len; i++) masked[i] = payload[i] ^ key[i & 3];
  return [header, masked];
}

/** The payload of a close frame: a code and a UTF-8 reason (at most 123 bytes). */
export function closePayload(code, reason = '') {
  let text = new TextEncoder().encode(reason);
  if (text.length > 123) text = text.subarray(0, 123);
  const out = new Uint8Array(2 + text.length);
  out[0] = code >> 8;
  out[1] = code & 0xff;
  out.set(text, 2);
  return out;
}

/**
 * Incremental frame parser. Feed it chunks with `push()`; it calls
 *   onMessage(data: string|Uint8Array, binary: boolean)
 *   onControl(opcode, payload: Uint8Array)   (close, ping, pong)
 * and throws FrameError on a protocol violation. A message larger than
 * `maxMessageBytes` is skipped (its bytes are read and dropped) and
 * reported to `onOversize(bytes)`, so the connection stays up; without
 * `onOversize` it is a FrameError (close code 1009).
 */
export class FrameParser {
  /**
   * @param {object} options
   * @param {boolean} options.expectMasked frames from a client are masked, from a server not
   * @param {number} options.maxMessageBytes largest message (after reassembly)
   * @param {function(string|Uint8Array, boolean): void} options.onMessage
   * @param {function(number, Uint8Array): void} options.onControl
   * @param {function(number): void} [options.onOversize]
   */
  constructor({ expectMasked, maxMessageBytes, onMessage, onControl, onOversize }) {
    this.expectMasked = expectMasked;
    this.onOversize = onOversize;
    this._skip = 0;          // payload bytes of an oversized frame still to drop
    this._skipMessage = false; // the rest of an oversized fragmented message is dropped too
    this.maxMessageBytes = maxMessageBytes;
    this.onMessage = onMessage;
    this.onControl = onControl;
    this._chunks = [];
    this._buffered = 0;
    this._parts = null;     // fragments of the message being reassembled
    this._partsBytes = 0;
    this._partsOpcode = 0;
  }

  /** @param {Uint8Array} chunk bytes read from the socket */
  push(chunk) {
    if (chunk.length === 0) return;
    this._chunks.push(chunk);
    this._buffered += chunk.length;
    for (;;) {
      if (this._skip) {
        const n = Math.min(this._skip, this._buffered);
        if (n === 0) return;
        this._take(n);
        this._skip -= n;
        if (this._skip) return;
      }
      const frame = this._next();
      if (!frame) return;
      if (!frame.skip) this._frame(frame);
    }
  }

  _peek(n) {
    // the first n buffered bytes, as one array (joins chunks only when needed)
    if (this._chunks[0].length >= n) return this._chunks[0];
    const joined = this._take(this._buffered);
    this._chunks = [joined];
    this._buffered = joined.length;
    return joined;
  }

  _take(n) {
    const first = this._chunks[0];
    if (first.length === n) {
      this._chunks.shift();
      this._buffered -= n;
      return first;
    }
    if (first.length > n) {
      this._chunks[0] = first.subarray(n);
      this._buffered -= n;
      return first.subarray(0, n);
    }
    const out = new Uint8Array(n);
    let off = 0;
    while (off < n) {
      const c = this._chunks[0];
      const k = Math.min(c.length, n - off);
      out.set(c.subarray(0, k), off);
      off += k;
      if (k === c.length) this._chunks.shift();
      else this._chunks[0] = c.subarray(k);
    }
    this._buffered -= n;
    return out;
  }

  _next() {
    if (this._buffered < 2) return null;
    let head = this._peek(2);
    const b0 = head[0];
    const b1 = head[1];
    const masked = (b1 & 0x80) !== 0;
    let len = b1 & 0x7f;
    const ext = len === 126 ? 2 : len === 127 ? 8 : 0;
    const headerBytes = 2 + ext + (masked ? 4 : 0);
    if (this._buffered < headerBytes) return null;
    head = this._peek(headerBytes);
    const view = new DataView(head.buffer, head.byteOffset, headerBytes);
    if (ext === 2) len = view.getUint16(2);
    else if (ext === 8) {
      const big = view.getBigUint64(2);
      if (big > BigInt(Number.MAX_SAFE_INTEGER)) throw new FrameError(CloseCode.TOO_BIG, `a frame of ${big} bytes`);
      len = Number(big);
    }
    const opcode = b0 & 0x0f;
    const fin = (b0 & 0x80) !== 0;
    if ((b0 & 0x70) !== 0) throw new FrameError(CloseCode.PROTOCOL_ERROR, 'a frame has RSV bits set, but no extension was negotiated');
    if (masked !== this.expectMasked) {
      throw new FrameError(CloseCode.PROTOCOL_ERROR, this.expectMasked
        ? 'a client frame is not masked (RFC 6455 5.1)' : 'a server frame is masked (RFC 6455 5.1)');
    }
    const data = opcode < 0x8;
    // before its payload is buffered: a ping that claims 2^53 bytes is refused at its header
    if (!data && (!fin || len > 125)) throw new FrameError(CloseCode.PROTOCOL_ERROR, 'a control frame is fragmented or longer than 125 bytes');
    if (data && (this._skipMessage || len > this.maxMessageBytes || this._partsBytes + len > this.maxMessageBytes)) {
      if (!this.onOversize) throw new FrameError(CloseCode.TOO_BIG, `a message of more than ${this.maxMessageBytes} bytes (the limit) was sent`);
      this._take(headerBytes);
      this._skip = len;
      if (!this._skipMessage) this.onOversize(this._partsBytes + len);
      this._skipMessage = !fin;
      this._parts = null;
      this._partsBytes = 0;
      return { skip: true };
    }
    if (this._buffered < headerBytes + len) return null;
    const key = masked ? head.slice(2 + ext, headerBytes) : null;
    this._take(headerBytes);
    let payload = len ? this._take(len) : new Uint8Array(0);
    if (key) {
      if (payload.byteOffset !== 0 || payload.buffer.byteLength !== len) payload = payload.slice();
      unmask(payload, key);
    }
    return { fin, opcode, payload };
  }

  _frame({ fin, opcode, payload }) {
    if (opcode >= 0x8) {
      if (!fin || payload.length > 125) throw new FrameError(CloseCode.PROTOCOL_ERROR, 'a control frame is fragmented or longer than 125 bytes');
      if (opcode !== Opcode.CLOSE && opcode !== Opcode.PING && opcode !== Opcode.PONG) {
        throw new FrameError(CloseCode.PROTOCOL_ERROR, `unknown control opcode ${opcode}`);
      }
      this.onControl(opcode, payload);
      return;
    }
    if (opcode === Opcode.CONTINUATION) {
      if (!this._parts) throw new FrameError(CloseCode.PROTOCOL_ERROR, 'a continuation frame without a message to continue');
      this._parts.push(payload);
      this._partsBytes += payload.length;
      if (fin) {
        const parts = this._parts;
        this._parts = null;
        this._partsBytes = 0;
        this._deliver(this._partsOpcode, concat(parts));
      }
      return;
    }
    if (opcode !== Opcode.TEXT && opcode !== Opcode.BINARY) throw new FrameError(CloseCode.PROTOCOL_ERROR, `unknown data opcode ${opcode}`);
    if (this._parts) throw new FrameError(CloseCode.PROTOCOL_ERROR, 'a new message started before the fragmented one ended');
    if (fin) {
      this._deliver(opcode, payload);
    } else {
      this._parts = [payload];
      this._partsBytes = payload.length;
      this._partsOpcode = opcode;
    }
  }

  _deliver(opcode, payload) {
    if (opcode === Opcode.TEXT) {
      let text;
      try {
        text = utf8.decode(payload);
      } catch {
        throw new FrameError(CloseCode.INVALID_DATA, 'a text message is not valid UTF-8');
      }
      this.onMessage(text, false);
    } else {
      this.onMessage(payload, true);
    }
  }
}

function unmask(payload, key) {
  const n = payload.length;
  let i = 0;
  if (n >= 8 && payload.byteOffset % 4 === 0) {
    const k32 = new Uint32Array(new Uint8Array([key[0], key[1], key[2], key[3]]).buffer)[0];
    const words = new Uint32Array(payload.buffer, payload.byteOffset, n >> 2);
    for (let w = 0; w < words.length; w++) words[w] ^= k32;
    i = words.length << 2;
  }
  for (; i < n; i++) payload[i] ^= key[i & 3];
}

function concat(parts) {
  if (parts.length === 1) return parts[0];
  let n = 0;
  for (const p of parts) n += p.length;
  const out = new Uint8Array(n);
  let off = 0;
  for (const p of parts) {
    out.set(p, off);
    off += p.length;
  }
  return out;
}
