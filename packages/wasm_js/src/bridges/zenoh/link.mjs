// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The socket under zenoh-pico's link (zenoh_wasm_gateway/src/zenoh_session.c).
 * zenoh-pico sees a datagram link, one Zenoh batch per read and per send;
 * this module keeps the batches that came in and sends the ones going out:
 * - `ws/HOST:PORT`: a WebSocket (`ws://HOST:PORT/`), one binary message per
 *   batch, as the Zenoh router's WebSocket listener frames them;
 * - `tcp/HOST:PORT` (Node.js only): a TCP socket, whose stream carries each
 *   batch after its length (2 bytes, little-endian), as Zenoh's TCP link.
 *
 * Nothing here polls: incoming batches wake the session (`onReadable`).
 *
 * @module bridges/zenoh/link
 */

/** Socket state codes zg_js_read returns: nothing yet, closed. */
export const READ_NOTHING = -1;
export const READ_CLOSED = -2;

/** A batch that holds a Zenoh Fragment transport message: its first byte's message id, and its R (reliable) flag. */
const FRAGMENT_ID = 0x06;
const RELIABLE_FLAG = 0x20;

/**
 * zenoh-pico 1.9 sends each fragment of a message too large for one batch
 * alone in its batch, but without the R flag of a reliable message (its
 * __unsafe_z_serialize_zenoh_fragment passes `reliability ==
 * Z_RELIABILITY_RELIABLE`, a bool, for a z_reliability_t whose RELIABLE is
 * 0): the router then takes the message for best effort, and drops it when
 * the way to a subscriber is congested. Every message the gateway sends is
 * reliable (zenoh-pico's default reliability: zenoh_session.c sets no
 * other), and its sequence number is of the reliable channel: the flag is
 * set here.
 */
export function markFragmentReliable(batch) {
  if (batch.length && (batch[0] & 0x1f) === FRAGMENT_ID) batch[0] |= RELIABLE_FLAG;
  return batch;
}

/** An InitAck transport message: its id and flags (A: an ack; S: resolution and batch size follow the zid). */
const INIT_ID = 0x01;
const INIT_ACK_FLAG = 0x20;
const INIT_SIZE_FLAG = 0x40;
/** The bytes of a batch's length on a stream link (tcp/), which count in the batch size. */
const STREAM_LENGTH_BYTES = 2;

/**
 * On a tcp/ endpoint, give zenoh-pico the router's batch size less the 2
 * bytes of each batch's length: zenoh-pico sees a datagram link (its
 * WebSocket one) and fills batches to the size agreed, but on a stream
 * link that size counts the length the link writes before each batch (the
 * router's TCP batches are 49152 bytes, its limit with the length: a
 * message fragmented into 49152-byte batches closed the session). The
 * router's InitAck: id and flags, version, whatami and zid length (its
 * high nibble + 1), zid, then with S the resolution and the batch size
 * (u16, little-endian).
 */
export function fitInitAckToStream(batch) {
  if (batch.length < 3 || (batch[0] & 0x1f) !== INIT_ID || !(batch[0] & INIT_ACK_FLAG) || !(batch[0] & INIT_SIZE_FLAG)) return batch;
  const at = 3 + (batch[2] >> 4) + 1 + 1; // header, version, whatami/zid length, zid, resolution
  if (at + 2 > batch.length) return batch;
  const size = batch[at] | (batch[at + 1] << 8);
  const fitted = size - STREAM_LENGTH_BYTES;
  batch[at] = fitted & 0xff;
  batch[at + 1] = fitted >> 8;
  return batch;
}

/**
 * Parse a Zenoh endpoint as the user gives it (`ws/127.0.0.1:7447`).
 * @param {string} endpoint
 * @returns {{scheme: 'ws'|'tcp', host: string, port: number, text: string}}
 * @throws {Error} naming the endpoint and what is accepted
 */
