// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Tools: a JS-only bus process in its own worker, driven from the main
 * thread (the page's echo / publish / service-call tools, `--echo`).
 * Calls are proxied to the worker (comlink style); received messages come
 * back in batches, one postMessage per wake-up, with their buffers
 * transferred.
 *
 * @module tools_process/main_thread
 */

import { BusError } from '../bus.mjs';
import { ProgramWorker, siblingUrl } from '../platform.mjs';
import { FromTools, ToTools } from '../protocol.mjs';

function toError(e) {
  const err = new BusError(e.code || 1, e.message);
  if (e.name && e.name !== 'BusError') err.name = e.name;
  return err;
}

/**
 * Handle of a tools subscription.
 * @typedef {object} ToolsSubscription
 * @property {number} id
 * @property {function(): Promise<void>} close
 */

/**
 * The main-thread side of the tools worker.
 */
export class Tools {
  /**
   * @param {import('../runtime.mjs').Runtime} runtime
   * @param {number} pid the bus process id of the tools worker
   * @returns {Promise<Tools>}
   */
  static async start(runtime, pid) {
    const worker = await ProgramWorker.start(siblingUrl('tools_process/worker.mjs'), { name: 'wasm_js tools', type: 'module' });
    const tools = new Tools(runtime, pid, worker);
    await tools._call('init', [runtime.bus.handle, pid], ToTools.INIT);
    return tools;
  }

  constructor(runtime, pid, worker) {
    /** Bus process id of the tools worker. */
    this.pid = pid;
    this._runtime = runtime;
    this._worker = worker;
    this._next = 1;
    this._pending = new Map();
    this._subscribers = new Map();
    this._defaultNodes = new Map();
    this._closing = false;
    /** Resolves once the worker has ended and its process left the bus (close(), or a crash). */
    this.ended = null;
    worker.on('message', (m) => this._onMessage(m));
    worker.on('error', (e) => this._failAll(new BusError(1, `the tools worker failed: ${e.message}`)));
    // A worker that ended by itself (Node.js tells; a browser's worker ends only when
    // terminated): its process leaves the bus, and the runtime's next tools() starts anew.
    worker.on('exit', ({ code }) => {
      if (!this._closing) this._ended(`the tools worker exited (code ${code})`);
    });
  }

  _ended(why) {
    if (!this.ended) {
      this._failAll(new BusError(1, why));
      if (this._runtime._tools && this._runtime._toolsPid === this.pid) this._runtime._tools = null;
      this.ended = this._runtime._reap(this.pid, null);
    }
    return this.ended;
  }

  _onMessage(m) {
    if (m.type === FromTools.RETURN) {
      const p = this._pending.get(m.id);
      if (!p) return;
      this._pending.delete(m.id);
      if (m.ok) p.resolve(m.value);
      else p.reject(toError(m.error));
    } else if (m.type === FromTools.BATCH || m.type === FromTools.REQUESTS) {
      const batch = m.type === FromTools.BATCH;
      const cb = this._subscribers.get(batch ? m.subscription : m.service);
      if (cb) {
        try {
          cb(batch ? m.messages : m.requests);
        } catch (e) {
          console.error('tools subscription callback threw:', e);
        }
      }
    }
  }

  _failAll(err) {
    for (const p of this._pending.values()) p.reject(err);
    this._pending.clear();
  }

  _call(method, args, type = ToTools.CALL, transfer = []) {
    const id = this._next++;
    return new Promise((resolve, reject) => {
      this._pending.set(id, { resolve, reject });
      this._worker.postMessage({ type, id, method, args }, transfer);
    });
  }

  /**
   * Create a node of the tools process.
   * @param {string} name
   * @param {object} [options] {namespace='/', domain=0}
   * @returns {Promise<number>} node handle
   */
  createNode(name, options = {}) {
    return this._call('createNode', [{ name, namespace: options.namespace || '/', domain: options.domain || 0 }]);
  }

  async _node(spec) {
    if (spec.node !== undefined) return spec.node;
    const domain = spec.domain || 0;
    if (!this._defaultNodes.has(domain)) {
      this._defaultNodes.set(domain, this.createNode(`wasm_js_tools_${this.pid}`, { domain }));
    }
    return this._defaultNodes.get(domain);
  }

  /**
   * Subscribe to a topic; `onBatch(messages)` receives arrays of
   * {data: Uint8Array, info: {sourceTime, receivedTime, publicationSequence, publisherGid}}.
   * @param {object} spec {topic, type, qos, node?, domain?, ignoreLocal?: not the tools' own publishers}
   * @param {function(object[]): void} onBatch
   * @returns {Promise<ToolsSubscription>}
   */
  async subscribe(spec, onBatch) {
    const node = await this._node(spec);
    const id = await this._call('subscribe', [{ node, name: spec.topic, type: spec.type, qos: spec.qos, ignoreLocal: spec.ignoreLocal }]);
    this._subscribers.set(id, onBatch);
    return {
      id,
      close: async () => {
        this._subscribers.delete(id);
        await this._call('destroy', [id]);
      },
    };
  }

  /**
   * Create a publisher.
   * @param {object} spec {topic, type, qos, node?, domain?}
   * @returns {Promise<{id: number, publish: function(Uint8Array): Promise<number>,
   *   publishMany: function(Uint8Array[]): Promise<number>,
   *   waitForAllAcked: function(number): Promise<boolean>, close: function(): Promise<void>}>}
   */
  async advertise(spec) {
    const node = await this._node(spec);
    const id = await this._call('advertise', [{ node, name: spec.topic, type: spec.type, qos: spec.qos }]);
    return {
      id,
      publish: (data) => this._call('publish', [id, data]),
      /** Publish several messages in one call (one message to the worker); resolves to the last sequence number. */
      publishMany: (list) => this._call('publishMany', [id, list]),
      /**
       * Resolves (true) once every matched reliable subscription took every message, or
       * (false) after `timeoutMs`; the tools worker waits meanwhile: keep it short.
       */
      waitForAllAcked: (timeoutMs) => this._call('waitForAllAcked', [id, timeoutMs]),
      close: () => this._call('destroy', [id]),
    };
  }

  /**
   * Publish one message (creates a publisher the first time for this topic, type and QoS).
   * @param {object} spec {topic, type, qos, node?, domain?}
   * @param {Uint8Array} data
   * @returns {Promise<number>} sequence number
   */
  async publish(spec, data) {
    const node = await this._node(spec);
    return this._call('publishOnce', [{ node, name: spec.topic, type: spec.type, qos: spec.qos }, data]);
  }

  /**
   * Serve a service: `onRequests(requests)` receives arrays of
   * {data: Uint8Array, id, info}; answer each with `respond(id, bytes)`.
   * @param {object} spec {service, type, qos, node?, domain?}
   * @param {function(object[]): void} onRequests
   * @returns {Promise<{id: number, respond: function(object, Uint8Array): Promise<boolean>, close: function(): Promise<void>}>}
   */
  async serve(spec, onRequests) {
    const node = await this._node(spec);
    const id = await this._call('serve', [{ node, name: spec.service, type: spec.type, qos: spec.qos }]);
    this._subscribers.set(id, onRequests);
    return {
      id,
      respond: (requestId, data, timeoutMs = 10000) => this._call('respond', [id, requestId, data, timeoutMs]),
      close: async () => {
        this._subscribers.delete(id);
        await this._call('destroy', [id]);
      },
    };
  }

  /**
   * Call a service.
   * @param {object} spec {service, type, qos, node?, domain?, timeoutMs=10000}
   * @param {Uint8Array} request
   * @returns {Promise<{data: Uint8Array, info: object}>}
   */
  async call(spec, request) {
    const node = await this._node(spec);
    return this._call('call', [{ node, name: spec.service, type: spec.type, qos: spec.qos }, request,
      spec.timeoutMs === undefined ? 10000 : spec.timeoutMs]);
  }

  /** The runtime's graph snapshot. */
  graph() {
    return this._runtime.graph();
  }

  /**
   * Tests only: stop the tools worker at a fault point of its next bus
   * operations (bus/faults.mjs), to kill it there.
   * @param {{point: string, flag: SharedArrayBuffer, skip?: number}} spec
   */
  armFaultPoint(spec) {
    return this._call('armFaultPoint', [spec]);
  }

  /**
   * Terminate the tools worker as a crash would (tests): its process leaves
   * the bus, and the runtime's next tools() starts a new one.
   */
  async kill() {
    await this._worker.terminate();
    await this._ended('the tools worker was killed');
  }

  /** Stop the tools worker. */
  async close() {
    this._closing = true;
    this._failAll(new BusError(1, 'the tools worker was closed'));
    await this._worker.terminate();
    await this._ended('the tools worker was closed');
  }
}
