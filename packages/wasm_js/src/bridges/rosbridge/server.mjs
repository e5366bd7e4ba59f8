// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A rosbridge v2 server over the bus, in Node.js (`colcon-wasm run|launch
 * --rosbridge [HOST:]PORT`): WebSocket clients (roslibjs, roslibpy,
 * dashboards) publish, subscribe, call and serve services and actions on
 * the nodes of one Runtime, with the build's type descriptions.
 *
 * Beyond rosbridge_server: loopback unless told otherwise; an optional
 * token, checked on connect (`?token=` in the URL, or an
 * `Authorization: Bearer` header; refused with HTTP 401); an optional
 * capability list (capabilities.mjs); a limit on the size of a client's
 * messages (a larger one is dropped with a status error, the connection
 * stays up) and on the bytes queued for a client (past it the client is cut
 * off, nothing waits for it).
 *
 * @module bridges/rosbridge/server
 */

import { timingSafeEqual } from 'node:crypto';
import http from 'node:http';

import { closeAll, listen } from '../common/listen.mjs';
import { loadSchemas } from '../common/schema_texts.mjs';
import { installActions } from './actions.mjs';
import { BusLink } from './bus_link.mjs';
import { Capabilities } from './capabilities.mjs';
import { Converter } from './convert.mjs';
import { pngEncodeText } from './png.mjs';
import { installServices } from './services.mjs';
import { Session } from './session.mjs';
import { installTopics } from './topics.mjs';
import { acceptWebSocket, refuse } from './ws_node.mjs';

/** Default limits (see README.md, docs/bridge.md). */
export const DEFAULT_LIMITS = Object.freeze({
  maxMessageBytes: 16 << 20,
  maxQueuedBytes: 64 << 20,
  callTimeoutMs: 10000,
  serveTimeoutMs: 30000,
});

/** A server that could not start (the port is taken, ...): the message says what to do. */
export class RosbridgeError extends Error {
  constructor(message) {
    super(message);
    this.name = 'RosbridgeError';
  }
}

function tokenOf(request) {
  const auth = request.headers.authorization;
  if (auth && /^Bearer\s+/i.test(auth)) return auth.replace(/^Bearer\s+/i, '').trim();
  try {
    return new URL(request.url, 'http://x').searchParams.get('token');
  } catch {
    return null;
  }
}

function sameToken(a, b) {
  const x = Buffer.from(String(a));
  const y = Buffer.from(String(b));
  return x.length === y.length && timingSafeEqual(x, y);
}

/** The rosbridge server of one Runtime. */
export class RosbridgeServer {
  /**
   * Start listening.
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../cdr.mjs').TypeRegistry} options.registry the build's type descriptions
   * @param {string} [options.host='127.0.0.1']
   * @param {number} [options.port=9090] 0 picks a free port
   * @param {string} [options.token] clients must present it
   * @param {object} [options.capabilities] the capability list (capabilities.mjs), null: everything
   * @param {object} [options.limits] DEFAULT_LIMITS' keys
   * @param {string} [options.schemas] the JSON file of the complete definitions (rosapi's
   *   topics_and_raw_types; ../common/schema_texts.mjs)
   * @param {function(string, string): void} [options.log] (level, text)
   * @returns {Promise<RosbridgeServer>}
   * @throws {RosbridgeError} when the port cannot be had
   */
  static async start(options) {
    const server = new RosbridgeServer(options);
    await server._listen();
    return server;
  }

  constructor({
    runtime, registry, host = '127.0.0.1', port = 9090, token = null, capabilities = null, limits = {}, schemas = null, log = null,
  }) {
    this.runtime = runtime;
    this.host = host;
    this.port = port;
    this.token = token || null;
    this.log = log;
    this.sessions = new Set();
    this._nextId = 1;
    this.core = {
      registry,
      converter: new Converter(registry),
      schemas: loadSchemas(schemas),
      capabilities: new Capabilities(capabilities),
      limits: { ...DEFAULT_LIMITS, ...limits },
      stats: { clients: 0, cutOff: 0, expired: 0, unanswered: 0, refused: 0 },
      services: new Map(),
      actions: new Map(),
      link: null,
      log,
      png: pngEncodeText,
    };
    this.http = http.createServer((req, res) => {
      res.writeHead(426, { 'Content-Type': 'text/plain; charset=utf-8', Upgrade: 'websocket' });
      res.end('this is a rosbridge v2 WebSocket server: connect with roslibjs, roslibpy or another rosbridge client (ws://)\n');
    });
    this.http.on('upgrade', (req, socket, head) => this._upgrade(req, socket, head));
  }

  async _listen() {
    // the bus side first: a client that connects at once finds it ready
    const tools = await this.runtime.tools();
    this.core.link = await BusLink.create({ runtime: this.runtime, tools, nodeName: 'rosbridge_websocket' });
    this.port = await listen(this.http, {
      host: this.host, port: this.port, option: '--rosbridge', other: 'another rosbridge server', ErrorClass: RosbridgeError,
    });
  }

  /** ws://host:port of the server. */
  get url() {
    const host = this.host.includes(':') ? `[${this.host}]` : this.host;
    return `ws://${host}:${this.port}`;
  }

  _upgrade(request, socket, head) {
    const peer = `${socket.remoteAddress}:${socket.remotePort}`;
    if (this.token && !sameToken(tokenOf(request) || '', this.token)) {
      this.core.stats.refused++;
      if (this.log) this.log('warning', `refused a client from ${peer}: no valid token`);
      refuse(socket, 401, 'Unauthorized', 'this rosbridge server needs a token: connect to ws://HOST:PORT/?token=TOKEN '
        + '(or send Authorization: Bearer TOKEN)');
      return;
    }
    let session = null;
    const conn = acceptWebSocket(request, socket, head, {
      maxMessageBytes: this.core.limits.maxMessageBytes,
      onOversize: (bytes) => session && session.status('error',
        `a message of ${bytes} bytes is larger than the limit of ${this.core.limits.maxMessageBytes} bytes `
        + '(--rosbridge-max-message-bytes); it was dropped'),
    });
    if (!conn) return;
    session = this.attach(conn, peer);
  }

  /**
   * Serve one client on an open connection: its messages go to the
   * session's `receive()` (also the entry point of tests/fuzz's driver).
   * @param {object} conn a WebSocket (send, close, terminate, bufferedAmount, ondrain, onmessage, onclose)
   * @param {string} peer the client's address, for logs
   * @returns {Session}
   */
  attach(conn, peer) {
    const session = new Session({ core: this.core, conn, id: this._nextId++, peer });
    installTopics(session);
    installServices(session);
    installActions(session);
    this.sessions.add(session);
    this.core.stats.clients++;
    if (this.log) this.log('info', `client ${session.id} connected from ${peer} (${this.sessions.size} connected)`);
    conn.onmessage = (e) => session.receive(e.binary ? new Uint8Array(e.data) : e.data, e.binary);
    conn.onerror = () => {};
    conn.onclose = (e) => {
      this.sessions.delete(session);
      session.end();
      if (this.log) this.log('info', `client ${session.id} disconnected (${e.code}${e.reason ? ` ${e.reason}` : ''}; ${this.sessions.size} connected)`);
    };
    return session;
  }

  /** Counters: clients served, cut off, messages dropped as stale, ... */
  stats() {
    const sessions = [...this.sessions].map((s) => ({ id: s.id, peer: s.peer, ...s.stats }));
    return { ...this.core.stats, connected: this.sessions.size, sessions };
  }

  /**
   * Stop listening and close every client: the closing handshake first
   * (what a client sent before it saw the close is still published), at
   * most `graceMs`, then the sockets.
   */
  async close(graceMs = 1500) {
    await closeAll(this.http, this.sessions, graceMs);
  }
}

/**
 * Read `[HOST:]PORT` (IPv6 hosts in brackets).
 * @returns {{host: string, port: number}}
 */
export function parseListenAddress(text, defaults = { host: '127.0.0.1', port: 9090 }) {
  const m = /^(?:\[([^\]]+)\]|([^:]*)):(\d+)$/.exec(text) || /^()()(\d+)$/.exec(text);
  if (!m) throw new RosbridgeError(`'${text}' is not [HOST:]PORT (e.g. 9090, 127.0.0.1:9090, 0.0.0.0:9090)`);
  return { host: m[1] || m[2] || defaults.host, port: Number(m[3]) };
}
