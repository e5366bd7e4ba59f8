// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * A rosbridge client in the runtime (`colcon-wasm launch
 * --rosbridge-connect ws://HOST:PORT`, the page's `?rosbridge=ws://...`):
 * it bridges the local nodes to a remote rosbridge v2 server (a robot's
 * rosbridge_server, or another colcon-wasm) by what they use, read from the
 * local graph as it changes:
 *
 *  - a topic local nodes publish: advertised remotely, each message sent
 *    as `publish` (JSON, with `ttl` when the publisher has a lifespan);
 *  - a topic local nodes subscribe to: subscribed remotely with cbor-raw
 *    compression, each message's CDR bytes published locally unchanged;
 *  - a service local nodes serve: advertised remotely, remote calls are
 *    made locally and answered;
 *  - a service local nodes call that no local node serves: served locally
 *    by the bridge, each call made remotely.
 *
 * The bridge's own endpoints belong to the `/rosbridge_client` node (the
 * remote side shows up there in the local graph views); `/rosout`,
 * `/parameter_events`, the rcl parameter services and hidden names are not
 * bridged unless `allow` names them; `deny` leaves out more. A message that
 * comes back from the remote side (our own publish, echoed to our
 * subscription of the same topic) is recognised by its bytes and dropped.
 *
 * Disconnected (or while the socket is backed up), what local publishers
 * send waits: KEEP_LAST keeps the last `depth` messages, RELIABLE KEEP_ALL
 * up to `limits.maxQueuedBytes` in all, BEST_EFFORT nothing; messages past
 * their lifespan are dropped. On reconnection (backoff 0.25 s doubling to
 * 8 s) everything is advertised and subscribed again and the queues are
 * sent in order once the remote topic has a subscriber (asked with
 * /rosapi/subscribers, at most `limits.flushWaitMs`). What was dropped is
 * counted (`stats()`) and reported in the log.
 *
 * @module bridges/rosbridge/client
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { graphModel } from '../../tools/graph.mjs';
import { BusLink, gidHex } from './bus_link.mjs';
import { decodeCbor } from './cbor.mjs';
import { Capabilities } from './capabilities.mjs';
import { Converter } from './convert.mjs';
import { parseJson, stringifyJson } from './json.mjs';

export const CLIENT_NODE = 'rosbridge_client';
const BRIDGE_NODES = new Set([`/${CLIENT_NODE}`, '/rosbridge_websocket']);
const DEFAULT_SKIP = new Set(['/rosout', '/parameter_events']);
const PARAMETER_SERVICES = /\/(describe_parameters|get_parameter_types|get_parameters|list_parameters|set_parameters|set_parameters_atomically)$/;
const IN_QOS = { history: 'keep_last', depth: 10, reliability: 'reliable', durability: 'transient_local' };

export const CLIENT_LIMITS = Object.freeze({
  maxQueuedBytes: 64 << 20,
  callTimeoutMs: 10000,
  flushWaitMs: 10000,
  backoffMinMs: 250,
  backoffMaxMs: 8000,
  highWaterBytes: 4 << 20,
  echoWindowMs: 5000,
});

/** A cheap fingerprint of bytes (FNV-1a over length and every byte). */
function fingerprint(bytes) {
  let h = 0x811c9dc5 ^ bytes.length;
  for (let i = 0; i < bytes.length; i++) h = Math.imul(h ^ bytes[i], 16777619);
  return `${bytes.length}:${h >>> 0}`;
}

/** The client side of a bridge to one remote rosbridge server. */
export class RosbridgeClient {
  /**
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../cdr.mjs').TypeRegistry} options.registry
   * @param {string} options.url ws://HOST:PORT of the remote server
   * @param {string} [options.token] sent as ?token=
   * @param {string[]} [options.allow] name patterns bridged even when skipped by default
   * @param {string[]} [options.deny] name patterns never bridged
   * @param {object} [options.limits] CLIENT_LIMITS' keys
   * @param {function} [options.WebSocket] the WebSocket class (the browser's by default)
   * @param {function(string, string): void} [options.log]
   * @param {function(object): void} [options.onChange] state and remote graph changes
   * @param {boolean} [options.remoteGraph=false] ask the remote graph (rosapi) every 2 s
   * @returns {Promise<RosbridgeClient>}
   */
  static async start(options) {
    const tools = await options.runtime.tools();
    const link = await BusLink.create({ runtime: options.runtime, tools, nodeName: CLIENT_NODE, ignoreLocal: true });
    const client = new RosbridgeClient(link, options);
    client._connect();
    options.runtime.onGraphChange(() => client._scheduleSync());
    client._scheduleSync();
    return client;
  }

