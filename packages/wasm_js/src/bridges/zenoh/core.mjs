// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the Zenoh gateway does, in its worker (gateway_worker.mjs): one bus
 * process with the node `/zenoh_gateway` (gateway_bus.mjs) and one
 * zenoh-pico session (session.mjs), which join the local graph to a ROS 2
 * graph of rmw_zenoh participants through a Zenoh router, speaking
 * rmw_zenoh's wire conventions (keys.mjs). Bridged by use, as the rosbridge
 * client:
 * - a topic local nodes publish goes out (TopicOut), a topic they subscribe
 *   to comes in (TopicIn);
 * - a local server answers remote clients (ServiceServed), and a remote
 *   server is offered to local clients (ServiceProxied);
 * - every local node and endpoint has its liveliness token (tokens.mjs), and
 *   remote ones appear in the local graph views, marked remote
 *   (remote_graph.mjs).
 * No router at the endpoint, or a router gone: the error is logged, the
 * gateway retries with backoff, local nodes go on; what waited is sent once
 * the session is back.
 *
 * @module bridges/zenoh/core
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { BRIDGE_NODES } from '../rosbridge/client_topics.mjs';
import { ServiceProxied, ServiceServed, TopicIn, TopicOut } from './bridges.mjs';
import { Kind } from './keys.mjs';
import { RemoteGraph, fqn } from './remote_graph.mjs';
import { ZenohSession } from './session.mjs';
import { LocalTokens } from './tokens.mjs';

/** The gateway's node in the local graph. */
export const GATEWAY_NODE = 'zenoh_gateway';

/** Limits (overridable with options.limits). */
export const GATEWAY_LIMITS = Object.freeze({
  queueBytes: 16 * 1024 * 1024, // RELIABLE messages kept per topic while there is no session
  callTimeoutMs: 10000,
  backoffMinMs: 500,
  backoffMaxMs: 8000,
});

const SKIPPED_NAMES = new Set(['/rosout', '/parameter_events']);
const PARAMETER_SERVICES = /\/(describe|get|get_parameter_types|list|set|set_parameters_atomically)_parameters?$|\/(describe_parameters|get_parameters|get_parameter_types|list_parameters|set_parameters|set_parameters_atomically)$/;

/** The known types, as the gateway asks: has(message), services.has(), actions.has(). */
export function knownTypes({ messages = [], services = [], actions = [] }) {
  const known = new Set(messages.map(normalizeTypeName));
  return { has: (name) => known.has(normalizeTypeName(name)), services: new Set(services), actions: new Set(actions) };
}

/**
 * The Zenoh gateway of one bus, in its worker.
 */
export class GatewayCore {
  /**
   * @param {import('./gateway_bus.mjs').GatewayBus} bus the gateway's bus process
   * @param {object} options
   * @param {{has: function(string): boolean, services: Set<string>, actions: Set<string>}} options.registry
   *   the types this install knows (knownTypes())
   * @param {string} options.endpoint `ws/HOST:PORT` or (Node.js) `tcp/HOST:PORT`
   * @param {function(object): Promise<object>} options.createModule zenoh_session.mjs's factory
   * @param {function} [options.WebSocket]
   * @param {number} [options.domain=0]
   * @param {object} [options.limits] GATEWAY_LIMITS' keys
   * @param {function(string, string): void} [options.log] (level, text)
   * @param {function(GatewayCore): void} [options.onChange] state or remote graph changes
   */
  constructor(bus, { registry, endpoint, createModule, WebSocket: WS, domain = 0, limits = {}, log, onChange }) {
    this.bus = bus;
    this.registry = registry;
    this.endpoint = endpoint;
    this.createModule = createModule;
    this.WebSocket = WS;
    this.domain = domain;
    this.limits = { ...GATEWAY_LIMITS, ...limits };
    this.log = log || (() => {});
    this.onChange = onChange || (() => {});
    this.state = 'connecting';
    this.session = null;
    this.closed = false;
    this.backoff = this.limits.backoffMinMs;
    this.counters = { connects: 0, sent: 0, received: 0, queued: 0, lost: 0, malformed: 0, calls: 0 };
    this.out = new Map();
    this.in = new Map();
    this.served = new Map();
    this.proxied = new Map();
    this.remoteGraph = new RemoteGraph({
      domain, ownZid: () => (this.session ? this.session.zid : ''), log: this.log,
      onChange: () => this._scheduleSync(),
    });
    this.tokens = new LocalTokens({ domain, skip: (n) => this._mine(n), log: this.log });
    this._warnedTypes = new Set();
    this._syncTimer = null;
  }

