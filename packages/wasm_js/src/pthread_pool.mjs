// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Pre-started pthread workers for a warm worker.
 *
 * Emscripten does not run a pthread program's main() before its whole pool
 * (`-sPTHREAD_POOL_SIZE`, 4 by default) has booted a worker each, loaded the
 * glue into it and instantiated the module: ~150 ms on two cores, most of it
 * booting workers (a Node.js worker thread takes ~30 ms to boot). A warm worker
 * boots these workers ahead, as stubs that have also imported the bus
 * client. While the glue loads, program_worker.mjs hands Emscripten a stub for
 * each `new Worker(url)` it makes for its pool (withPthreadStubs); a stub
 * told `url` (Emscripten's worker script) loads it, and from then on it is
 * Emscripten's worker.
 *
 * Stub protocol (pthread_stub_node.mjs, pthread_stub_web.js): one message
 * each way at most, so that nothing of ours reaches Emscripten's handlers:
 *   worker -> stub {colconWasmPreload: busModuleUrl, state: Int32Array(1)}
 *     the stub imports the module, then stores 1 (ready) or 2 (failed) in
 *     state[0] (and, failed and not yet taken, posts {colconWasmError})
 *   worker -> stub {colconWasmWorkerScript: url, scripts, exitRing}
 *     the stub loads url (once); its onmessage takes over, and its
 *     `cleanupThread` messages go to `exitRing` (pthread_exits.mjs). `scripts`
 *     (absolute URL -> text, browsers) are the worker script and the glue,
 *     prefetched by the Runtime: the stub's importScripts() runs those from
 *     memory (a stub under Node.js reads files and ignores them)
 * A stub is handed out booting or ready; its messages wait in its queue.
 *
 * @module pthread_pool
 */

/**
 * A platform's stub: the worker object Emscripten will use, and how to hear from it.
 * @typedef {object} PthreadStub
 * @property {object} worker a Web Worker, or a Node.js worker_threads Worker
 * @property {function(function(object): void): function(): void} listen
 *   call fn with each message, and with {colconWasmError} when the worker
 *   fails or exits; returns a function that stops listening
 * @property {function(): void} [idle] the stub is waiting in the pool (Node.js: unref)
 * @property {function(): void} [busy] the stub was taken (Node.js: ref)
 */

const BOOTING = 0;
const READY = 1;
const FAILED = 2;

export class PthreadPool {
  /**
   * @param {function(): PthreadStub} createStub start one stub worker
   */
  constructor(createStub) {
    this._create = createStub;
    /** Untaken stubs, oldest first. @type {PthreadStub[]} */
    this._stubs = [];
    /** Stubs handed to Emscripten so far. */
    this.taken = 0;
    /**
     * Workers of stubs that were ready when taken: booted, so they load and
     * run what they are sent with no help from the worker's event loop.
     * @type {WeakSet<object>}
     */
    this.readyWorkers = new WeakSet();
  }

  /** Number of untaken stubs (booting or ready). */
  get size() {
    return this._stubs.length;
  }

  /**
   * Boot `count` stubs; resolves when each is ready or has failed (a failed
   * stub is left out: Emscripten then starts its own worker).
   * @param {number} count
   * @param {string} busModuleUrl the bus client module the pthreads will import
   * @returns {Promise<void>}
   */
  async prestart(count, busModuleUrl) {
    const starts = [];
    for (let i = 0; i < count; i++) starts.push(this._prestartOne(busModuleUrl));
    await Promise.all(starts);
  }

  /** Stop a stub that failed before it was taken. */
  _drop(stub) {
    const i = this._stubs.indexOf(stub);
    if (i < 0) return;
    this._stubs.splice(i, 1);
    stub.stop();
    stub.worker.terminate();
  }

  async _prestartOne(busModuleUrl) {
    let stub;
    try {
      stub = this._create();
    } catch (e) {
      return; // Emscripten starts its own worker instead
    }
    // BOOTING, READY or FAILED, written by the stub
    stub.state = new Int32Array(new SharedArrayBuffer(4));
    this._stubs.push(stub);
    // Until it is taken: its death, or its failure to import the bus module.
    stub.stop = stub.listen((m) => {
      if (m && m.colconWasmError !== undefined) this._drop(stub);
    });
    stub.worker.postMessage({ colconWasmPreload: busModuleUrl, state: stub.state });
    const w = Atomics.waitAsync(stub.state, 0, BOOTING);
    if (w.async) await w.value;
    if (Atomics.load(stub.state, 0) === READY && this._stubs.includes(stub) && stub.idle) stub.idle();
  }

  /**
   * Hand a stub (a ready one first) to Emscripten, told to load its worker script.
   * @param {string} url Emscripten's pthread worker script (URL or path)
   * @param {Object<string, string>} [scripts] prefetched script texts (see the stub protocol)
   * @param {Int32Array} [exitRing] where its ended threads are written (pthread_exits.mjs)
   * @returns {object|null} the worker, or null when the pool is empty
   */
  take(url, scripts, exitRing) {
    for (const s of [...this._stubs]) {
      if (Atomics.load(s.state, 0) === FAILED) this._drop(s);
    }
    let i = this._stubs.findIndex((s) => Atomics.load(s.state, 0) === READY);
    if (i < 0) i = this._stubs.length ? 0 : -1;
    if (i < 0) return null;
    const [stub] = this._stubs.splice(i, 1);
    if (Atomics.load(stub.state, 0) === READY) this.readyWorkers.add(stub.worker);
    stub.stop();
    if (stub.busy) stub.busy();
    stub.worker.postMessage({ colconWasmWorkerScript: url, scripts: scripts || {}, exitRing });
    this.taken++;
    return stub.worker;
  }
}