  constructor(link, { registry, url, token, allow = [], deny = [], limits = {}, WebSocket: WS, log, onChange, remoteGraph = false }) {
    this.link = link;
    this.registry = registry;
    this.converter = new Converter(registry);
    this.url = token ? `${url}${url.includes('?') ? '&' : '?'}token=${encodeURIComponent(token)}` : url;
    this.displayUrl = url;
    this.allow = allow.length ? new Capabilities({ subscribe: allow }) : null;
    this.deny = deny.length ? new Capabilities({ subscribe: deny }) : null;
    this.limits = { ...CLIENT_LIMITS, ...limits };
    this.WebSocket = WS || globalThis.WebSocket;
    this.log = log || (() => {});
    this.onChange = onChange || (() => {});
    this.wantRemoteGraph = remoteGraph;
    this.relay = false; // the server is serve's relay (it greets with colcon_wasm_relay)
    this._reported = null;
    this.state = 'connecting';
    this.remote = { nodes: [], topics: [], services: [] };
    this.ws = null;
    this.closed = false;
    this.backoff = this.limits.backoffMinMs;
    this.out = new Map(); // topic -> outgoing bridge (local publishers)
    this.in = new Map(); // topic -> incoming bridge (local subscribers)
    this.served = new Map(); // service -> local server advertised remotely
    this.proxied = new Map(); // service -> remote server proxied locally
    this.pending = new Map(); // call id -> {resolve, reject, timer}
    this.draining = new Set(); // outgoing bridges whose publishers left, with messages to deliver
    this.queuedBytes = 0;
    this.counters = { connects: 0, sent: 0, received: 0, queued: 0, lost: 0, replaced: 0, expired: 0, echoes: 0, dropped: 0 };
    this._seq = 0;
    this._syncTimer = null;
    this._graphTimer = null;
  }

  /** Counters and state, for logs, tests and the page. */
  stats() {
    return { state: this.state, url: this.displayUrl, queuedBytes: this.queuedBytes, ...this.counters };
  }

  // ----------------------------------------------------------- connection

  _connect() {
    if (this.closed) return;
    this.state = this.counters.connects ? 'reconnecting' : 'connecting';
    this.onChange(this);
    let ws;
    try {
      ws = new this.WebSocket(this.url);
    } catch (e) {
      this.log('error', `cannot connect to ${this.displayUrl}: ${e.message}`);
      this._retry();
      return;
    }
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onopen = () => this._opened();
    ws.onmessage = (e) => this._message(e.data);
    ws.onerror = () => {};
    ws.onclose = (e) => this._closed(e);
  }

  _retry() {
    if (this.closed) return;
    const delay = this.backoff * (0.8 + Math.random() * 0.4);
    this.backoff = Math.min(this.backoff * 2, this.limits.backoffMaxMs);
    const t = setTimeout(() => this._connect(), delay);
    if (t.unref) t.unref();
  }

  _opened() {
    this.counters.connects++;
    this.backoff = this.limits.backoffMinMs;
    const again = this.counters.connects > 1;
    this.state = 'connected';
    this.log('info', `${again ? 'reconnected' : 'connected'} to ${this.displayUrl}`);
    this._reported = null;
    this._send({ op: 'set_level', level: 'warning' });
    for (const b of [...this.out.values(), ...this.draining]) this._advertise(b);
    for (const b of this.in.values()) this._subscribe(b);
    for (const s of this.served.values()) this._advertiseService(s);
    for (const b of [...this.out.values(), ...this.draining]) this._flushWhenHeard(b);
    for (const p of this.proxied.values()) this._sendWaitingCalls(p);
    if (this.wantRemoteGraph) this._pollRemoteGraph();
    this.onChange(this);
  }