  /** The remote graph (nodes, topics, services) as the local graph views merge it. */
  get remote() {
    return this.remoteGraph.view();
  }

  /** Follow the local graph and connect (in the background: see `state`). */
  start() {
    this.bus.onGraphChange(() => this._scheduleSync());
    this._connect();
  }

  _mine(e) {
    const name = fqn(e.namespace, e.node || e.name);
    return e.pid === this.bus.pid || name === `/${GATEWAY_NODE}` || BRIDGE_NODES.has(name);
  }

  async _connect() {
    if (this.closed) return;
    this.state = this.counters.connects ? 'reconnecting' : 'connecting';
    this.onChange(this);
    let session;
    try {
      session = await ZenohSession.open({
        endpoint: this.endpoint, createModule: this.createModule, WebSocket: this.WebSocket,
        onClosed: (error) => this._lost(session, error),
      });
    } catch (error) {
      if (this.closed) return;
      this.log(this.counters.connects ? 'warning' : 'error',
        `cannot reach a Zenoh router at ${this.endpoint}: ${error.message}; retrying in ${(this.backoff / 1000).toFixed(1)} s `
        + '(local nodes keep running; start a router, e.g. zenohd, or check the endpoint)');
      this._retry();
      return;
    }
    if (this.closed) {
      session.close();
      return;
    }
    this.session = session;
    this.backoff = this.limits.backoffMinMs;
    this.counters.connects += 1;
    this.state = 'connected';
    this.log('info', `connected to the Zenoh router at ${this.endpoint} (session ${session.zid})`);
    this.tokens.attach(session);
    const prefix = `@ros2_lv/${this.domain}/**`;
    try {
      this.livelinessSub = session.subscribeLiveliness(prefix, (s) => this.remoteGraph.sample(s), { history: true });
    } catch (error) {
      this.log('error', `cannot follow the remote graph: ${error.message}`);
    }
    for (const map of [this.out, this.in, this.served, this.proxied]) for (const b of map.values()) b.attach(session);
    this._sync();
    this.onChange(this);
  }

  _retry() {
    if (this.closed) return;
    this.state = 'retrying';
    this.onChange(this);
    const delay = this.backoff;
    this.backoff = Math.min(this.backoff * 2, this.limits.backoffMaxMs);
    this._retryTimer = setTimeout(() => { this._retryTimer = null; this._connect(); }, delay);
  }

  _lost(session, error) {
    if (this.session !== session || this.closed) return;
    this.session = null;
    this.log('warning', `lost the Zenoh router at ${this.endpoint}: ${error.message}; reconnecting`);
    for (const map of [this.out, this.in, this.served, this.proxied]) for (const b of map.values()) b.detach();
    this.remoteGraph.clear();
    this._retry();
  }

  _scheduleSync() {
    if (this._syncTimer || this.closed) return;
    this._syncTimer = setTimeout(() => {
      this._syncTimer = null;
      this._sync();
    }, 30);
  }

  _bridged(name) {
    if (SKIPPED_NAMES.has(name) || PARAMETER_SERVICES.test(name)) return false;
    // hidden names stay local, but for actions' (rmw_zenoh carries them as any other)
    return !name.split('/').some((part) => part.startsWith('_') && part !== '_action');
  }

  _known(type, where, isService = false) {
    // an action's services and feedback topic have types of their own, known with the action
    const action = /^(.+\/action\/.+)_(SendGoal|GetResult|FeedbackMessage)$/.exec(type);
    const known = (action && this.registry.actions && this.registry.actions.has(action[1]))
      || (isService ? this.registry.services.has(type) : this.registry.has(type));
    if (!known && !this._warnedTypes.has(type)) {
      this._warnedTypes.add(type);
      this.log('warning', `${where} has type ${type}, which this install does not know (no interface package for it): not bridged to Zenoh`);
    }
    return known;
  }

