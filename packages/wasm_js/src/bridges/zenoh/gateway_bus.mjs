// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The bus side of the Zenoh gateway, in the gateway's worker
 * (gateway_worker.mjs): one JS-only bus process (Runtime.helperProcess)
 * with the node `/zenoh_gateway`, whose endpoints the bridges use
 * directly, without a round trip through another thread:
 * - subscriptions whose owner takes the messages itself when they come
 *   (TopicOut copies them straight into zenoh-pico's memory);
 * - publishers, service clients (calls) and servers;
 * - the graph, and a callback on its changes.
 * The worker sleeps on its process' doorbell with Atomics.waitAsync, as
 * the tools worker does (tools_process/worker.mjs): registered as a sleeper,
 * it reads the doorbell, drains, and waits while the doorbell keeps the
 * value read (the no-lost-wake-up protocol of bus_client.mjs).
 *
 * @module bridges/zenoh/gateway_bus
 */

import {
  BusClient, KIND_CLIENT, KIND_PUBLISHER, KIND_SERVICE, KIND_SUBSCRIPTION, TakeMode,
} from '../../bus_client.mjs';
import { graphOf } from '../../bus/graph.mjs';

/** How long a publish or a response may block on a full KEEP_ALL reader (as the tools worker's). */
const WRITE_TIMEOUT_MS = 10000;

/**
 * One bus process of the gateway, used by one thread (its worker).
 */
export class GatewayBus {
  /**
   * Attach to a runtime's bus and create the gateway's node.
   * @param {SharedArrayBuffer|WebAssembly.Memory} handle the bus (`runtime.bus.handle`)
   * @param {number} pid the process id the runtime gave (helperProcess)
   * @param {{name: string, domain: number}} node the gateway's node
   * @returns {GatewayBus}
   */
  static attach(handle, pid, { name, domain }) {
    const client = BusClient.attach(handle, pid);
    const node = client.createNode({ name, namespace: '/', domain, context: client.createContext() }).index;
    return new GatewayBus(client, node);
  }

  constructor(client, node) {
    this.client = client;
    this.pid = client.pid;
    this.node = node;
    /** subscription endpoint -> onData() (takes what is there) */
    this._readers = new Map();
    /** service endpoint -> onRequest({data, id}) */
    this._servers = new Map();
    /** client endpoint -> Map(sequence number -> pending call) */
    this._calls = new Map();
    /** service name and type -> client endpoint */
    this._clients = new Map();
    this._graph = null;
    this._closed = false;
    this._armed = false;
    this._arm();
  }

  /** The graph as Runtime.graph() gives it (cached per graph version). */
  rawGraph() {
    const version = this.client.graphVersion();
    if (!this._graph || this._graph.version !== version) this._graph = graphOf(this.client.graph());
    return this._graph;
  }

  /** Call `callback()` after each change of the graph (coalesced), until close(). */
  onGraphChange(callback) {
    let seen = this.client.graphVersion();
    const loop = () => {
      if (this._closed) return;
      const v = this.client.graphVersion();
      if (v !== seen) {
        seen = v;
        callback();
      }
      const r = this.client.bus.waitGraphAsync(v);
      if (r.async) r.value.then(loop);
      else Promise.resolve().then(loop);
    };
    loop();
  }

  _endpoint(kind, name, type, qos, ignoreLocal = false) {
    return this.client.createEndpoint({ kind, node: this.node, name, type, qos: qos || {}, ignoreLocal }).index;
  }

  /**
   * Subscribe; `onData()` is called when messages may be there and takes
   * them (client.takeBegin/takeCopy, or client.take). The gateway's own
   * publishers are not heard (ignore local).
   * @returns {{ep: number, close: function(): void}}
   */
  subscribe(topic, type, qos, onData) {
    const ep = this._endpoint(KIND_SUBSCRIPTION, topic, type, qos, true);
    this._readers.set(ep, onData);
    // a TRANSIENT_LOCAL writer's history is there at once
    queueMicrotask(() => this._drain());
    return { ep, close: this._closer(ep) };
  }

  /**
   * A publisher of the gateway's node.
   * @returns {{ep: number, publish: function(Uint8Array): number, close: function(): void}}
   */
  publisher(topic, type, qos) {
    const ep = this._endpoint(KIND_PUBLISHER, topic, type, qos);
    return {
      ep,
      publish: (data) => this.client.publish(ep, data, WRITE_TIMEOUT_MS),
      close: this._closer(ep),
    };
  }

  /**
   * Call a local service; resolves to the response's bytes.
   * @returns {Promise<Uint8Array>}
   * @throws {Error} (rejects) after `timeoutMs` without a response
   */
  call(service, type, request, timeoutMs) {
    const key = `${service}\u0000${type}`;
    let ep = this._clients.get(key);
    if (ep === undefined) {
      ep = this._endpoint(KIND_CLIENT, service, type, {});
      this._clients.set(key, ep);
      this._calls.set(ep, new Map());
    }
    const pending = this._calls.get(ep);
    return new Promise((resolve, reject) => {
      const seq = this.client.publish(ep, request, timeoutMs);
      const timer = setTimeout(() => {
        pending.delete(seq);
        reject(new Error(`service call to '${service}' timed out after ${timeoutMs} ms (server available: ${this.client.serverAvailable(ep)})`));
      }, timeoutMs);
      pending.set(seq, { resolve, timer });
      this._drain();
    });
  }

  /**
   * Serve a service: `onRequest({data, id})` for each request; answer with `respond(id, bytes)`.
   * @returns {{ep: number, respond: function(object, Uint8Array): boolean, close: function(): void}}
   */
  serve(service, type, onRequest) {
    const ep = this._endpoint(KIND_SERVICE, service, type, {});
    this._servers.set(ep, onRequest);
    queueMicrotask(() => this._drain());
    return {
      ep,
      respond: (id, data) => this.client.sendResponse(ep, id.gid, id.seqLo, id.seqHi, data, WRITE_TIMEOUT_MS),
      close: this._closer(ep),
    };
  }

  /** A closer of endpoint `ep` that removes it once. */
  _closer(ep) {
    let closed = false;
    return () => {
      if (closed || this._closed) return;
      closed = true;
      this._readers.delete(ep);
      this._servers.delete(ep);
      this.client.destroyEndpoint(ep);
    };
  }

  _drain() {
    if (this._closed) return;
    for (const onData of this._readers.values()) onData();
    for (const [ep, onRequest] of this._servers) {
      let data;
      while ((data = this.client.take(ep, TakeMode.REQUEST))) {
        const i = this.client.info;
        onRequest({ data, id: { gid: Int32Array.from(i.gid), seqLo: i.reqLo, seqHi: i.reqHi } });
      }
    }
    for (const [ep, pending] of this._calls) {
      let data;
      while (pending.size && (data = this.client.take(ep, TakeMode.RESPONSE))) {
        const seq = this.client.info.reqHi * 4294967296 + (this.client.info.reqLo >>> 0);
        const p = pending.get(seq);
        if (p) {
          pending.delete(seq);
          clearTimeout(p.timer);
          p.resolve(data);
        }
      }
    }
  }

  /** Sleep on the doorbell without blocking; drain on each wake-up. */
  _arm() {
    if (this._armed || this._closed) return;
    this._armed = true;
    const client = this.client;
    client.register();
    const bell = client.bell();
    try {
      this._drain();
    } catch (error) {
      if (this.onError) this.onError(error);
    }
    const r = Atomics.waitAsync(client.bus.i32, client.bellIndex, bell);
    const wake = () => {
      client.unregister();
      this._armed = false;
      this._arm();
    };
    if (r.async) r.value.then(wake);
    else Promise.resolve().then(wake);
  }

  /** Remove the gateway's node (and its endpoints) from the bus. */
  close() {
    if (this._closed) return;
    this._closed = true;
    for (const pending of this._calls.values()) for (const p of pending.values()) clearTimeout(p.timer);
    try {
      this.client.destroyNode(this.node);
    } catch {
      // the runtime removed the process already
    }
    this.client.ringSelf();
  }
}

export { TakeMode };