  _closed(e) {
    const was = this.state;
    this.ws = null;
    this.state = this.closed ? 'closed' : 'disconnected';
    for (const p of this.pending.values()) {
      clearTimeout(p.timer);
      p.reject(new Error(`the connection to ${this.displayUrl} closed`));
    }
    this.pending.clear();
    if (!this.closed) {
      if (was === 'connected') this.log('warning', `lost the connection to ${this.displayUrl} (${e.code}${e.reason ? ` ${e.reason}` : ''}); reconnecting`);
      else if (this.counters.connects === 0 && this.backoff === this.limits.backoffMinMs) this.log('warning', `cannot connect to ${this.displayUrl} yet; retrying`);
      this._retry();
    }
    this.onChange(this);
  }

  /** Open, and not closing (a message sent while closing would be lost: it is queued instead). */
  get connected() {
    return this.state === 'connected' && this.ws !== null && this.ws.readyState === 1;
  }

  _send(obj) {
    return this._sendRaw(typeof obj === 'string' ? obj : stringifyJson(obj));
  }

  _sendRaw(text) {
    if (!this.connected) return false;
    this.ws.send(text);
    this.counters.sent++;
    return true;
  }

  _call(service, args, timeoutMs = this.limits.callTimeoutMs) {
    if (!this.connected) return Promise.reject(new Error(`not connected to ${this.displayUrl}`));
    const id = `client_call:${++this._seq}`;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.pending.delete(id);
        reject(new Error(`${service} did not answer within ${timeoutMs} ms`));
      }, timeoutMs);
      this.pending.set(id, { resolve, reject, timer });
      this._send({ op: 'call_service', id, service, args, timeout: timeoutMs / 1000 });
    });
  }

  _message(data) {
    this.counters.received++;
    let msg;
    try {
      msg = typeof data === 'string' ? parseJson(data) : decodeCbor(new Uint8Array(data));
    } catch (e) {
      this.log('warning', `a message from ${this.displayUrl} could not be read: ${e.message}`);
      return;
    }
    switch (msg.op) {
      case 'publish': this._remotePublish(msg); break;
      case 'service_response': {
        const p = this.pending.get(msg.id);
        if (p) {
          this.pending.delete(msg.id);
          clearTimeout(p.timer);
          if (msg.result) p.resolve(msg.values);
          else p.reject(new Error(typeof msg.values === 'string' ? msg.values : `${msg.service} failed`));
        }
        break;
      }
      case 'call_service': this._remoteCall(msg); break;
      case 'status': this.log(msg.level === 'error' ? 'error' : 'warning', `${this.displayUrl}: ${msg.msg}`); break;
      case 'fragment': this._fragment(msg); break;
      case 'colcon_wasm_relay': this._relayMode(); break;
      default: break;
    }
  }

  _fragment(msg) {
    if (!this._fragments) this._fragments = new Map();
    let g = this._fragments.get(msg.id);
    if (!g) {
      g = { parts: new Array(msg.total), received: 0 };
      this._fragments.set(msg.id, g);
    }
    if (g.parts[msg.num] === undefined) { g.parts[msg.num] = msg.data; g.received++; }
    if (g.received === msg.total) {
      this._fragments.delete(msg.id);
      this._message(g.parts.join(''));
    }
  }

  // ----------------------------------------------------------- what to bridge

  _bridged(name) {
    if (this.deny && this.deny.allows('subscribe', name)) return false;
    if (this.allow && this.allow.allows('subscribe', name)) return true;
    if (DEFAULT_SKIP.has(name) || PARAMETER_SERVICES.test(name)) return false;
    return !name.split('/').some((part) => part.startsWith('_'));
  }

  _scheduleSync() {
    if (this._syncTimer || this.closed) return;
    this._syncTimer = setTimeout(() => {
      this._syncTimer = null;
      this._sync();
    }, 30);
  }

  /** Compare what local nodes use with what is bridged; add and remove bridges. */
  _sync() {
    const raw = this.link.rawGraph();
    const mine = (e) => BRIDGE_NODES.has(`${e.namespace === '/' ? '' : e.namespace}/${e.node}`);
    const wantOut = new Map();
    const wantIn = new Map();
    for (const t of raw.topics) {
      if (!this._bridged(t.name)) continue;
      const pubs = t.publishers.filter((e) => !mine(e));
      const subs = t.subscriptions.filter((e) => !mine(e));
      if (pubs.length && this.registry.has(pubs[0].type)) wantOut.set(t.name, { type: pubs[0].type, publishers: pubs });
      if (subs.length && this.registry.has(subs[0].type)) wantIn.set(t.name, { type: subs[0].type });
    }
    const wantServed = new Map();
    const wantProxied = new Map();
    for (const s of raw.services) {
      if (!this._bridged(s.name)) continue;
      const servers = s.servers.filter((e) => !mine(e));
      const clients = s.clients.filter((e) => !mine(e));
      const type = (servers[0] || clients[0] || {}).type;
      if (!type || !this.registry.services.has(type)) continue;
      if (servers.length) wantServed.set(s.name, { type });
      else if (clients.length) wantProxied.set(s.name, { type });
    }
    this._apply(this.out, wantOut, (name, w) => this._startOut(name, w), (b) => this._stopOut(b));
    this._apply(this.in, wantIn, (name, w) => this._startIn(name, w), (b) => this._stopIn(b));
    this._apply(this.served, wantServed, (name, w) => this._startServed(name, w), (b) => this._stopServed(b));
    this._apply(this.proxied, wantProxied, (name, w) => this._startProxied(name, w), (b) => this._stopProxied(b));
    for (const [name, w] of wantOut) {
      const b = this.out.get(name);
      if (b) b.publishers = w.publishers;
    }
    this._reportGraph();
    this.onChange(this);
  }

  _apply(current, wanted, start, stop) {
    for (const [name, b] of current) {
      const w = wanted.get(name);
      if (!w || normalizeTypeName(w.type) !== normalizeTypeName(b.type)) {
        current.delete(name);
        stop(b);
      }
    }
    for (const [name, w] of wanted) if (!current.has(name)) current.set(name, start(name, w));
  }

  // ----------------------------------------------------------- topics out

  _startOut(topic, { type, publishers }) {
    const b = { topic, type, publishers, queue: [], stop: null, lifespans: new Map(), echoes: new Map(), flushing: false };
    this._advertise(b);
    // hear every message the publishers keep: KEEP_ALL publishers wait for a KEEP_ALL reader
    const qos = publishers.map((e) => e.qos || {});
    const keepAll = qos.some((q) => q.history === 'keep_all' && q.reliability !== 'best_effort');
    const tapQos = {
      history: keepAll ? 'keep_all' : 'keep_last', depth: Math.max(100, ...qos.map((q) => q.depth || 0)),
      reliability: qos.some((q) => q.reliability === 'best_effort') ? 'best_effort' : 'reliable',
      durability: qos.length && qos.every((q) => q.durability === 'transient_local') ? 'transient_local' : 'volatile',
    };
    this.link.listen(topic, type, (batch) => this._localMessages(b, batch), tapQos).then((stop) => {
      if (this.out.get(topic) !== b) stop();
      else b.stop = stop;
    }, (e) => this.log('error', `cannot bridge ${topic}: ${e.message}`));
    return b;
  }

  _stopOut(b) {
    if (b.stop) b.stop();
    if (b.kick) clearTimeout(b.kick);
    if (b.queue.length && !this.closed) {
      // the publisher is gone, what it sent is not: deliver it, then unadvertise
      b.draining = true;
      this.draining.add(b);
      if (this.connected) this._flushWhenHeard(b);
      return;
    }
    this._send({ op: 'unadvertise', topic: b.topic });
  }

  _advertise(b) {
    const q = (b.publishers[0] && b.publishers[0].qos) || {};
    this._send({
      op: 'advertise', topic: b.topic, type: b.type, latch: q.durability === 'transient_local',
      queue_size: q.depth || 10,
    });
  }

  _publisherQos(b, gid) {
    const hex = gidHex(gid);
    const p = b.publishers.find((e) => e.gid === hex) || b.publishers[0] || {};
    return p.qos || {};
  }

  _localMessages(b, batch) {
    for (const m of batch) {
      const qos = this._publisherQos(b, m.info.publisherGid);
      const lifespan = Number.isFinite(qos.lifespanMs) && qos.lifespanMs > 0 ? qos.lifespanMs : 0;
      const entry = { data: m.data, time: m.info.sourceTime, expires: lifespan ? m.info.sourceTime + lifespan : Infinity, qos };
      if (this.connected && !b.queue.length && !b.flushing && this.ws.bufferedAmount < this.limits.highWaterBytes) this._publishOut(b, entry);
      else this._enqueue(b, entry);
    }
    if (b.queue.length && this.connected && !b.flushing && !b.kick) {
      b.kick = setTimeout(() => { b.kick = null; this._flush(b); }, 10);
    }
  }

  _enqueue(b, entry) {
    const qos = entry.qos;
    if (qos.reliability === 'best_effort') {
      this.counters.dropped++;
      return;
    }
    if (qos.history !== 'keep_all') {
      const depth = Math.max(1, qos.depth || 10);
      while (b.queue.length >= depth) {
        const old = b.queue.shift();
        this.queuedBytes -= old.data.length;
        this.counters.replaced++;
        b.replaced = (b.replaced || 0) + 1;
      }
    } else if (this.queuedBytes + entry.data.length > this.limits.maxQueuedBytes) {
      this.counters.lost++;
      b.lost = (b.lost || 0) + 1;
      return;
    }
    b.queue.push(entry);
    this.queuedBytes += entry.data.length;
    this.counters.queued++;
  }

  _dropQueue(b) {
    for (const e of b.queue) this.queuedBytes -= e.data.length;
    b.queue = [];
  }

  _publishOut(b, entry) {
    if (Date.now() > entry.expires) {
      this.counters.expired++;
      return true;
    }
    let json;
    try {
      json = this.converter.jsonWriter(b.type)(this.registry.decode(b.type, entry.data));
    } catch (e) {
      this.log('error', `cannot bridge a message of ${b.topic}: ${e.message}`);
      return true;
    }
    if (this.in.has(b.topic)) this._expectEcho(b, entry.data);
    const ttl = entry.expires === Infinity ? '' : `,"ttl":${Math.max(1, Math.round(entry.expires - Date.now()))}`;
    return this._sendRaw(`{"op":"publish","topic":${JSON.stringify(b.topic)},"msg":${json}${ttl}}`);
  }

  _expectEcho(b, data) {
    const key = fingerprint(data);
    const now = Date.now();
    const list = b.echoes.get(key) || [];
    list.push(now + this.limits.echoWindowMs);
    b.echoes.set(key, list);
  }

  /** After (re)connecting: send the queue once the remote topic has a subscriber. */
  async _flushWhenHeard(b) {
    if (!b.queue.length || b.flushing) return;
    b.flushing = true;
    const deadline = Date.now() + this.limits.flushWaitMs;
    try {
      while (this.connected && Date.now() < deadline) {
        let subscribers;
        try {
          subscribers = (await this._call('/rosapi/subscribers', { topic: b.topic }, 3000)).subscribers || [];
        } catch {
          break; // no rosapi: send now
        }
        if (subscribers.some((n) => n !== '/rosbridge_websocket')) break;
        await new Promise((r) => setTimeout(r, 100));
      }
    } finally {
      b.flushing = false;
    }
    this._flush(b);
  }

  _flush(b) {
    if (b.replaced || b.lost) {
      this.log('warning', `${b.topic}: ${b.replaced || 0} older messages were replaced (KEEP_LAST) and ${b.lost || 0} lost `
        + `(past the bound of ${this.limits.maxQueuedBytes} bytes) while ${this.displayUrl} was unreachable`);
      b.replaced = 0;
      b.lost = 0;
    }
    while (b.queue.length && this.connected) {
      if (this.ws.bufferedAmount >= this.limits.highWaterBytes) {
        setTimeout(() => this._flush(b), 20);
        return;
      }
      const entry = b.queue.shift();
      this.queuedBytes -= entry.data.length;
      this._publishOut(b, entry);
    }
    if (b.draining && !b.queue.length) {
      this.draining.delete(b);
      if (!this.out.has(b.topic)) this._send({ op: 'unadvertise', topic: b.topic });
    }
  }

  // ----------------------------------------------------------- topics in

  _startIn(topic, { type }) {
    const b = { topic, type, publisher: null, ready: null };
    b.ready = this.link.publisher(topic, type, IN_QOS).then((p) => {
      if (this.in.get(topic) !== b) p.release();
      else b.publisher = p;
      return p;
    });
    b.ready.catch((e) => this.log('error', `cannot bridge ${topic} in: ${e.message}`));
    this._subscribe(b);
    return b;
  }

  _stopIn(b) {
    b.ready.then((p) => p.release(), () => {});
    this._send({ op: 'unsubscribe', topic: b.topic, id: `bridge:${b.topic}` });
  }

  _subscribe(b) {
    // CDR bytes as they are, unless the server is serve's relay (JSON only)
    this._send({ op: 'subscribe', id: `bridge:${b.topic}`, topic: b.topic, type: b.type, compression: this.relay ? 'none' : 'cbor-raw' });
  }

  /**
   * The server is `colcon-wasm serve --rosbridge`'s relay (it said so): it
   * forwards JSON, and shows the nodes each client reports in its rosapi.
   */
  _relayMode() {
    if (this.relay) return;
    this.relay = true;
    for (const b of this.in.values()) this._subscribe(b);
    this._reported = null;
    this._reportGraph();
  }

  _reportGraph() {
    if (!this.relay || !this.connected) return;
    const nodes = this.link.rawGraph().nodes.map((n) => `${n.namespace === '/' ? '' : n.namespace}/${n.name}`)
      .filter((fqn) => !BRIDGE_NODES.has(fqn)).sort();
    const key = nodes.join('\n');
    if (key === this._reported) return;
    this._reported = key;
    this._send({ op: 'colcon_wasm_graph', nodes });
  }

  _remotePublish(msg) {
    const b = this.in.get(msg.topic);
    if (!b) return;
    if (typeof msg.ttl === 'number' && msg.ttl <= 0) {
      this.counters.expired++;
      return;
    }
    let bytes;
    if (msg.msg && msg.msg.bytes instanceof Uint8Array) bytes = msg.msg.bytes;
    else {
      try {
        bytes = this.registry.encode(b.type, this.converter.fromJson(b.type, msg.msg));
      } catch (e) {
        this.log('error', `a message of ${msg.topic} from ${this.displayUrl} does not fit ${b.type}: ${e.message}`);
        return;
      }
    }
    const out = this.out.get(msg.topic);
    if (out && out.echoes.size) {
      const key = fingerprint(bytes);
      const list = out.echoes.get(key);
      const now = Date.now();
      if (list) {
        while (list.length && list[0] < now) list.shift();
        if (list.length) {
          list.shift();
          if (!list.length) out.echoes.delete(key);
          this.counters.echoes++;
          return;
        }
        out.echoes.delete(key);
      }
    }
    if (b.publisher) b.publisher.publish(bytes).catch(() => {});
    else b.ready.then((p) => p.publish(bytes)).catch(() => {});
  }

  // ----------------------------------------------------------- services

  _startServed(service, { type }) {
    const s = { service, type };
    this._advertiseService(s);
    return s;
  }

  _advertiseService(s) {
    this._send({ op: 'advertise_service', service: s.service, type: s.type });
  }

  _stopServed(s) {
    this._send({ op: 'unadvertise_service', service: s.service });
  }

  async _remoteCall(msg) {
    const s = this.served.get(msg.service);
    const reply = (values, result) => this._send({ op: 'service_response', id: msg.id, service: msg.service, values, result });
    if (!s) {
      reply(`${msg.service} is not served here`, false);
      return;
    }
    try {
      const entry = this.registry.service(s.type);
      const request = this.registry.encode(entry.request, this.converter.fromJson(entry.request, msg.args || {}));
      const response = await this.link.call(msg.service, s.type, request, this.limits.callTimeoutMs);
      const json = this.converter.jsonWriter(entry.response)(this.registry.decode(entry.response, response));
      this._sendRaw(`{"op":"service_response","id":${stringifyJson(msg.id)},"service":${JSON.stringify(msg.service)},"values":${json},"result":true}`);
    } catch (e) {
      reply(e.message, false);
    }
  }

  _startProxied(service, { type }) {
    const p = { service, type, server: null, waiting: [] };
    const entry = this.registry.service(type);
    p.ready = this.link.serve(service, type, (requests) => {
      for (const r of requests) {
        p.waiting.push({ r, at: Date.now() });
        if (this.connected) this._sendWaitingCalls(p);
      }
    }, undefined);
    p.ready.then((server) => {
      if (this.proxied.get(service) !== p) server.close().catch(() => {});
      else p.server = server;
    }, (e) => this.log('error', `cannot serve ${service} for ${this.displayUrl}: ${e.message}`));
    p.entry = entry;
    return p;
  }

  _sendWaitingCalls(p) {
    const waiting = p.waiting.splice(0);
    for (const { r, at } of waiting) {
      if (Date.now() - at > this.limits.callTimeoutMs) {
        this.counters.lost++;
        this.log('warning', `a call of ${p.service} waited more than ${this.limits.callTimeoutMs} ms for ${this.displayUrl} and was dropped`);
        continue;
      }
      let args;
      try {
        args = parseJson(this.converter.jsonWriter(p.entry.request)(this.registry.decode(p.entry.request, r.data)));
      } catch (e) {
        this.log('error', `a call of ${p.service} could not be decoded: ${e.message}`);
        continue;
      }
      this._call(p.service, args).then(async (values) => {
        const bytes = this.registry.encode(p.entry.response, this.converter.fromJson(p.entry.response, values || {}));
        const server = p.server || await p.ready;
        await server.respond(r.id, bytes);
      }, (e) => {
        // the remote server may not be there yet: try again within the caller's time
        if (/does not exist/.test(e.message) && Date.now() - at + 250 < this.limits.callTimeoutMs) {
          const t = setTimeout(() => {
            p.waiting.push({ r, at });
            if (this.connected) this._sendWaitingCalls(p);
          }, 250);
          if (t.unref) t.unref();
          return;
        }
        this.log('warning', `${p.service} on ${this.displayUrl} failed: ${e.message} (the local caller gets no response)`);
      });
    }
  }

  _stopProxied(p) {
    p.ready.then((s) => s.close(), () => {}).catch(() => {});
  }

  // ----------------------------------------------------------- remote graph

  async _pollRemoteGraph() {
    if (this._graphTimer || !this.connected) return;
    const poll = async () => {
      this._graphTimer = null;
      if (!this.connected) return;
      try {
        const [topics, nodes, services] = await Promise.all([
          this._call('/rosapi/topics', {}, 5000), this._call('/rosapi/nodes', {}, 5000), this._call('/rosapi/services', {}, 5000),
        ]);
        this.remote = {
          topics: topics.topics.map((name, i) => ({ name, type: topics.types[i] })), nodes: nodes.nodes, services: services.services,
        };
        this.onChange(this);
      } catch {
        // a server without rosapi: no remote graph
      }
      if (this.connected && !this.closed) {
        this._graphTimer = setTimeout(poll, 2000);
        if (this._graphTimer.unref) this._graphTimer.unref();
      }
    };
    await poll();
  }

  /** Stop bridging and close the connection. */
  async close() {
    this.closed = true;
    if (this._syncTimer) clearTimeout(this._syncTimer);
    if (this._graphTimer) clearTimeout(this._graphTimer);
    for (const b of this.out.values()) if (b.stop) b.stop();
    for (const b of this.in.values()) b.ready.then((p) => p.release(), () => {});
    for (const p of this.proxied.values()) this._stopProxied(p);
    if (this.ws) this.ws.close(1000, 'bridge closed');
    this.state = 'closed';
    this.onChange(this);
  }
}

export { graphModel };