  /** Compare what local nodes use with what is bridged; add and remove bridges and tokens. */
  _sync() {
    if (this.closed) return;
    const raw = this.bus.rawGraph();
    if (this.session && this.session.up) this.tokens.sync(raw);
    const mine = (e) => this._mine(e);
    const wantOut = new Map();
    const wantIn = new Map();
    for (const t of raw.topics) {
      if (t.domain !== this.domain || !this._bridged(t.name)) continue;
      const pubs = t.publishers.filter((e) => !mine(e));
      const subs = t.subscriptions.filter((e) => !mine(e));
      if (pubs.length && this._known(pubs[0].type, t.name)) wantOut.set(t.name, { type: normalizeTypeName(pubs[0].type), publishers: pubs });
      // in: local subscriptions and remote publishers (their tokens); the gateway has one local
      // proxy publisher per remote one, so local subscriptions see each leave (graph, liveliness)
      const remotePubs = this.remoteGraph.endpoints(Kind.PUBLISHER, t.name);
      if (subs.length && remotePubs.length && this._known(subs[0].type, t.name)) {
        const qos = subs.map((e) => e.qos || {});
        const latched = qos.filter((q) => q.durability === 'transient_local');
        const remoteLatched = remotePubs.some((e) => e.qos && e.qos.durability === 'transient_local');
        wantIn.set(t.name, {
          type: normalizeTypeName(subs[0].type), remotes: remotePubs.length,
          qos: latched.length && remoteLatched
            ? { history: 'keep_last', depth: Math.max(1, ...latched.map((q) => q.depth || 1)), reliability: 'reliable', durability: 'transient_local' }
            : { history: 'keep_last', depth: Math.max(10, ...qos.map((q) => q.depth || 10)), reliability: qos.every((q) => q.reliability === 'best_effort') ? 'best_effort' : 'reliable', durability: 'volatile' },
        });
      }
    }
    for (const e of this.remoteGraph.entities.values()) {
      // a remote type the local side uses under another name is named once
      const local = raw.topics.find((t) => t.name === e.name && t.domain === this.domain);
      if (local && local.types.length && normalizeTypeName(local.types[0]) !== normalizeTypeName(e.type)) {
        this._known(`${e.type} (locally ${local.types[0]})`, `remote ${e.name}`);
      }
    }
    const wantServed = new Map();
    const wantProxied = new Map();
    for (const s of raw.services) {
      if (s.domain !== this.domain || !this._bridged(s.name)) continue;
      const servers = s.servers.filter((e) => !mine(e));
      const clients = s.clients.filter((e) => !mine(e));
      const type = (servers[0] || clients[0] || {}).type;
      if (!type || !this._known(type, s.name, true)) continue;
      if (servers.length) wantServed.set(s.name, { type: normalizeTypeName(type) });
      else if (clients.length && this.remoteGraph.endpoints(Kind.SERVER, s.name).length) wantProxied.set(s.name, { type: normalizeTypeName(type) });
    }
    this._apply(this.out, wantOut, TopicOut);
    this._apply(this.in, wantIn, TopicIn, (b, w) => b.qos.durability === w.qos.durability && b.qos.depth === w.qos.depth);
    this._apply(this.served, wantServed, ServiceServed);
    this._apply(this.proxied, wantProxied, ServiceProxied);
    for (const [name, w] of wantOut) {
      const b = this.out.get(name);
      if (b) b.publishers = w.publishers;
    }
    // one local publisher per remote one: a remote publisher that goes is one less alive
    for (const [name, w] of wantIn) this.in.get(name).setRemotes(w.remotes);
    this.onChange(this);
  }

  _apply(current, wanted, Bridge, same = () => true) {
    for (const [name, b] of current) {
      const w = wanted.get(name);
      if (!w || w.type !== b.type || !same(b, w)) {
        current.delete(name);
        b.close();
      }
    }
    for (const [name, w] of wanted) {
      if (current.has(name)) continue;
      this.log('debug', `bridging ${name} (${Bridge.name}, ${w.type})`);
      const b = new Bridge(this, name, w);
      current.set(name, b);
      if (this.session && this.session.up) b.attach(this.session);
    }
  }

  /** What the gateway did, for `--zenoh` status lines and tests. */
  status() {
    return {
      state: this.state, endpoint: this.endpoint, zid: this.session ? this.session.zid : null,
      counters: { ...this.counters, malformedTokens: this.remoteGraph.malformed },
      out: [...this.out.keys()], in: [...this.in.keys()], served: [...this.served.keys()], proxied: [...this.proxied.keys()],
    };
  }

  /** Stop bridging: tokens are withdrawn with the session. */
  async close() {
    this.closed = true;
    if (this._syncTimer) clearTimeout(this._syncTimer);
    if (this._retryTimer) clearTimeout(this._retryTimer);
    for (const map of [this.out, this.in, this.served, this.proxied]) {
      for (const b of map.values()) b.close();
      map.clear();
    }
    if (this.session) this.session.close();
    this.session = null;
    this.bus.close();
    this.state = 'closed';
    this.onChange(this);
  }
}
