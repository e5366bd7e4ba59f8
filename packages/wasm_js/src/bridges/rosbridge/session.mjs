// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * One WebSocket client of the rosbridge server: reads its requests (JSON
 * text, or CBOR binary), checks them, runs the operation, and writes what
 * goes back (JSON text, fragments, PNG, CBOR). Bad input never closes the
 * connection: it gets a `status` error that names the field or the type,
 * with the request's id. The operations live in topics.mjs, services.mjs
 * and actions.mjs, which register handlers here.
 *
 * Limits (rowe's "a slow peer must not stall the others"): every write
 * checks how much the socket still holds; past `maxQueuedBytes` the client
 * is cut off (close 1008) and its subscriptions end, so neither the bus nor
 * other clients ever wait for it.
 *
 * @module bridges/rosbridge/session
 */

import { decodeCbor } from './cbor.mjs';
import { JsonError, parseJson, stringifyJson } from './json.mjs';
import { CLIENT_OPS, field, FieldError, LEVELS } from './protocol.mjs';

const ID_IN_TEXT = /"id"\s*:\s*("(?:[^"\\]|\\.)*"|-?\d+)/;
const MAX_FRAGMENT_GROUPS = 16;
const FRAGMENT_TIMEOUT_MS = 60000;

/** The id of a request whose JSON could not be parsed, when it can be read anyway. */
function idOfText(text) {
  const m = ID_IN_TEXT.exec(text.slice(0, 4096));
  if (!m) return undefined;
  try {
    return JSON.parse(m[1]);
  } catch {
    return undefined;
  }
}

/** A client connection's protocol state. */
export class Session {
  /**
   * @param {object} options
   * @param {object} options.core shared by all sessions: {link, converter, registry, capabilities,
   *   limits: {maxMessageBytes, maxQueuedBytes}, stats, services, actions, log}
   * @param {object} options.conn a WebSocket (send, close, terminate, bufferedAmount, ondrain)
   * @param {number} options.id
   * @param {string} options.peer the client's address, for logs
   */
  constructor({ core, conn, id, peer }) {
    this.core = core;
    this.conn = conn;
    this.id = id;
    this.peer = peer;
    this.level = 'error';
    this.fragmentSize = undefined;
    this.closed = false;
    this.ops = new Map();
    this.cleanups = [];
    this.stats = { received: 0, sent: 0, sentBytes: 0, dropped: 0, expired: 0, errors: 0 };
    this._fragments = new Map();
    this._drainListeners = new Set();
    this._fragmentSeed = 0;
    conn.ondrain = () => {
      for (const f of [...this._drainListeners]) f();
    };
    this.register('fragment', (msg) => this._fragment(msg));
    this.register('set_level', (msg) => this._setLevel(msg));
    this.register('status', () => {}); // a client's status report needs no answer
  }

  /** Register the handler of an operation: `handler(msg)` may return a Promise. */
  register(op, handler) {
    this.ops.set(op, handler);
  }

  /** Run `fn` when the session ends. */
  onClose(fn) {
    this.cleanups.push(fn);
  }

  /** Call `fn` when the socket has written what it held (for queues waiting on a slow client). */
  onDrain(fn) {
    this._drainListeners.add(fn);
    return () => this._drainListeners.delete(fn);
  }

  /** Is the socket holding more than `bytes` not yet written? */
  backedUp(bytes) {
    return this.conn.bufferedAmount > bytes;
  }

  // ------------------------------------------------------------- incoming

  /**
   * A message from the client: text (JSON) or bytes (CBOR).
   * @param {string|ArrayBuffer|Uint8Array} data
   * @param {boolean} binary
   */
  receive(data, binary) {
    if (this.closed) return;
    this.stats.received++;
    let msg;
    if (binary) {
      try {
        msg = decodeCbor(data instanceof Uint8Array ? data : new Uint8Array(data));
      } catch (e) {
        this.status('error', `a binary message is not CBOR: ${e.message} (send rosbridge requests as JSON text, or as CBOR)`);
        return;
      }
    } else {
      try {
        msg = parseJson(data);
      } catch (e) {
        if (!(e instanceof JsonError)) throw e;
        this.status('error', `malformed JSON: ${e.message}; the request was dropped`, idOfText(data));
        return;
      }
    }
    this.handle(msg);
  }

  /** Run one parsed request. */
  handle(msg) {
    if (msg === null || typeof msg !== 'object' || Array.isArray(msg)) {
      this.status('error', `a rosbridge request must be a JSON object with an 'op' field, got ${Array.isArray(msg) ? 'an array' : typeof msg}`);
      return;
    }
    const id = msg.id;
    if (msg.op === undefined) {
      this.status('error', `the request has no 'op' field: every request needs one, of ${CLIENT_OPS.join(', ')}`, id);
      return;
    }
    const handler = this.ops.get(msg.op);
    if (!handler) {
      this.status('error', `unknown operation ${stringifyJson(msg.op).slice(0, 100)}: the operations are ${CLIENT_OPS.join(', ')}`, id);
      return;
    }
    if (msg.fragment_size !== undefined && msg.op !== 'subscribe') {
      try {
        this.fragmentSize = field(msg, 'fragment_size', 'int') || undefined;
      } catch (e) {
        this.error(msg, e);
        return;
      }
    }
    let result;
    try {
      result = handler(msg);
    } catch (e) {
      this.error(msg, e);
      return;
    }
    if (result && typeof result.then === 'function') result.catch((e) => this.error(msg, e));
  }

