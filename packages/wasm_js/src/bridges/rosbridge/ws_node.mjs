// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * WebSocket connections over Node.js sockets (RFC 6455), without npm
 * packages: the server side of the opening handshake (`acceptWebSocket`,
 * for an `http.Server` 'upgrade' event) and a client (`NodeWebSocket`, the
 * browser's `WebSocket` interface, for Node.js 20, which has none). Frames
 * are ws_frames.mjs'. Pings are answered; a close is answered and ends the
 * socket; `bufferedAmount` is what the socket has not written yet (the
 * measure of a peer that stops reading).
 *
 * @module bridges/rosbridge/ws_node
 */

import { createHash, randomBytes } from 'node:crypto';
import http from 'node:http';

import { CloseCode, closePayload, encodeFrame, FrameError, FrameParser, Opcode } from './ws_frames.mjs';

const GUID = '258EAFA5-E914-47DA-95CA-C5AB0DC85B11';
const enc = new TextEncoder();

export const ReadyState = Object.freeze({ CONNECTING: 0, OPEN: 1, CLOSING: 2, CLOSED: 3 });

/** The Sec-WebSocket-Accept value of a key (RFC 6455 4.2.2). */
export function acceptKey(key) {
  return createHash('sha1').update(key + GUID).digest('base64');
}

/**
 * One open WebSocket over a socket, either side. Browser-like events:
 * onmessage({data}), onclose({code, reason, wasClean}), onerror(error),
 * ondrain() when the socket has written what was queued.
 */
export class WebSocketConnection {
  /**
   * @param {import('node:net').Socket} socket
   * @param {object} options
   * @param {boolean} options.client this end is the client (masks, expects unmasked frames)
   * @param {number} [options.maxMessageBytes=64 MiB]
   * @param {Uint8Array} [options.head] bytes read past the handshake
   * @param {function(number): void} [options.onOversize] a message over the limit was skipped
   *   (without it, such a message closes the connection with 1009)
   */
  constructor(socket, { client, maxMessageBytes = 64 << 20, head, onOversize } = {}) {
    this.socket = socket;
    this.client = client;
    this.readyState = ReadyState.OPEN;
    this.binaryType = 'arraybuffer';
    this.onmessage = null;
    this.onclose = null;
    this.onerror = null;
    this.ondrain = null;
    this._closeSent = false;
    this._closed = false;
    this._parser = new FrameParser({
      expectMasked: !client,
      maxMessageBytes,
      onMessage: (data, binary) => {
        if (this.onmessage) this.onmessage({ data: binary ? toArrayBuffer(data) : data, binary });
      },
      onControl: (opcode, payload) => this._control(opcode, payload),
      onOversize,
    });
    socket.setNoDelay(true);
    socket.on('data', (chunk) => this._data(chunk));
    socket.on('drain', () => { if (this.ondrain) this.ondrain(); });
    socket.on('error', (e) => { if (this.onerror) this.onerror(e); });
    socket.on('close', () => this._finish(this._closeCode || CloseCode.GOING_AWAY, this._closeReason || 'the connection was lost'));
    if (head && head.length) this._data(head);
  }

  /** Bytes queued in the socket and not yet written. */
  get bufferedAmount() {
    return this.socket.writableLength;
  }

  _data(chunk) {
    if (this._closed) return;
    try {
      this._parser.push(new Uint8Array(chunk.buffer, chunk.byteOffset, chunk.length));
    } catch (e) {
      if (!(e instanceof FrameError)) throw e;
      if (this.onerror) this.onerror(e);
      this.close(e.code, e.message);
      this.socket.end();
    }
  }

  _control(opcode, payload) {
    if (opcode === Opcode.PING) {
      this._write(Opcode.PONG, payload);
    } else if (opcode === Opcode.CLOSE) {
      const code = payload.length >= 2 ? (payload[0] << 8) | payload[1] : 1005;
      const reason = payload.length > 2 ? new TextDecoder().decode(payload.subarray(2)) : '';
      this._closeCode = code;
      this._closeReason = reason;
      if (!this._closeSent) {
        this._closeSent = true;
        this._write(Opcode.CLOSE, payload.length >= 2 ? payload.subarray(0, 2) : new Uint8Array(0));
      }
      this.readyState = ReadyState.CLOSING;
      this.socket.end();
    }
  }

  /** Cork the socket until the end of this turn: the frames of one turn go out in one write. */
  _cork() {
    if (this._corked) return;
    this._corked = true;
    this.socket.cork();
    process.nextTick(() => {
      this._corked = false;
      this.socket.uncork();
    });
  }

  _write(opcode, payload) {
    this._cork();
    const [header, body] = encodeFrame(opcode, payload, { mask: this.client });
    if (body.length < 1024) {
      const one = Buffer.allocUnsafe(header.length + body.length);
      one.set(header);
      one.set(body, header.length);
      return this.socket.write(one);
    }
    this.socket.write(header);
    return this.socket.write(body);
  }

  /** A text frame written straight from the string (a server's frames are not masked). */
  _writeText(text) {
    const len = Buffer.byteLength(text);
    const headerBytes = len < 126 ? 2 : len < 65536 ? 4 : 10;
    const frame = Buffer.allocUnsafe(headerBytes + len);
    frame[0] = 0x80 | Opcode.TEXT;
    if (headerBytes === 2) frame[1] = len;
    else if (headerBytes === 4) { frame[1] = 126; frame.writeUInt16BE(len, 2); } else { frame[1] = 127; frame.writeBigUInt64BE(BigInt(len), 2); }
    frame.write(text, headerBytes, 'utf8');
    this._cork();
    return this.socket.write(frame);
  }

  /**
   * Send a text (string) or binary (Uint8Array / ArrayBuffer) message.
   * @returns {boolean} false when the socket's buffer is over its high-water mark
   */
  send(data) {
    if (this.readyState !== ReadyState.OPEN) return false;
    if (typeof data === 'string') return this.client ? this._write(Opcode.TEXT, enc.encode(data)) : this._writeText(data);
    const bytes = data instanceof Uint8Array ? data : new Uint8Array(data);
    return this._write(Opcode.BINARY, bytes);
  }

  /** Send a ping (keep-alive). */
  ping() {
    if (this.readyState === ReadyState.OPEN) this._write(Opcode.PING, new Uint8Array(0));
  }

  /** Start the closing handshake; the socket ends when the peer answers (or after 2 s). */
  close(code = CloseCode.NORMAL, reason = '') {
    if (this.readyState >= ReadyState.CLOSING) return;
    this.readyState = ReadyState.CLOSING;
    this._closeCode = code;
    this._closeReason = reason;
    if (!this._closeSent) {
      this._closeSent = true;
      this._write(Opcode.CLOSE, closePayload(code, reason));
    }
    setTimeout(() => this.socket.destroy(), 2000).unref();
  }

  /** Drop the connection without a closing handshake. */
  terminate(code = CloseCode.GOING_AWAY, reason = 'terminated') {
    this._closeCode = this._closeCode || code;
    this._closeReason = this._closeReason || reason;
    this.socket.destroy();
  }

  _finish(code, reason) {
    if (this._closed) return;
    this._closed = true;
    this.readyState = ReadyState.CLOSED;
    if (this.onclose) this.onclose({ code, reason, wasClean: this._closeSent });
  }
}

function toArrayBuffer(bytes) {
  if (bytes.byteOffset === 0 && bytes.byteLength === bytes.buffer.byteLength) return bytes.buffer;
  return bytes.slice().buffer;
}

/**
 * Complete the server side of the opening handshake for an HTTP upgrade
 * request, or answer it with an HTTP error.
 * @param {http.IncomingMessage} request
 * @param {import('node:net').Socket} socket
 * @param {Buffer} head
 * @param {object} [options] {maxMessageBytes, onOversize}
 * @param {string[]} [options.protocols] subprotocols this server speaks, preferred first: the
 *   first the client offers is selected (`connection.protocol`); a client that offers none of
 *   them is refused (HTTP 400, `options.refusal` as the body)
 * @param {string} [options.what] what this server is, for a request that is no WebSocket upgrade
 * @returns {WebSocketConnection|null} null when the request was refused
 */
export function acceptWebSocket(request, socket, head, options = {}) {
  const key = request.headers['sec-websocket-key'];
  const upgrade = String(request.headers.upgrade || '').toLowerCase();
  const what = options.what || 'a rosbridge WebSocket server';
  if (request.method !== 'GET' || upgrade !== 'websocket' || !key) {
    refuse(socket, 400, 'Bad Request', `this is ${what}: connect with a WebSocket client (ws://)`);
    return null;
  }
  if (String(request.headers['sec-websocket-version']) !== '13') {
    socket.end('HTTP/1.1 426 Upgrade Required\r\nSec-WebSocket-Version: 13\r\nConnection: close\r\n\r\n');
    return null;
  }
  let protocol = '';
  if (options.protocols) {
    const offered = String(request.headers['sec-websocket-protocol'] || '').split(',').map((p) => p.trim());
    protocol = options.protocols.find((p) => offered.includes(p)) || '';
    if (!protocol) {
      refuse(socket, 400, 'Bad Request', options.refusal || `this is ${what}: offer one of the subprotocols ${options.protocols.join(', ')}`);
      return null;
    }
  }
  const lines = [
    'HTTP/1.1 101 Switching Protocols', 'Upgrade: websocket', 'Connection: Upgrade',
    `Sec-WebSocket-Accept: ${acceptKey(key)}`,
  ];
  if (protocol) lines.push(`Sec-WebSocket-Protocol: ${protocol}`);
  socket.write(`${lines.join('\r\n')}\r\n\r\n`);
  const connection = new WebSocketConnection(socket, {
    client: false, maxMessageBytes: options.maxMessageBytes, head, onOversize: options.onOversize,
  });
  connection.protocol = protocol;
  return connection;
}

/** Answer an upgrade request with an HTTP error and close the socket. */
export function refuse(socket, status, text, body = '') {
  socket.end(`HTTP/1.1 ${status} ${text}\r\nContent-Type: text/plain; charset=utf-8\r\n`
    + `Content-Length: ${Buffer.byteLength(body)}\r\nConnection: close\r\n\r\n${body}`);
}

/**
 * A WebSocket client with the browser's interface (onopen, onmessage,
 * onclose, onerror, send, close, readyState, bufferedAmount), for Node.js.
 */
export class NodeWebSocket {
  /**
   * @param {string} url ws://host:port/path (wss is not supported)
   * @param {object} [options] {headers, maxMessageBytes}
   */
  constructor(url, options = {}) {
    this.url = url;
    this.readyState = ReadyState.CONNECTING;
    this.binaryType = 'arraybuffer';
    this.onopen = null;
    this.onmessage = null;
    this.onclose = null;
    this.onerror = null;
    this._conn = null;
    const u = new URL(url);
    if (u.protocol !== 'ws:') {
      queueMicrotask(() => this._fail(new Error(`cannot connect to ${url}: only ws:// URLs are supported in Node.js`)));
      return;
    }
    const key = randomBytes(16).toString('base64');
    const request = http.request({
      host: u.hostname.replace(/^\[|\]$/g, ''), port: u.port || 80, path: `${u.pathname}${u.search}`,
      headers: {
        Connection: 'Upgrade', Upgrade: 'websocket', 'Sec-WebSocket-Version': '13',
        'Sec-WebSocket-Key': key, ...(options.headers || {}),
      },
    });
    request.on('upgrade', (response, socket, head) => {
      if (response.headers['sec-websocket-accept'] !== acceptKey(key)) {
        socket.destroy();
        this._fail(new Error(`${url} answered the WebSocket handshake with a wrong Sec-WebSocket-Accept`));
        return;
      }
      const conn = new WebSocketConnection(socket, { client: true, maxMessageBytes: options.maxMessageBytes, head });
      this._conn = conn;
      this.readyState = ReadyState.OPEN;
      conn.onmessage = (e) => { if (this.onmessage) this.onmessage(e); };
      conn.onerror = (e) => { if (this.onerror) this.onerror(e); };
      conn.onclose = (e) => {
        this.readyState = ReadyState.CLOSED;
        if (this.onclose) this.onclose(e);
      };
      if (this.onopen) this.onopen({});
    });
    request.on('response', (response) => {
      let body = '';
      response.on('data', (c) => { body += c; });
      response.on('end', () => this._fail(new Error(`${url} refused the WebSocket: HTTP ${response.statusCode}${body ? `: ${body.trim()}` : ''}`),
        response.statusCode === 401 || response.statusCode === 403 ? CloseCode.POLICY : CloseCode.GOING_AWAY));
    });
    request.on('error', (e) => this._fail(new Error(`cannot connect to ${url}: ${e.message}`)));
    request.end();
  }

  get bufferedAmount() {
    return this._conn ? this._conn.bufferedAmount : 0;
  }

  /** CONNECTING, OPEN, CLOSING (a close frame came or went: send() would drop), CLOSED. */
  get readyState() {
    return this._conn ? this._conn.readyState : this._state;
  }

  set readyState(state) {
    this._state = state;
  }

  _fail(error, code = 1006) {
    if (this.readyState === ReadyState.CLOSED) return;
    this.readyState = ReadyState.CLOSED;
    if (this.onerror) this.onerror(error);
    if (this.onclose) this.onclose({ code, reason: error.message, wasClean: false });
  }

  send(data) {
    if (!this._conn) throw new Error(`the WebSocket to ${this.url} is not open`);
    return this._conn.send(data);
  }

  close(code, reason) {
    if (this._conn) this._conn.close(code, reason);
    else this.readyState = ReadyState.CLOSED;
  }
}
