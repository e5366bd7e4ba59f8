// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * What the rosbridge server and client do on the bus, on top of a Runtime's
 * tools process (tools_process/): one bus subscription per topic shared by every
 * WebSocket client that subscribes to it ("taps", messages decoded once),
 * publishers shared by the clients that advertise a topic (reference
 * counted, as rosbridge_library's publisher manager does), service calls,
 * service servers, and the graph. Every endpoint belongs to one node of the
 * tools process (`/rosbridge_websocket` for the server), so the graph shows
 * who bridges what.
 *
 * @module bridges/rosbridge/bus_link
 */

import { normalizeTypeName } from '../../cdr.mjs';
import { graphModel, nodeName, subscriptionQos } from '../../page/graph.mjs';

/** A gid (4 words) as Runtime.graph() spells it. */
export function gidHex(words) {
  return Array.from(new Uint8Array(Int32Array.from(words).buffer), (b) => b.toString(16).padStart(2, '0')).join('');
}

/** The QoS of a publisher for a client's advertise (rosbridge: latch, queue_size). */
export function publisherQos({ latch = false, queueSize = 100, lifespanMs = 0 } = {}) {
  return {
    history: 'keep_last', depth: Math.max(1, queueSize | 0), reliability: 'reliable',
    durability: latch ? 'transient_local' : 'volatile', lifespanMs,
  };
}

/** One bus subscription fanned out to listeners: `listener(batch)` gets [{data, info}]. */
class Tap {
  constructor(link, topic, type) {
    this.link = link;
    this.topic = topic;
    this.type = type;
    this.listeners = new Set();
    this.subscription = null;
    this.ready = null;
  }

  start(options) {
    const qos = options.qos || subscriptionQos(this.link.publisherQosOf(this.topic));
    this.ready = this.link.tools.subscribe({
      topic: this.topic, type: this.type, qos, node: this.link.node, ignoreLocal: options.ignoreLocal,
    }, (batch) => {
      // what this link published was delivered already (deliverLocal)
      const own = this.link.ownPublishers;
      const pid = this.link.tools.pid;
      const heard = own.size ? batch.filter((m) => !(m.info.publisherGid[1] === pid && own.has(m.info.publisherGid[2] & 0xffffff))) : batch;
      if (heard.length) this.deliver(heard);
    }).then((s) => { this.subscription = s; return s; });
    return this.ready;
  }

  deliver(batch) {
    for (const l of this.listeners) l(batch);
  }
}

/**
 * The bus side of a bridge.
 */
export class BusLink {
  /**
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../tools_process/main_thread.mjs').Tools} options.tools
   * @param {string} [options.nodeName='rosbridge_websocket'] the tools node the endpoints belong to
   * @param {boolean} [options.ignoreLocal=false] taps do not hear this link's own publishers
   */
  static async create({ runtime, tools, nodeName: name = 'rosbridge_websocket', ignoreLocal = false }) {
    const node = await tools.createNode(name, { namespace: '/' });
    return new BusLink(runtime, tools, node, name, ignoreLocal);
  }

  constructor(runtime, tools, node, name, ignoreLocal) {
    this.runtime = runtime;
    this.tools = tools;
    this.node = node;
    this.nodeName = `/${name}`;
    this.ignoreLocal = ignoreLocal;
    this._taps = new Map();
    this._publishers = new Map();
    /** endpoint indexes of this link's publishers (their messages reach taps in-process) */
    this.ownPublishers = new Set();
    this._graph = null;
    runtime.onGraphChange(() => { this._graph = null; });
  }

  /** Can this runtime's tools serve services (older install-space runtimes cannot)? */
  get canServe() {
    return typeof this.tools.serve === 'function';
  }

  /** The raw graph snapshot (cached until the graph changes). */
  rawGraph() {
    if (!this._graph) this._graph = this.runtime.graph();
    return this._graph;
  }

  /** The ROS view of the graph, this bridge's endpoints included. */
  graph() {
    return graphModel(this.rawGraph());
  }

  /** The type of a topic in the graph, or null. */
  topicType(topic) {
    const t = this.rawGraph().topics.find((x) => x.name === topic);
    return t && t.types.length ? t.types[0] : null;
  }

  /** The QoS profiles of a topic's publishers (not this bridge's). */
  publisherQosOf(topic) {
    const t = this.rawGraph().topics.find((x) => x.name === topic);
    if (!t) return [];
    return t.publishers.filter((e) => e.pid !== this.tools.pid).map((e) => e.qos).filter(Boolean);
  }

  /** The lifespan (ms, 0: none) of the publisher with this gid on a topic. */
  lifespanOf(topic, gid) {
    const t = this.rawGraph().topics.find((x) => x.name === topic);
    if (!t) return 0;
    const hex = gidHex(gid);
    const e = t.publishers.find((p) => p.gid === hex);
    const ms = e && e.qos ? e.qos.lifespanMs : 0;
    return Number.isFinite(ms) && ms > 0 ? ms : 0;
  }

  /** Is there a server for this service? */
  hasServer(service) {
    const s = this.rawGraph().services.find((x) => x.name === service);
    return !!(s && s.servers.length);
  }

  /** The type of a service in the graph, or null. */
  serviceType(service) {
    const s = this.rawGraph().services.find((x) => x.name === service);
    return s && s.types.length ? s.types[0] : null;
  }

  /**
   * Listen to a topic; the bus subscription is shared.
   * @param {object} [qos] the subscription's QoS (default: as `ros2 topic echo` picks it)
   * @returns {Promise<function(): void>} stop listening
   */
  async listen(topic, type, listener, qos = undefined) {
    const full = normalizeTypeName(type);
    let tap = this._taps.get(topic);
    if (tap && tap.type !== full) {
      throw new Error(`topic '${topic}' is already bridged with type ${tap.type}, not ${full}`);
    }
    if (!tap) {
      tap = new Tap(this, topic, full);
      this._taps.set(topic, tap);
      tap.start({ ignoreLocal: this.ignoreLocal, qos }).catch(() => this._taps.delete(topic));
    }
    tap.listeners.add(listener);
    try {
      await tap.ready;
    } catch (e) {
      tap.listeners.delete(listener);
      throw e;
    }
    return () => {
      tap.listeners.delete(listener);
      if (tap.listeners.size === 0 && this._taps.get(topic) === tap) {
        this._taps.delete(topic);
        tap.ready.then((s) => s.close()).catch(() => {});
      }
    };
  }

  /**
   * A publisher shared by everyone who advertises this topic with this type and QoS.
   * @returns {Promise<{publish: function(Uint8Array): Promise<number>, release: function(): void, type: string}>}
   */
  async publisher(topic, type, qos = publisherQos()) {
    const full = normalizeTypeName(type);
    const key = JSON.stringify([topic, full, qos]);
    let entry = this._publishers.get(key);
    if (!entry) {
      entry = { refs: 0, handle: this.tools.advertise({ topic, type: full, qos, node: this.node }) };
      this._publishers.set(key, entry);
      entry.handle.catch(() => this._publishers.delete(key));
    }
    // counted before the wait: a release() meanwhile (the same client advertising the
    // topic again) must not close the handle this call is about to hand out
    entry.refs++;
    let handle;
    try {
      handle = await entry.handle;
    } catch (e) {
      entry.refs--;
      throw e;
    }
    if (!entry.batcher) entry.batcher = this._batcher(topic, handle);
    let released = false;
    return {
      type: full,
      publish: entry.batcher,
      release: () => {
        if (released) return;
        released = true;
        if (--entry.refs === 0 && this._publishers.get(key) === entry) {
          this._publishers.delete(key);
          this.ownPublishers.delete(handle.id);
          handle.close().catch(() => {});
        }
      },
    };
  }

  /**
   * publish(data) of a publisher: the messages of one turn of the event loop
   * go to the tools worker in one call, and this link's taps of the topic
   * (its WebSocket subscribers) get them at once, in this thread, instead of
   * after a round trip through the bus.
   */
  _batcher(topic, handle) {
    const many = typeof handle.publishMany === 'function';
    // a link that ignores its own publishers (the client) hears none of them, in-process either
    const local = many && !this.ignoreLocal;
    if (local) this.ownPublishers.add(handle.id);
    let pending = null;
    let serial = 0;
    const gid = [0, this.tools.pid, (1 << 24) | handle.id, 0];
    return (data) => {
      if (!many) return handle.publish(data);
      const tap = local && this._taps.get(topic);
      if (tap && tap.subscription) tap.deliver([{ data, info: { sourceTime: Date.now(), publisherGid: gid, publicationSequence: ++serial } }]);
      if (!pending) {
        pending = { list: [], promise: null };
        const batch = pending;
        batch.promise = new Promise((resolve, reject) => {
          queueMicrotask(() => {
            pending = null;
            handle.publishMany(batch.list).then(resolve, reject);
          });
        });
      }
      pending.list.push(data);
      return pending.promise;
    };
  }

  /** Call a service; resolves to the response bytes. */
  async call(service, type, request, timeoutMs) {
    const r = await this.tools.call({ service, type, node: this.node, timeoutMs }, request);
    return r.data;
  }

  /** Serve a service (tools.serve). */
  serve(service, type, onRequests, qos) {
    if (!this.canServe) {
      throw new Error('the wasm_js runtime of this install space cannot serve services from JavaScript '
        + "(it predates rosbridge): rebuild it with 'colcon build --wasm --packages-select wasm_js'");
    }
    return this.tools.serve({ service, type, node: this.node, qos }, onRequests);
  }

  /** The bus interface of page/ros_clients.mjs (ActionClient). */
  clientBus() {
    return {
      call: (service, type, bytes, timeoutMs) => this.call(service, type, bytes, timeoutMs),
      subscribe: (topic, type, onBatch) => {
        let stop = null;
        let closed = false;
        const ready = this.listen(topic, type, (batch) => onBatch(batch.map((m) => ({ bytes: m.data, time: m.info.sourceTime }))))
          .then((s) => { stop = s; if (closed) s(); });
        return { ready, close: () => { closed = true; if (stop) stop(); } };
      },
    };
  }
}

export { nodeName };