export function parseEndpoint(endpoint) {
  const match = /^(ws|tcp)\/(\[[^\]]+\]|[^:/]+):(\d+)$/.exec(String(endpoint || '').trim());
  if (!match || Number(match[3]) < 1 || Number(match[3]) > 65535) {
    throw new Error(`'${endpoint}' is not a Zenoh endpoint: expected ws/HOST:PORT (browser and Node.js) `
      + 'or tcp/HOST:PORT (Node.js), e.g. ws/127.0.0.1:7447');
  }
  return { scheme: match[1], host: match[2], port: Number(match[3]), text: `${match[1]}/${match[2]}:${match[3]}` };
}

/** One open socket: the batches received and not read yet. */
class Socket {
  constructor(id, transport) {
    this.id = id;
    this.transport = transport;
    this.batches = [];
    this.closed = false;
    this.waiters = [];
    this.stream = null; // tcp: bytes of a batch not complete yet
  }

  push(batch) {
    this.batches.push(batch);
    this.wake();
  }

  wake() {
    const waiters = this.waiters;
    this.waiters = [];
    for (const w of waiters) w();
  }
}

/**
 * The sockets of one zenoh-pico session.
 */
export class ZenohLink {
  /**
   * @param {{scheme: string, host: string, port: number}} endpoint from parseEndpoint
   * @param {object} options
   * @param {function} [options.WebSocket] the WebSocket class (the browser's, or NodeWebSocket)
   * @param {function(): void} options.onReadable a batch came in (the session spins)
   * @param {function(Error): void} [options.onClosed] the socket closed or failed
   */
  constructor(endpoint, { WebSocket: WS, onReadable, onClosed = () => {} }) {
    this.endpoint = endpoint;
    this.WebSocket = WS || globalThis.WebSocket;
    this.onReadable = onReadable;
    this.onClosed = onClosed;
    this.sockets = new Map();
    this.nextId = 1;
    this.lastError = null;
    this.stats = { batchesIn: 0, batchesOut: 0, bytesIn: 0, bytesOut: 0 };
  }

  /** Open a socket to the endpoint; resolves to its id, or -1 (lastError says why). */
  async connect(address, timeoutMs) {
    const id = this.nextId++;
    const { scheme, host, port } = this.endpoint;
    try {
      const transport = scheme === 'tcp'
        ? await this._openTcp(id, host, port, timeoutMs) : await this._openWs(id, host, port, timeoutMs);
      this.sockets.get(id).transport = transport;
      return id;
    } catch (error) {
      this.sockets.delete(id);
      this.lastError = error;
      return -1;
    }
  }

  _socketClosed(socket, error) {
    if (socket.closed) return;
    socket.closed = true;
    socket.wake();
    if (error) this.lastError = error;
    this.onClosed(error || new Error(`the Zenoh router at ${this.endpoint.text} closed the connection`));
    this.onReadable();
  }

  _received(socket, batch) {
    this.stats.batchesIn += 1;
    this.stats.bytesIn += batch.length;
    socket.push(batch);
    this.onReadable();
  }

  _openWs(id, host, port, timeoutMs) {
    const url = `ws://${host}:${port}/`;
    return new Promise((resolve, reject) => {
      const ws = new this.WebSocket(url);
      const socket = new Socket(id, ws);
      this.sockets.set(id, socket);
      ws.binaryType = 'arraybuffer';
      const timer = setTimeout(() => {
        ws.close();
        reject(new Error(`no answer from the Zenoh router at ws/${host}:${port} within ${timeoutMs} ms`));
      }, timeoutMs);
      let open = false;
      ws.onopen = () => { open = true; clearTimeout(timer); resolve(ws); };
      ws.onmessage = (event) => {
        if (typeof event.data === 'string') return; // a router sends binary frames only
        this._received(socket, new Uint8Array(event.data));
      };
      ws.onerror = (event) => {
        if (!open) {
          clearTimeout(timer);
          reject(new Error(`cannot connect to the Zenoh router at ws/${host}:${port}${event && event.message ? `: ${event.message}` : ''}`));
        }
      };
      ws.onclose = (event) => {
        clearTimeout(timer);
        if (!open) reject(new Error(`cannot connect to the Zenoh router at ws/${host}:${port}`));
        else this._socketClosed(socket, event && event.reason ? new Error(event.reason) : null);
      };
    });
  }

