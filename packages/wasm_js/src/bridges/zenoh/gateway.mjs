// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

/**
 * The Zenoh gateway: joins the local graph of a Runtime to a ROS 2 graph of
 * rmw_zenoh participants through a Zenoh router (docs/zenoh.md). It runs in
 * a worker of its own (gateway_worker.mjs), a bus process of the runtime
 * (Runtime.helperProcess) with the node `/zenoh_gateway`: zenoh-pico, its
 * socket and the bus are in that thread, so messages go between the bus
 * and the router without the main thread. This is its handle on the main
 * thread: its state, the remote graph (merged into the graph views) and
 * its counters, as the worker last told them.
 *
 * @module bridges/zenoh/gateway
 */

import { PROC_KIND_TOOLS } from '../../layout.mjs';
import { ProgramWorker } from '../../platform.mjs';
import { parseEndpoint } from './link.mjs';

export { GATEWAY_LIMITS, GATEWAY_NODE } from './core.mjs';

/** How long close() waits for the worker to close the session (its Close to the router). */
const CLOSE_WAIT_MS = 2000;

/**
 * A bus process id for the gateway's worker: Runtime.helperProcess, or, from
 * a runtime older than it (an install space's, built before), the same
 * with the runtime's own pid allocation and clean-up.
 */
async function helperProcess(runtime, name) {
  if (typeof runtime.helperProcess === 'function') return runtime.helperProcess(name);
  const pid = await runtime._allocPid(PROC_KIND_TOOLS);
  let released = null;
  return { pid, release: () => (released = released || runtime._reap(pid, null)) };
}

/**
 * The Zenoh gateway of a runtime.
 */
export class ZenohGateway {
  /**
   * Start the gateway; it connects in the background (see `state`).
   * @param {object} options
   * @param {import('../../runtime.mjs').Runtime} options.runtime
   * @param {import('../../cdr.mjs').TypeRegistry} options.registry the types this install knows
   * @param {string} options.endpoint `ws/HOST:PORT` or (Node.js) `tcp/HOST:PORT`
   * @param {string} options.module zenoh_session.mjs of the zenoh_wasm_gateway package: its
   *   URL (Node.js: also a path)
   * @param {number} [options.domain=0]
   * @param {object} [options.limits] GATEWAY_LIMITS' keys
   * @param {function(string, string): void} [options.log] (level, text)
   * @param {function(ZenohGateway): void} [options.onChange] state, remote graph or counters changed
   * @returns {Promise<ZenohGateway>}
   * @throws {Error} for an endpoint that is not ws/HOST:PORT or tcp/HOST:PORT
   */
  static async start(options) {
    parseEndpoint(options.endpoint);
    const runtime = options.runtime;
    const helper = await helperProcess(runtime, 'zenoh');
    let worker;
    try {
      worker = await ProgramWorker.start(new URL('./gateway_worker.mjs', import.meta.url).href,
        { name: 'zenoh gateway', type: 'module' });
    } catch (error) {
      await helper.release();
      throw new Error(`cannot start the Zenoh gateway's worker: ${error.message}`);
    }
    const gateway = new ZenohGateway(helper, worker, options);
    const registry = options.registry;
    worker.postMessage({
      type: 'start', bus: runtime.bus.handle, pid: helper.pid,
      options: {
        endpoint: options.endpoint, domain: options.domain || 0, limits: options.limits || {}, module: String(options.module),
        types: {
          messages: [...registry.messages.keys()], services: [...registry.services.keys()], actions: [...registry.actions.keys()],
        },
      },
    });
    if (runtime._atClose) runtime._atClose(() => gateway.close());
    return gateway;
  }

  constructor(helper, worker, { endpoint, log, onChange }) {
    this.helper = helper;
    this.worker = worker;
    this.endpoint = endpoint;
    this.displayUrl = `zenoh ${endpoint}`;
    this.log = log || (() => {});
    this.onChange = onChange || (() => {});
    this.state = 'connecting';
    this.remote = { nodes: [], topics: [], services: [] };
    this._status = {
      state: this.state, endpoint, zid: null, counters: {}, out: [], in: [], served: [], proxied: [],
    };
    this._closing = null;
    this._closedByWorker = null;
    worker.on('message', (m) => this._onMessage(m));
    worker.on('error', (e) => this._failed(`the Zenoh gateway's worker failed: ${e.message}`));
    worker.on('exit', ({ code }) => { if (!this._closing) this._failed(`the Zenoh gateway's worker exited (code ${code})`); });
  }

  /** The bus process id of the gateway (its node and endpoints). */
  get pid() {
    return this.helper.pid;
  }

  /** Is the gateway's session up? */
  get connected() {
    return this.state === 'connected';
  }

  /** The gateway's counters (sent, received, queued, lost, ...). */
  get counters() {
    return this._status.counters;
  }

  _onMessage(m) {
    if (!m) return;
    if (m.type === 'log') this.log(m.level, m.text);
    else if (m.type === 'state') {
      if (this._closing) return;
      this.state = m.state;
      this.remote = m.remote;
      this._status = m.status;
      this.onChange(this);
    } else if (m.type === 'closed' && this._closedByWorker) this._closedByWorker();
  }

  _failed(text) {
    if (this._closing || this.state === 'failed') return;
    this.log('error', text);
    this.state = 'failed';
    this.remote = { nodes: [], topics: [], services: [] };
    this._status = { ...this._status, state: 'failed', zid: null };
    this.helper.release();
    this.onChange(this);
  }

  /** What the gateway did, for `--zenoh` status lines and tests. */
  status() {
    return this._status;
  }

  /** Stop bridging: tokens are withdrawn with the session, the gateway's node leaves the graph. */
  close() {
    if (!this._closing) {
      this._closing = (async () => {
        if (this.state !== 'failed') {
          await new Promise((resolve) => {
            const timer = setTimeout(resolve, CLOSE_WAIT_MS);
            this._closedByWorker = () => { clearTimeout(timer); resolve(); };
            this.worker.postMessage({ type: 'close' });
          });
        }
        await this.worker.terminate();
        await this.helper.release();
        this.state = 'closed';
        this._status = { ...this._status, state: 'closed', zid: null };
        this.remote = { nodes: [], topics: [], services: [] };
        this.onChange(this);
      })();
    }
    return this._closing;
  }
}
