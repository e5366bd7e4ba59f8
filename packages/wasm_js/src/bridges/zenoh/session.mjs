// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A Zenoh session in JavaScript: the zenoh-pico build of the
 * zenoh_wasm_gateway package (zenoh_session.mjs/.wasm, single-threaded) over
 * a ZenohLink. The session spins when a batch comes in and once a second
 * (keep-alives, the router's lease); handlers of samples, queries and
 * replies run after the spin, never inside zenoh-pico.
 *
 * @module bridges/zenoh/session
 */

import { ZenohLink, parseEndpoint } from './link.mjs';

/** How often the session spins without traffic (keep-alives go at a quarter of the 10 s lease). */
const SPIN_INTERVAL_MS = 1000;

/** zenoh-pico's connect timeout for the handshake. */
const OPEN_TIMEOUT_MS = 5000;

/** 16 random bytes, the last one not zero (zenoh prints the id as a number: no leading zeros to drop). */
export function randomZid() {
  const bytes = new Uint8Array(16);
  globalThis.crypto.getRandomValues(bytes);
  bytes[15] = bytes[15] || 1;
  return bytes;
}

/**
 * The text zenoh-pico's _z_uuid_to_bytes reads back as `bytes`: hex pairs in
 * byte order, with the four skipped characters it expects where a UUID has
 * dashes (after the 4th, 6th, 8th and 9th byte, as it counts them).
 */
export function uuidText(bytes) {
  const chars = new Array(36).fill('-');
  let dashes = 0;
  for (let i = 0; i < 32; i += 2) {
    if (i === 8 || i === 12 || i === 16 || i === 18) dashes += 1;
    const hex = bytes[i / 2].toString(16).padStart(2, '0');
    chars[i + dashes] = hex[0];
    chars[i + 1 + dashes] = hex[1];
  }
  return chars.join('');
}

/** A JavaScript-side entity id: the context zenoh-pico hands back with each sample. */
let nextEntityId = 1;

/**
 * One client session to a Zenoh router.
 */
export class ZenohSession {
  /**
   * Connect to a router and open a session.
   * @param {object} options
   * @param {string} options.endpoint `ws/HOST:PORT` or `tcp/HOST:PORT` (Node.js)
   * @param {function(object): Promise<object>} options.createModule the Emscripten factory of zenoh_session.mjs
   * @param {function} [options.WebSocket] the WebSocket class (Node.js: NodeWebSocket)
   * @param {function(Error): void} [options.onClosed] the router went away
   * @returns {Promise<ZenohSession>}
   * @throws {Error} naming the endpoint when no router answers
   */
  static async open({ endpoint, createModule, WebSocket: WS, onClosed = () => {} }) {
    const parsed = parseEndpoint(endpoint);
    const session = new ZenohSession(parsed, onClosed);
    session.link = new ZenohLink(parsed, {
      WebSocket: WS, onReadable: () => session._schedule(), onClosed: (e) => session._linkClosed(e),
    });
    session.module = await createModule({ zenohHost: session._host(), print: () => {}, printErr: () => {} });
    const locator = `ws/${parsed.host}:${parsed.port}`;
    const ret = await session.module.ccall('zg_open', 'number', ['string', 'string'], [locator, uuidText(randomZid())], { async: true });
    if (ret !== 0) {
      const why = session.link.lastError ? session.link.lastError.message
        : `the router at ${parsed.text} refused the session (zenoh-pico error ${ret})`;
      session.link.close(1);
      throw new Error(why);
    }
    session.up = true;
    const zid = session.module._malloc(33);
    session.module._zg_zid(zid);
    session.zid = session.module.UTF8ToString(zid).replace(/^0+(?=.)/, '');
    session.module._free(zid);
    session.timer = setInterval(() => session._spin(), SPIN_INTERVAL_MS);
    if (session.timer.unref) session.timer.unref();
    return session;
  }

  constructor(endpoint, onClosed) {
    this.endpoint = endpoint;
    this.onClosed = onClosed;
    this.up = false;
    this.handlers = new Map(); // entity id -> {sample, query, reply, done}
    this.scheduled = false;
    this.stats = { samples: 0, queries: 0, replies: 0, handlerErrors: 0 };
    this._scratch = 0;
    this._scratchBytes = 0;
  }

  _host() {
    const defer = (fn) => queueMicrotask(() => {
      try { fn(); } catch (error) { this.stats.handlerErrors += 1; this.lastHandlerError = error; }
    });
    return {
      connect: (address, timeout) => this.link.connect(address, Math.min(timeout, OPEN_TIMEOUT_MS)),
      waitReadable: (id, timeout) => this.link.waitReadable(id, timeout),
      read: (id, view) => this.link.read(id, view),
      send: (id, bytes) => this.link.send(id, bytes),
      close: (id) => this.link.close(id),
      sample: (id, kind, key, payload, attachment) => {
        this.stats.samples += 1;
        const h = this.handlers.get(id);
        if (h && h.sample) defer(() => h.sample({ kind, key, payload, attachment }));
      },
      query: (id, handle, key, payload, attachment) => {
        this.stats.queries += 1;
        const h = this.handlers.get(id);
        const query = new Query(this, handle, key, payload, attachment);
        if (h && h.query) defer(() => h.query(query));
        else query.drop();
      },
      reply: (id, ok, key, payload, attachment) => {
        this.stats.replies += 1;
        const h = this.handlers.get(id);
        if (h && h.reply) defer(() => h.reply({ ok, key, payload, attachment }));
      },
      matching: (id, matching) => {
        const h = this.handlers.get(id);
        if (h && h.matching) defer(() => h.matching(matching));
      },
      replyDone: (id) => {
        const h = this.handlers.get(id);
        this.handlers.delete(id);
        if (h && h.done) defer(() => h.done());
      },
    };
  }

  _schedule() {
    if (this.scheduled || !this.up) return;
    this.scheduled = true;
    setTimeout(() => { this.scheduled = false; this._spin(); }, 0);
  }

  _spin() {
    if (!this.up) return;
    let rounds = 0;
    do {
      if (!this.module._zg_spin()) {
        this._linkClosed(this.link.lastError);
        return;
      }
      rounds += 1;
    } while (this.link.anyReadable() && rounds < 256);
    if (this.link.anyReadable()) this._schedule();
  }

  _linkClosed(error) {
    if (!this.up) return;
    this.up = false;
    clearInterval(this.timer);
    try { this.module._zg_close(); } catch { /* the session is gone either way */ }
    this.onClosed(error || new Error(`the Zenoh router at ${this.endpoint.text} closed the session`));
  }

  /**
   * Run `fn` with zenoh-pico's batching on: what it sends goes out in as few
   * Zenoh batches (socket writes) as fit, at its end.
   */
  batch(fn) {
    if (!this.up) return fn();
    this.module._zg_batch_start();
    try {
      return fn();
    } finally {
      if (this.up) this.module._zg_batch_stop();
    }
  }

  _bytes(data) {
    if (!data || !data.length) return [0, 0];
    const ptr = this.module._malloc(data.length);
    this.module.HEAPU8.set(data, ptr);
    return [ptr, data.length];
  }

  /**
   * Copy a payload and an attachment into the module for one call:
   * `fn(payloadPtr, payloadLength, attachmentPtr, attachmentLength)`, the
   * payload's length -1 when there is none (null); both freed after.
   */
  _withBytes(payload, attachment, fn) {
    const [p, n] = payload === null ? [0, -1] : this._bytes(payload);
    const [a, m] = this._bytes(attachment);
    try {
      return fn(p, n, a, m);
    } finally {
      if (p) this.module._free(p);
      if (a) this.module._free(a);
    }
  }

  /**
   * Give a publisher entity `put(payload, attachment)`, calling the module's
   * `put` export, and `putAt(ptr, length, attachmentPtr, attachmentLength)`
   * for bytes already in the module's memory (see scratch()).
   */
  _withPut(entity, handle, put) {
    const fn = this.module[put];
    entity.put = (payload, attachment = null) => {
      if (!this.up || entity.closed) return -1;
      return this._withBytes(payload, attachment, (p, n, a, m) => fn(handle, p, n, a, m));
    };
    entity.putAt = (p, n, a, m) => (this.up && !entity.closed ? fn(handle, p, n, a, m) : -1);
    return entity;
  }

  /**
   * A buffer of at least `bytes` in the module's memory, kept for the next
   * calls (one per session: valid until the next scratch()); its address.
   * Re-read `module.HEAPU8` after it: the memory may have grown.
   */
  scratch(bytes) {
    if (bytes > this._scratchBytes) {
      if (this._scratch) this.module._free(this._scratch);
      this._scratchBytes = Math.max(bytes, 2 * this._scratchBytes, 4096);
      this._scratch = this.module._malloc(this._scratchBytes);
      if (!this._scratch) {
        this._scratchBytes = 0;
        throw new Error(`zenoh-pico's module cannot allocate ${bytes} bytes`);
      }
    }
    return this._scratch;
  }

  _string(text) {
    const size = this.module.lengthBytesUTF8(text) + 1;
    const ptr = this.module._malloc(size);
    this.module.stringToUTF8(text, ptr, size);
    return ptr;
  }

  _declare(fn, key, ...args) {
    if (!this.up) throw new Error(`the Zenoh session to ${this.endpoint.text} is closed`);
    const k = this._string(key);
    try {
      return fn(k, ...args);
    } finally {
      this.module._free(k);
    }
  }

  /**
   * Subscribe to a key expression.
   * @param {string} key
   * @param {function({kind: string, key: string, payload: Uint8Array, attachment: Uint8Array}): void} onSample
   * @returns {{close: function(): void}}
   */
  subscribe(key, onSample) {
    const id = nextEntityId++;
    this.handlers.set(id, { sample: onSample });
    const handle = this._declare((k) => this.module._zg_subscriber(id, k), key);
    return this._entity(handle, id, key, '_zg_subscriber_drop', 'subscriber');
  }

  /**
   * Subscribe to liveliness tokens; with `history`, the live ones arrive first as puts.
   * @returns {{close: function(): void}}
   */
  subscribeLiveliness(key, onSample, { history = true } = {}) {
    const id = nextEntityId++;
    this.handlers.set(id, { sample: onSample });
    const handle = this._declare((k) => this.module._zg_liveliness_subscriber(id, k, history ? 1 : 0), key);
    return this._entity(handle, id, key, '_zg_subscriber_drop', 'liveliness subscriber');
  }

  /**
   * Declare a publisher.
   * @param {string} key
   * @param {{reliable?: boolean, express?: boolean, onMatching?: function(boolean): void}} [options]
   *   onMatching: the router declared (true) or withdrew (false) the last matching subscriber
   * @returns {{put: function(Uint8Array, Uint8Array=): number, close: function(): void}}
   */
  publisher(key, { reliable = true, express = false, onMatching = null } = {}) {
    const id = nextEntityId++;
    this.handlers.set(id, { matching: onMatching });
    const handle = this._declare((k) => this.module._zg_publisher(id, k, reliable ? 1 : 0, express ? 1 : 0), key);
    return this._withPut(this._entity(handle, id, key, '_zg_publisher_drop', 'publisher'), handle, '_zg_put');
  }

  /**
   * Declare zenoh-ext's advanced publisher, as rmw_zenoh does for TRANSIENT_LOCAL:
   * a cache of the last `depth` samples for late subscribers, detectable.
   * @returns {{put: function(Uint8Array, Uint8Array=): number, close: function(): void}}
   */
  advancedPublisher(key, { reliable = true, depth = 1, onMatching = null } = {}) {
    const id = nextEntityId++;
    this.handlers.set(id, { matching: onMatching });
    const handle = this._declare((k) => this.module._zg_advanced_publisher(id, k, reliable ? 1 : 0, depth), key);
    const entity = this._entity(handle, id, key, '_zg_advanced_publisher_drop', 'advanced publisher');
    return this._withPut(entity, handle, '_zg_advanced_put');
  }

  /**
   * Subscribe with zenoh-ext's advanced subscriber (rmw_zenoh's TRANSIENT_LOCAL):
   * the publishers' caches are asked for their last `depth` samples, late publishers too.
   * @returns {{close: function(): void}}
   */
  advancedSubscribe(key, onSample, { reliable = true, depth = 1 } = {}) {
    const id = nextEntityId++;
    this.handlers.set(id, { sample: onSample });
    const handle = this._declare((k) => this.module._zg_advanced_subscriber(id, k, reliable ? 1 : 0, depth), key);
    return this._entity(handle, id, key, '_zg_advanced_subscriber_drop', 'advanced subscriber');
  }

  /** Declare a liveliness token. @returns {{close: function(): void}} */
  token(key) {
    const handle = this._declare((k) => this.module._zg_token(k), key);
    return this._entity(handle, 0, key, '_zg_token_drop', 'liveliness token');
  }

  /**
   * Declare a queryable (complete); `onQuery(query)` must reply or drop it.
   * @returns {{close: function(): void}}
   */
  queryable(key, onQuery) {
    const id = nextEntityId++;
    this.handlers.set(id, { query: onQuery });
    const handle = this._declare((k) => this.module._zg_queryable(id, k), key);
    return this._entity(handle, id, key, '_zg_queryable_drop', 'queryable');
  }

  /**
   * Send a query; resolves to the replies once the router says they are all in (or the timeout).
   * @param {string} key
   * @param {{payload?: Uint8Array, attachment?: Uint8Array, timeoutMs?: number, onReply?: function}} [options]
   * @returns {Promise<Array<{ok: boolean, key: string, payload: Uint8Array, attachment: Uint8Array}>>}
   */
  get(key, { payload = null, attachment = null, timeoutMs = 10000, onReply = null } = {}) {
    return new Promise((resolve, reject) => {
      const id = nextEntityId++;
      const replies = [];
      this.handlers.set(id, {
        reply: (r) => { replies.push(r); if (onReply) onReply(r); },
        done: () => resolve(replies),
      });
      const ret = this._withBytes(payload, attachment,
        (p, n, a, m) => this._declare((k) => this.module._zg_get(id, k, p, n, a, m, timeoutMs), key));
      if (ret !== 0) {
        this.handlers.delete(id);
        reject(new Error(`zenoh-pico could not send the query on '${key}' (error ${ret})`));
      }
    });
  }

  /** Query the liveliness tokens alive on `key`: resolves to their key expressions. */
  livelinessGet(key, { timeoutMs = 5000 } = {}) {
    return new Promise((resolve, reject) => {
      const id = nextEntityId++;
      const keys = [];
      this.handlers.set(id, { reply: (r) => { if (r.ok) keys.push(r.key); }, done: () => resolve(keys) });
      const ret = this._declare((k) => this.module._zg_liveliness_get(id, k, timeoutMs), key);
      if (ret !== 0) {
        this.handlers.delete(id);
        reject(new Error(`zenoh-pico could not query the liveliness tokens on '${key}' (error ${ret})`));
      }
    });
  }

  _entity(handle, id, key, drop, what) {
    if (!handle) {
      if (id) this.handlers.delete(id);
      throw new Error(`zenoh-pico could not declare a ${what} on '${key}' (not a valid key expression, or the session is down)`);
    }
    const entity = {
      key, closed: false,
      close: () => {
        if (entity.closed) return;
        entity.closed = true;
        if (id) this.handlers.delete(id);
        this.module[drop](handle);
      },
    };
    return entity;
  }

  /** Close the session: undeclares everything on the router's side. */
  close() {
    if (!this.module) return;
    clearInterval(this.timer);
    const wasUp = this.up;
    this.up = false;
    if (wasUp) this.module._zg_close();
    for (const id of [...this.link.sockets.keys()]) this.link.close(id);
  }
}

/** A query kept until the local service answers. */
class Query {
  constructor(session, handle, key, payload, attachment) {
    this.session = session;
    this.handle = handle;
    this.key = key;
    this.payload = payload;
    this.attachment = attachment;
    this.done = false;
  }

  /** Reply once (then the final response goes). */
  reply(key, payload, attachment) {
    this._finish(key, payload, attachment);
  }

  /** Release the query without a reply. */
  drop() {
    this._finish(this.key, null, null);
  }

  _finish(key, payload, attachment) {
    if (this.done) return;
    this.done = true;
    // also when the session is down: zenoh-pico then only releases the query
    const module = this.session.module;
    const k = this.session._string(key);
    try {
      this.session._withBytes(payload, attachment, (p, n, a, m) => module._zg_query_reply(this.handle, k, p, n, a, m));
    } finally {
      module._free(k);
    }
  }
}