  async _openTcp(id, host, port, timeoutMs) {
    const net = await import('node:net');
    return new Promise((resolve, reject) => {
      const tcp = net.connect({ host: host.replace(/^\[|\]$/g, ''), port, noDelay: true });
      const socket = new Socket(id, tcp);
      this.sockets.set(id, socket);
      let open = false;
      tcp.setTimeout(timeoutMs, () => {
        if (!open) {
          tcp.destroy();
          reject(new Error(`no answer from the Zenoh router at tcp/${host}:${port} within ${timeoutMs} ms`));
        }
      });
      tcp.on('connect', () => { open = true; tcp.setTimeout(0); resolve(tcp); });
      tcp.on('data', (chunk) => this._splitStream(socket, chunk));
      tcp.on('error', (e) => {
        if (!open) reject(new Error(`cannot connect to the Zenoh router at tcp/${host}:${port}: ${e.message}`));
        else this.lastError = e;
      });
      tcp.on('close', () => { if (open) this._socketClosed(socket, null); });
    });
  }

  _splitStream(socket, chunk) {
    let data = socket.stream ? Buffer.concat([socket.stream, chunk]) : chunk;
    let at = 0;
    while (data.length - at >= 2) {
      const size = data[at] | (data[at + 1] << 8);
      if (data.length - at - 2 < size) break;
      this._received(socket, fitInitAckToStream(new Uint8Array(data.subarray(at + 2, at + 2 + size))));
      at += 2 + size;
    }
    socket.stream = at < data.length ? Buffer.from(data.subarray(at)) : null;
  }

  /** Copy the next batch into `view`: its length, READ_NOTHING or READ_CLOSED. */
  read(id, view) {
    const socket = this.sockets.get(id);
    if (!socket) return READ_CLOSED;
    const batch = socket.batches.shift();
    if (!batch) return socket.closed ? READ_CLOSED : READ_NOTHING;
    if (batch.length > view.length) {
      this.lastError = new Error(`a Zenoh batch of ${batch.length} bytes is larger than zenoh-pico's buffer (${view.length})`);
      this.close(id);
      return READ_CLOSED;
    }
    view.set(batch);
    return batch.length;
  }

  /** Whether a socket has a batch to read. */
  readable(id) {
    const socket = this.sockets.get(id);
    return Boolean(socket && (socket.batches.length || socket.closed));
  }

  /** Resolve true when `id` has a batch (or closed), false after `timeoutMs`. */
  waitReadable(id, timeoutMs) {
    const socket = this.sockets.get(id);
    if (!socket || socket.batches.length || socket.closed) return Promise.resolve(true);
    return new Promise((resolve) => {
      const timer = setTimeout(() => {
        socket.waiters = socket.waiters.filter((w) => w !== done);
        resolve(false);
      }, timeoutMs);
      const done = () => { clearTimeout(timer); resolve(true); };
      socket.waiters.push(done);
    });
  }

  /** Send one batch; returns its length, or -1 when the socket is closed. */
  send(id, bytes) {
    const socket = this.sockets.get(id);
    if (!socket || socket.closed || !socket.transport) return -1;
    this.stats.batchesOut += 1;
    this.stats.bytesOut += bytes.length;
    markFragmentReliable(bytes);
    if (this.endpoint.scheme === 'tcp') {
      const framed = Buffer.allocUnsafe(bytes.length + 2);
      framed[0] = bytes.length & 0xff;
      framed[1] = bytes.length >> 8;
      framed.set(bytes, 2);
      socket.transport.write(framed);
    } else {
      socket.transport.send(bytes);
    }
    return bytes.length;
  }

  /** Close a socket. */
  close(id) {
    const socket = this.sockets.get(id);
    if (!socket) return;
    this.sockets.delete(id);
    socket.closed = true;
    socket.wake();
    const t = socket.transport;
    if (!t) return;
    if (this.endpoint.scheme === 'tcp') t.destroy();
    else t.close();
  }

  /** Whether any socket has a batch to read. */
  anyReadable() {
    for (const id of this.sockets.keys()) if (this.readable(id)) return true;
    return false;
  }
}
