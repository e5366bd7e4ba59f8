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
 *    as `publish` (JSON, with `ttl` when the publisher has a lifespan; to
 *    serve's relay in the forms it asks for with `colcon_wasm_forms`: the
 *    CDR bytes as a CBOR publish, JSON, or both);
 *  - a topic local nodes subscribe to: subscribed remotely with cbor-raw
 *    compression, each message's CDR bytes published locally unchanged;
 *  - a service local nodes serve: advertised remotely, remote calls are
 *    made locally and answered;
 *  - a service local nodes call that no local node serves: served locally
 *    by the bridge, each call made remotely;
 *  - an action local nodes serve: advertised remotely (advertise_action),
 *    remote goals sent to it; an action local nodes use that no local node
 *    serves: served locally by the bridge (action_server.mjs), each goal
 *    sent remotely (send_action_goal), feedback, result and cancel passed on.
 *
 * The bridge's own endpoints belong to the `/rosbridge_client` node (the
 * remote side shows up there in the local graph views); `/rosout`,
 * `/parameter_events`, the rcl parameter services and hidden names are not
 * bridged unless `allow` names them; `deny` leaves out more. To serve's
 * relay, the local nodes' parameter services are advertised and
 * `/parameter_events` is published (not subscribed), so that its clients
 * (serve --foxglove) get and set parameters and hear their changes; and the
 * client reports which local node holds which endpoint (`colcon_wasm_graph`
 * with `endpoints`), so that the relay's rosapi names nodes exactly. A
 * message that comes back from the remote side (our own publish, echoed to
 * our subscription of the same topic) is recognised by its bytes and dropped.
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
import { graphModel } from '../../page/graph.mjs';
import { BusLink } from './bus_link.mjs';
import { ClientCalls } from './client_calls.mjs';
import { BRIDGE_NODES, ClientTopics } from './client_topics.mjs';
import { decodeCbor } from './cbor.mjs';
import { Capabilities } from './capabilities.mjs';
import { Converter } from './convert.mjs';
import { parseJson, stringifyJson } from './json.mjs';

export const CLIENT_NODE = 'rosbridge_client';
const DEFAULT_SKIP = new Set(['/rosout', '/parameter_events']);
const PARAMETER_SERVICES = /\/(describe_parameters|get_parameter_types|get_parameters|list_parameters|set_parameters|set_parameters_atomically)$/;

export const CLIENT_LIMITS = Object.freeze({
  maxQueuedBytes: 64 << 20,
  callTimeoutMs: 10000,
  flushWaitMs: 10000,
  backoffMinMs: 250,
  backoffMaxMs: 8000,
  highWaterBytes: 4 << 20,
  echoWindowMs: 5000,
});


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
    this.relayVersion = 0; // 2: it forwards CDR (cbor-raw) and asks for forms (colcon_wasm_forms)
    this.forms = new Map(); // topic -> {json, cdr}: what the relay's subscribers need of our messages
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
    this.actionsServed = new Map(); // action -> local action server advertised remotely
    this.actionsProxied = new Map(); // action -> remote action server proxied locally
    this.remoteGoals = new Map(); // goal id of the remote side -> local goal handle
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
    this.forms.clear();
    this._send({ op: 'set_level', level: 'warning' });
    for (const b of [...this.out.values(), ...this.draining]) this._advertise(b);
    for (const b of this.in.values()) this._subscribe(b);
    for (const s of this.served.values()) this._advertiseService(s);
    for (const a of this.actionsServed.values()) this._advertiseAction(a);
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
      case 'send_action_goal': this._remoteGoal(msg); break;
      case 'cancel_action_goal': this._remoteCancel(msg); break;
      case 'action_feedback': this._proxiedFeedback(msg); break;
      case 'action_result': this._proxiedResult(msg); break;
      case 'status': this.log(msg.level === 'error' ? 'error' : 'warning', `${this.displayUrl}: ${msg.msg}`); break;
      case 'fragment': this._fragment(msg); break;
      case 'colcon_wasm_relay': this._relayMode(msg); break;
      case 'colcon_wasm_forms': this._relayForms(msg); break;
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

  /**
   * Is a name bridged in this direction: `out` (local publishers), `in`
   * (local subscribers), `served` (local servers), `proxied` (local callers)?
   */
  _bridged(name, direction) {
    if (this.deny && this.deny.allows('subscribe', name)) return false;
    if (this.allow && this.allow.allows('subscribe', name)) return true;
    if (PARAMETER_SERVICES.test(name)) return this.relay && direction === 'served';
    if (name === '/parameter_events') return this.relay && direction === 'out';
    if (DEFAULT_SKIP.has(name)) return false;
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
      const pubs = this._bridged(t.name, 'out') ? t.publishers.filter((e) => !mine(e)) : [];
      const subs = this._bridged(t.name, 'in') ? t.subscriptions.filter((e) => !mine(e)) : [];
      if (pubs.length && this.registry.has(pubs[0].type)) wantOut.set(t.name, { type: pubs[0].type, publishers: pubs });
      if (subs.length && this.registry.has(subs[0].type)) wantIn.set(t.name, { type: subs[0].type });
    }
    const wantServed = new Map();
    const wantProxied = new Map();
    for (const s of raw.services) {
      const servers = s.servers.filter((e) => !mine(e));
      const clients = s.clients.filter((e) => !mine(e));
      const type = (servers[0] || clients[0] || {}).type;
      if (!type || !this.registry.services.has(type)) continue;
      if (servers.length) {
        if (this._bridged(s.name, 'served')) wantServed.set(s.name, { type });
      } else if (clients.length && this._bridged(s.name, 'proxied')) wantProxied.set(s.name, { type });
    }
    const wantActionsServed = new Map();
    const wantActionsProxied = new Map();
    for (const s of raw.services) {
      const m = /^(.*)\/_action\/send_goal$/.exec(s.name);
      if (!m || !this._bridged(m[1])) continue;
      const servers = s.servers.filter((e) => !mine(e));
      const clients = s.clients.filter((e) => !mine(e));
      const type = ((servers[0] || clients[0] || {}).type || '').replace(/_SendGoal$/, '');
      if (!type || !this.registry.actions.has(type)) continue;
      if (servers.length) wantActionsServed.set(m[1], { type });
      else if (clients.length) wantActionsProxied.set(m[1], { type });
    }
    this._apply(this.actionsServed, wantActionsServed, (name, w) => this._startActionServed(name, w), (a) => this._send({ op: 'unadvertise_action', action: a.action }));
    this._apply(this.actionsProxied, wantActionsProxied, (name, w) => this._startActionProxied(name, w), (a) => a.server.close());
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
    for (const a of this.actionsProxied.values()) a.server.close();
    if (this.ws) this.ws.close(1000, 'bridge closed');
    this.state = 'closed';
    this.onChange(this);
  }
}

// topics (client_topics.mjs), services and actions (client_calls.mjs)
for (const part of [ClientTopics, ClientCalls]) {
  for (const name of Object.getOwnPropertyNames(part.prototype)) {
    if (name !== 'constructor') RosbridgeClient.prototype[name] = part.prototype[name];
  }
}

export { graphModel };
