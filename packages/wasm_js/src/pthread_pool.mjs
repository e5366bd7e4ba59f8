// Copyright 2026 The colcon-wasm authors. Licensed under the Apache License 2.0.

/**
 * Pre-started pthread workers for a warm host.
 *
 * An Emscripten pthread program does not run main() before its whole pool
 * (`-sPTHREAD_POOL_SIZE`, 4 by default) has booted a worker each, loaded the
 * glue into it and instantiated the module: ~150 ms on two cores, most of it
 * booting workers (a Node.js worker thread takes ~30 ms to boot). A warm host
 * boots these workers ahead, as stubs that have also imported the bus
 * client. While the glue loads, host_common.mjs hands Emscripten a stub for
 * each `new Worker(url)` it makes for its pool (withPthreadStubs); a stub
 * told `url` (Emscripten's worker script) loads it, and from then on it is
 * Emscripten's worker.
 *
 * Stub protocol (pthread_stub_node.mjs, pthread_stub_web.js): one message
 * each way at most, so that nothing of ours reaches Emscripten's handlers:
 *   host -> stub {colconWasmPreload: busModuleUrl, state: Int32Array, index}
 *     the stub imports the module, then stores 1 (ready) or 2 (failed) at
 *     state[index] (and, failed and not yet taken, posts {colconWasmError})
 *   host -> stub {colconWasmWorkerScript: url}
 *     the stub loads url (once); its onmessage takes over
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
    /** Why the last stub failed (for messages), or ''. */
    this.error = '';
    /** Stubs handed to Emscripten so far. */
    this.taken = 0;
    this._next = 0;
    this._state = null;
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

  _slot() {
    if (!this._state || this._next >= this._state.length) {
      this._state = new Int32Array(new SharedArrayBuffer(4 * 16));
      this._next = 0;
    }
    return [this._state, this._next++];
  }

  _drop(stub, why) {
    this.error = why;
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
      this.error = `cannot start a pthread worker: ${e && e.message ? e.message : e}`;
      return;
    }
    const [state, index] = this._slot();
    stub.state = state;
    stub.index = index;
    this._stubs.push(stub);
    // Until it is taken: its death, or its failure to import the bus module.
    stub.stop = stub.listen((m) => {
      if (m && m.colconWasmError !== undefined) {
        this._drop(stub, `a pthread worker failed before it was used (${busModuleUrl}): ${m.colconWasmError}`);
      }
    });
    stub.worker.postMessage({ colconWasmPreload: busModuleUrl, state, index });
    const w = Atomics.waitAsync(state, index, BOOTING);
    if (w.async) await w.value;
    if (Atomics.load(state, index) === READY && this._stubs.includes(stub) && stub.idle) stub.idle();
  }

  /**
   * Hand a stub (a ready one first) to Emscripten, told to load its worker script.
   * @param {string} url Emscripten's pthread worker script (URL or path)
   * @returns {object|null} the worker, or null when the pool is empty
   */
  take(url) {
    for (const s of [...this._stubs]) {
      if (Atomics.load(s.state, s.index) === FAILED) this._drop(s, 'a pthread worker could not import the bus module');
    }
    let i = this._stubs.findIndex((s) => Atomics.load(s.state, s.index) === READY);
    if (i < 0) i = this._stubs.length ? 0 : -1;
    if (i < 0) return null;
    const [stub] = this._stubs.splice(i, 1);
    stub.stop();
    if (stub.busy) stub.busy();
    stub.worker.postMessage({ colconWasmWorkerScript: url });
    this.taken++;
    return stub.worker;
  }
}