  /** Report a failed request as a status error (naming the op unless the error does). */
  error(msg, e) {
    this.stats.errors++;
    const text = e instanceof FieldError || String(e.message).startsWith(`${msg.op}:`) ? e.message : `${msg.op}: ${e.message}`;
    if (!(e instanceof FieldError) && !e.expected && this.core.log && e.name !== 'ConvertError' && e.name !== 'UnknownTypeError' && e.name !== 'CdrError') {
      this.core.log('debug', `[client ${this.id}] ${msg.op} failed: ${e.stack || e}`);
    }
    this.status('error', text, msg.id);
  }

  _fragment(msg) {
    const id = field(msg, 'id', 'id', { required: true, what: 'the fragments of one message share it' });
    const num = field(msg, 'num', 'int', { required: true });
    const total = field(msg, 'total', 'int', { required: true });
    const data = field(msg, 'data', 'string', { required: true });
    if (total < 1 || num < 0 || num >= total) throw new FieldError('fragment', 'num', `must be from 0 to total - 1 (${total - 1}), got ${num}`);
    let group = this._fragments.get(id);
    if (!group) {
      if (this._fragments.size >= MAX_FRAGMENT_GROUPS) {
        throw new Error(`more than ${MAX_FRAGMENT_GROUPS} fragmented messages are incomplete; fragment ${num} of '${id}' was dropped`);
      }
      group = { total, parts: new Array(total), received: 0, bytes: 0, timer: null };
      group.timer = setTimeout(() => {
        this._fragments.delete(id);
        this.status('warning', `fragmented message '${id}' timed out with ${group.received} of ${group.total} fragments`, id);
      }, FRAGMENT_TIMEOUT_MS);
      if (group.timer.unref) group.timer.unref();
      this._fragments.set(id, group);
    }
    if (total !== group.total) throw new FieldError('fragment', 'total', `is ${total}, but earlier fragments of '${id}' said ${group.total}`);
    if (group.parts[num] !== undefined) return;
    group.parts[num] = data;
    group.received++;
    group.bytes += data.length;
    if (group.bytes > this.core.limits.maxMessageBytes) {
      clearTimeout(group.timer);
      this._fragments.delete(id);
      throw new Error(`the fragmented message '${id}' is larger than the limit of ${this.core.limits.maxMessageBytes} bytes`);
    }
    if (group.received === group.total) {
      clearTimeout(group.timer);
      this._fragments.delete(id);
      this.receive(group.parts.join(''), false);
    }
  }

  _setLevel(msg) {
    const level = field(msg, 'level', 'string', { required: true });
    if (!LEVELS.includes(level)) throw new FieldError('set_level', 'level', `must be one of ${LEVELS.join(', ')}, got '${level}'`);
    this.level = level;
  }

  // ------------------------------------------------------------- outgoing

  /** Send a status message when the client's level shows it. */
  status(level, text, id) {
    const rank = LEVELS.indexOf(level === 'warn' ? 'warning' : level);
    if (rank < 0 || rank > LEVELS.indexOf(this.level) || this.level === 'none') return;
    const out = { op: 'status', level: LEVELS[rank], msg: text };
    if (id !== undefined && id !== null) out.id = id;
    this.sendJson(out);
  }

  /** Send a protocol message (a JS object, BigInt allowed). */
  sendJson(obj, fragmentSize = this.fragmentSize) {
    this.sendText(stringifyJson(obj), fragmentSize, obj.id);
  }

  /** Send JSON text, fragmented when longer than `fragmentSize`. */
  sendText(text, fragmentSize = this.fragmentSize, id = undefined) {
    if (fragmentSize && text.length > fragmentSize) {
      const fid = id !== undefined ? id : `fragment:${this.id}:${++this._fragmentSeed}`;
      const total = Math.ceil(text.length / fragmentSize);
      for (let i = 0; i < total; i++) {
        this.write(stringifyJson({ op: 'fragment', id: fid, data: text.slice(i * fragmentSize, (i + 1) * fragmentSize), num: i, total }));
      }
      return;
    }
    this.write(text);
  }

  /**
   * Write one WebSocket message; cut the client off when its socket holds
   * more than the limit.
   * @returns {boolean} false once the session is closed
   */
  write(data) {
    if (this.closed) return false;
    this.conn.send(data);
    this.stats.sent++;
    this.stats.sentBytes += data.length;
    const limit = this.core.limits.maxQueuedBytes;
    if (this.conn.bufferedAmount > limit) {
      this.cutOff(`the client did not read: more than ${limit} bytes were waiting to be sent (--rosbridge-max-queued-bytes)`);
      return false;
    }
    return true;
  }

  /** Close a client that breaks a limit; nothing waits for it. */
  cutOff(reason) {
    if (this.closed) return;
    if (this.core.log) this.core.log('warning', `[client ${this.id} ${this.peer}] cut off: ${reason}`);
    this.core.stats.cutOff++;
    this.end();
    this.conn.close(1008, reason.slice(0, 120));
    setTimeout(() => this.conn.terminate(), 200).unref?.();
  }

  /** End the session: unsubscribe, unadvertise, fail pending calls. */
  end() {
    if (this.closed) return;
    this.closed = true;
    for (const g of this._fragments.values()) clearTimeout(g.timer);
    this._fragments.clear();
    this._drainListeners.clear();
    for (const fn of this.cleanups.splice(0).reverse()) {
      try {
        fn();
      } catch (e) {
        if (this.core.log) this.core.log('debug', `[client ${this.id}] cleanup failed: ${e.stack || e}`);
      }
    }
  }
}
